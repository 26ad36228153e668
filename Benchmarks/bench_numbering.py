"""The filter on meshes numbered the way scipy/Qhull numbers them, with the
automatic renumbering decision against renumbering always.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_numbering.py
        [--bench BIN] [--peer LIB] [--meshes DIR] [--sizes 2:1e5,2:1e6,3:1e4,3:1e5]
        [--scale 1] [--runs 3] [--markdown FILE]

Each pair is two random Delaunay meshes of the unit square (cube) made as a
new user would make them: a jittered grid of points (grid order) given to
scipy.spatial.Delaunay, the cells kept in Qhull's order (a point's new
cells together as Qhull inserts it, the points inserted in no spatial
order); the source has about 0.8 times the target's cells, from another
seed. --sizes gives the target's cells per pair, --scale multiplies them
(0.1 for a quick run). Each pair is written to DIR (default
build/bench-meshes/numbering) as .vtu three times over:

* as numbered: Qhull's order;
* sorted: cells along a Z-order (Morton) curve by their lowest corner,
  points in the order the sorted cells first use them;
* shuffled: points and cells in random orders.

For each of them mesh-projection-bench --filter-only times the whole filter
on 1 and 2 threads (the best of --runs alternating runs), with the filter's
Renumbering automatic, always on and never on (what automatic did before it
saw cell order, on Qhull's numbering), and, in the first of these runs, libsupermesh's intersections alone on the same meshes (--peer,
or the `libsupermesh` package of a `python3` on PATH; the column is left
out without it). It prints one Markdown table and, per pair, the numbering
spread: the slowest of the three numberings over the fastest (automatic
renumbering, 1 and 2 threads).
"""
import argparse
import os
import sys

import numpy as np
from scipy.spatial import Delaunay
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

import mpbench

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CELLS_PER_POINT = {2: 2.0, 3: 6.5}  # Delaunay cells per point of a jittered grid (measured)


def qhull_mesh(dim, cells, seed):
    """A Delaunay mesh of about `cells` cells of a jittered grid of the unit
    square (cube), in Qhull's order: (points, cells, type). Cells of (nearly)
    no measure on the hull, where jittered boundary points line up, are
    left out; the others keep their order."""
    rng = np.random.default_rng(seed)
    k = max(3, int(round((cells / CELLS_PER_POINT[dim]) ** (1.0 / dim))))
    axis = np.linspace(0.0, 1.0, k)
    grid = np.stack(np.meshgrid(*([axis] * dim), indexing="ij"), -1).reshape(-1, dim)[:, ::-1]
    grid = grid + rng.uniform(-0.3, 0.3, grid.shape) / k
    simplices = Delaunay(grid).simplices.astype(np.int64)
    corners = grid[simplices]
    edges = corners[:, 1:, :] - corners[:, :1, :]
    measure = np.abs(np.linalg.det(edges))
    simplices = simplices[measure > 1e-6 * np.mean(measure)]
    points = np.zeros((len(grid), 3))
    points[:, :dim] = grid
    kind = mpbench.square_mesh(2, 2, 0)[2] if dim == 2 else mpbench.cube_mesh(2, 2, 2, 0)[2]
    return points, simplices, kind


def morton_sorted(mesh):
    """The same mesh with cells along a Z-order curve (by their lowest
    corner's key, 2^10 steps per axis), points in the order the cells first
    use them."""
    points, cells, kind = mesh
    low, high = points.min(0), points.max(0)
    dim = int(np.count_nonzero(high > low))
    q = ((points[:, :dim] - low[:dim]) / (high[:dim] - low[:dim]) * 1023).astype(np.uint64)
    key = np.zeros(len(points), dtype=np.uint64)
    for bit in range(10):
        for a in range(dim):
            key |= ((q[:, a] >> np.uint64(bit)) & np.uint64(1)) << np.uint64(bit * dim + a)
    cells = cells[np.argsort(key[cells].min(1), kind="stable")]
    flat = cells.ravel()
    _, first = np.unique(flat, return_index=True)
    used = flat[np.sort(first)]
    order = np.concatenate([used, np.setdiff1d(np.arange(len(points)), used)])
    new_id = np.empty(len(points), dtype=np.int64)
    new_id[order] = np.arange(len(order))
    return points[order], new_id[cells], kind


def write(mesh, path):
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(mpbench.to_grid(*mesh))
    writer.SetDataModeToBinary()  # inline binary: Debian's expat rejects appended data
    if not writer.Write():
        raise RuntimeError("cannot write " + path)


NUMBERINGS = ("as numbered", "sorted", "shuffled")


def pair(directory, dim, cells):
    """{numbering: (target file, source file)} of the pair of about `cells` target cells."""
    files = {}
    made = {}
    for role, scale, seed in (("target", 1.0, 1), ("source", 0.8, 2)):
        for numbering in NUMBERINGS:
            name = os.path.join(directory, "%dd_%g_%s_%s.vtu" % (dim, cells, role, numbering.replace(" ", "_")))
            files.setdefault(numbering, []).append(name)
            if os.path.exists(name):
                continue
            if role not in made:
                made[role] = qhull_mesh(dim, cells * scale, seed)
            mesh = made[role]
            if numbering == "sorted":
                mesh = morton_sorted(mesh)
            elif numbering == "shuffled":
                mesh = mpbench.shuffled(mesh, seed + 10)
            write(mesh, name)
    return files


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
    parser.add_argument("--markdown", default=None, help="also write the table to this file")
    args = parser.parse_args()
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
        files = pair(args.meshes, dim, cells)
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
