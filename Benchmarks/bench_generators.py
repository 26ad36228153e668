"""The filter against libsupermesh on meshes as a real mesh generator numbers them.

    /usr/bin/python3 Benchmarks/bench_generators.py [--bench BIN] [--peer LIB]
        [--meshes DIR] [--sizes 2:1e5,2:1e6,3:1e4,3:1e5] [--runs 5] [--markdown FILE]

Gmsh (its Python API, `apt-get install python3-gmsh`) meshes two non-matching
pairs of domains, each pair with two of its algorithms so that nothing lines
up:

* 2D: the unit disk with an off-centre hole; target by Delaunay
  (Mesh.Algorithm 5), source by Frontal-Delaunay (6) at a 7% larger size;
* 3D: the unit ball; target by Delaunay (Mesh.Algorithm3D 1), source by
  HXT (10) at a 7% larger size.

The meshes keep Gmsh's numbering: cells in element-tag order, points in
node-tag order (compacted). They are written once to DIR (default
build/bench-meshes) as .vtu and reused.

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
import math
import os
import sys

import gmsh
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE, vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

import mpbench

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
HOLE = (0.2, 0.1, 0.3)  # 2D: centre and radius of the hole in the unit disk
GMSH_TYPE = {2: 2, 3: 4}  # Gmsh element type: 3-node triangle, 4-node tetrahedron


def mesh(dim, cells, algorithm, path):
    """Meshes the 2D or 3D domain with about `cells` cells, writes `path`."""
    try:
        gmsh.initialize(interruptible=False)  # Gmsh >= 4.9: leave SIGINT to Python
    except TypeError:
        gmsh.initialize()  # Debian 12's Gmsh 4.8
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.model.add("bench")
        occ = gmsh.model.occ
        if dim == 2:
            outer = occ.addDisk(0, 0, 0, 1, 1)
            hole = occ.addDisk(HOLE[0], HOLE[1], 0, HOLE[2], HOLE[2])
            occ.cut([(2, outer)], [(2, hole)])
            measure = math.pi * (1 - HOLE[2] ** 2)
            # Gmsh's Delaunay triangles average about 0.38 h^2 (measured).
            h = math.sqrt(measure / cells / 0.38)
            gmsh.option.setNumber("Mesh.Algorithm", algorithm)
        else:
            occ.addSphere(0, 0, 0, 1)
            measure = 4 * math.pi / 3
            # Gmsh's Delaunay tetrahedra average about h^3 / 4.8 (measured).
            h = (measure / cells * 4.8) ** (1 / 3)
            gmsh.option.setNumber("Mesh.Algorithm", 6)
            gmsh.option.setNumber("Mesh.Algorithm3D", algorithm)
        occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.model.mesh.generate(dim)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        etags, enodes = gmsh.model.mesh.getElementsByType(GMSH_TYPE[dim])
    finally:
        gmsh.finalize()
    corners = dim + 1
    enodes = np.asarray(enodes, dtype=np.int64).reshape(-1, corners)[np.argsort(etags)]
    tags = np.asarray(tags, dtype=np.int64)
    coords = np.asarray(coords).reshape(-1, 3)
    order = np.argsort(tags)
    tags, coords = tags[order], coords[order]
    used = np.isin(tags, enodes)  # drop nodes no cell uses (geometry vertices)
    tags, coords = tags[used], coords[used]
    ids = np.searchsorted(tags, enodes)  # node tag -> 0..n-1, in tag order
    grid = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(coords), deep=True))
    grid.SetPoints(points)
    offsets = numpy_to_vtkIdTypeArray(np.arange(0, corners * len(ids) + 1, corners, dtype=np.int64), deep=True)
    connectivity = numpy_to_vtkIdTypeArray(np.ascontiguousarray(ids.ravel()), deep=True)
    array = vtkCellArray()
    array.SetData(offsets, connectivity)
    grid.SetCells(VTK_TRIANGLE if dim == 2 else VTK_TETRA, array)
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(grid)
    writer.SetDataModeToBinary()  # inline binary: Debian's expat rejects appended data
    if not writer.Write():
        raise RuntimeError("cannot write " + path)
    return len(ids)


def pair(directory, dim, cells):
    """The target and source files of the pair of about `cells` cells."""
    algorithms = (5, 6) if dim == 2 else (1, 10)
    names = []
    for role, algorithm, scale in (("target", algorithms[0], 1.0), ("source", algorithms[1], 1 / 1.07 ** dim)):
        name = os.path.join(directory, "%dd_%s_%g.vtu" % (dim, role, cells))
        if not os.path.exists(name):
            made = mesh(dim, cells * scale, algorithm, name)
            print("  meshed %s: %d cells" % (os.path.basename(name), made), file=sys.stderr, flush=True)
        names.append(name)
    return names


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
        target, source = pair(args.meshes, dim, cells)
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
