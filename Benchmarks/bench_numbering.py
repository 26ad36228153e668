"""The filter on meshes numbered the way scipy/Qhull numbers them, with the
automatic renumbering decision against renumbering always.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_numbering.py
        [--bench BIN] [--peer LIB] [--meshes DIR] [--sizes 2:1e5,2:1e6,3:1e4,3:1e5]
        [--scale 1] [--seeds 1,2] [--runs 3] [--markdown FILE]

Each pair is two random Delaunay meshes of the unit square (cube) made as a
new user would make them (benchpairs.qhull_mesh): a jittered grid of points
(grid order) given to scipy.spatial.Delaunay, the cells kept in Qhull's
order (a point's new cells together as Qhull inserts it, the points
inserted in no spatial order); the source has about 0.8 times the target's
cells, from another seed (--seeds T,S, default 1,2). --sizes gives the
target's cells per pair, --scale multiplies them (0.1 for a quick run).
Each pair is written to DIR (default build/bench-meshes/numbering) as .vtu
three times over:

* as numbered: Qhull's order;
* sorted: cells along a Z-order (Morton) curve by their lowest corner,
  points in the order the sorted cells first use them;
* shuffled: points and cells in random orders.

For each of them mesh-projection-bench --filter-only times the whole filter
on 1 and 2 threads (the best of --runs alternating runs), with the filter's
Renumbering automatic, always on and never on, and, in the first of these
runs, libsupermesh's intersections alone on the same meshes (--peer, or the `libsupermesh` package of a `python3` on PATH; the column is left
out without it). It prints one Markdown table and, per pair, the numbering
spread: the slowest of the three numberings over the fastest (automatic
renumbering, 1 and 2 threads).
"""
import argparse
import os
import sys

import benchpairs
import mpbench

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
NUMBERINGS = benchpairs.NUMBERINGS


def run(bench, target, source, renumber, peer, runs):
    """The filter on 1 and 2 threads (and the peer's intersections) in alternating runs."""
    return mpbench.bench_pair(bench, target, source,
                              ["--threads", "1,2", "--order", "asis", "--renumber", renumber], peer, runs)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bench", default=os.path.join(ROOT, "build", "bin", "mesh-projection-bench"))
    parser.add_argument("--peer", default=None, help="libsupermesh's shared library")
    parser.add_argument("--meshes", default=os.path.join(ROOT, "build", "bench-meshes", "numbering"))
    parser.add_argument("--sizes", default="2:1e5,2:1e6,3:1e4,3:1e5")
    parser.add_argument("--scale", type=float, default=1.0, help="multiplies every size (0.1: a quick run)")
    parser.add_argument("--runs", type=int, default=3, help="runs per measurement, the best kept")
    parser.add_argument("--seeds", default="1,2", help="the target's and the source's seeds")
    parser.add_argument("--markdown", default=None, help="also write the table to this file")
    args = parser.parse_args()
    args.seeds = tuple(int(x) for x in args.seeds.split(","))
    peer = args.peer or mpbench.find_peer()
    if not peer:
        print("libsupermesh not found: the table has no peer column (see --peer)", file=sys.stderr)
    os.makedirs(args.meshes, exist_ok=True)
    lines = ["| pair (Qhull, target / source cells) | numbering | renumbered (automatic) | "
             "automatic 1 / 2 threads (s) | always 1 / 2 threads (s) | never 1 / 2 threads (s) | "
             "automatic / always (1 thread) |" +
             (" libsupermesh (s) | filter / libsupermesh |" if peer else ""),
             "|---|---|---:|---:|---:|---:|---:|" + ("---:|---:|" if peer else "")]
    summary = []
    for item in args.sizes.split(","):
        dim, cells = item.split(":")
        dim, cells = int(dim), float(cells) * args.scale
        files = benchpairs.qhull_pair(args.meshes, dim, cells, args.seeds)
        times = {}
        for numbering in NUMBERINGS:
            target, source = files[numbering]
            auto = run(args.bench, target, source, "auto", peer, args.runs)
            always = run(args.bench, target, source, "always", None, args.runs)
            never = run(args.bench, target, source, "never", None, args.runs)
            times[numbering] = (auto["filter"], auto["filter2"])
            label = "%dD %s %d / %d" % (dim, "triangles" if dim == 2 else "tetrahedra", auto["cells"], auto["source"])
            row = "| %s | %s | %d of 2 | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | %.2f |" % (
                label, numbering, auto["renumbered"], auto["filter"], auto["filter2"],
                always["filter"], always["filter2"], never["filter"], never["filter2"],
                auto["filter"] / always["filter"])
            if peer:
                row += " %.3f | %.2f |" % (auto["peer"], auto["filter"] / auto["peer"]) if auto["peer"] else " - | - |"
            lines.append(row)
            print(row, flush=True)
        one = [t[0] for t in times.values()]
        two = [t[1] for t in times.values()]
        summary.append("%dD %g: numbering spread (slowest / fastest numbering, automatic) %.2f on 1 thread, "
                       "%.2f on 2" % (dim, cells, max(one) / min(one), max(two) / min(two)))
    mpbench.print_table(lines, summary, args.markdown)


if __name__ == "__main__":
    main()
