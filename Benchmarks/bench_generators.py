"""The filter against libsupermesh on meshes as a real mesh generator numbers them.

    /usr/bin/python3 Benchmarks/bench_generators.py [--bench BIN] [--peer LIB]
        [--meshes DIR] [--sizes 2:1e5,2:1e6,3:1e4,3:1e5] [--seed 1] [--runs 5] [--markdown FILE]

Gmsh (its Python API, `apt-get install python3-gmsh`; benchpairs.gmsh_pair)
meshes two non-matching pairs of domains, each pair with two of its
algorithms so that nothing lines up:

* 2D: the unit disk with an off-centre hole; target by Delaunay
  (Mesh.Algorithm 5), source by Frontal-Delaunay (6) at a 7% larger size;
* 3D: the unit ball; target by Delaunay (Mesh.Algorithm3D 1), source by
  HXT (10) at a 7% larger size.

The meshes keep Gmsh's numbering: cells in element-tag order, points in
node-tag order (compacted); --seed is Gmsh's Mesh.RandomSeed. They are
written once to DIR (default build/bench-meshes) as .vtu and reused.

For every pair and every order (as Gmsh numbers them, sorted into bands,
cells and points shuffled: mesh-projection-bench --order) it runs
mesh-projection-bench --filter-only --threads 1,2 (the filter on 1 and 2
threads) and, in the same run, libsupermesh's intersections on the same
meshes (--peer; found with the `libsupermesh` Python package of a `python3`
on PATH when not given), each timed --runs times (default 5) with the best
kept, the filter's (on either number of threads) and the peer's alike,
their runs alternating (on a shared machine single runs vary widely and
busy spells outlast a run: the best of several alternating runs is what
repeats from one run of this script to the next),
and prints one Markdown table: the whole filter's seconds, its speed-up, the
peer's seconds and the ratio, the filter's peak memory beyond its inputs,
and per pair the worst order over the best.
"""
import argparse
import os
import sys

import benchpairs
import mpbench

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def run(bench, target, source, order, threads, peer, runs):
    """`threads` "1,2": one and two threads in alternating runs (and the peer's)."""
    return mpbench.bench_pair(bench, target, source, ["--threads", str(threads), "--order", order], peer, runs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bench", default=os.path.join(ROOT, "build", "bin", "mesh-projection-bench"))
    parser.add_argument("--peer", default=None, help="libsupermesh's shared library")
    parser.add_argument("--meshes", default=os.path.join(ROOT, "build", "bench-meshes"))
    parser.add_argument("--sizes", default="2:1e5,2:1e6,3:1e4,3:1e5")
    parser.add_argument("--runs", type=int, default=5, help="runs per measurement, the best kept")
    parser.add_argument("--seed", type=int, default=1, help="Gmsh's Mesh.RandomSeed")
    parser.add_argument("--markdown", default=None, help="also write the table to this file")
    args = parser.parse_args()
    peer = args.peer or mpbench.find_peer()
    if not peer:
        print("libsupermesh not found: the table has no peer column (see --peer)", file=sys.stderr)
    os.makedirs(args.meshes, exist_ok=True)
    lines = ["| mesh pair (Gmsh) | order | filter 1 thread (s) | 2 threads (s) | speed-up | "
             "libsupermesh (s) | filter / libsupermesh | memory / inputs |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    summary = []
    for item in args.sizes.split(","):
        dim, cells = item.split(":")
        dim, cells = int(dim), float(cells)
        target, source = benchpairs.gmsh_pair(args.meshes, dim, cells, args.seed)
        times = {}
        for order in ("asis", "sorted", "shuffled"):
            # One and two threads and the peer in alternating runs of one process.
            one = run(args.bench, target, source, order, "1,2", peer, args.runs)
            two = {"filter": one["filter2"]}
            times[order] = one["filter"]
            label = "%dD %s %d / %d" % (dim, "triangles" if dim == 2 else "tetrahedra", one["cells"], one["source"])
            name = {"asis": "as Gmsh numbers them", "sorted": "sorted into bands", "shuffled": "shuffled"}[order]
            if one["renumbered"]:
                name += " (renumbered: %.3f s)" % one["renumber"]
            peer_cells = ("%.3f" % one["peer"], "%.2f" % (one["filter"] / one["peer"])) if one["peer"] else ("-", "-")
            lines.append("| %s | %s | %.3f | %.3f | %.2f | %s | %s | %.2f |" % (
                label, name, one["filter"], two["filter"], one["filter"] / two["filter"],
                peer_cells[0], peer_cells[1], one["memory"]))
            print(lines[-1], flush=True)
        summary.append("%dD %g: worst order / best order %.2f" % (dim, cells, max(times.values()) / min(times.values())))
    mpbench.print_table(lines, summary, args.markdown)


if __name__ == "__main__":
    main()
