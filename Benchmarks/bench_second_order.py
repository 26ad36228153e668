"""What second-order cells cost: a pair of 6-node triangles / 10-node
tetrahedra against the linear projection on the same nodes' linear split.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_second_order.py [--cells 2e5,1e5]

(PYTHONPATH: the build's `meshprojection` and `mpsupport` packages; see README.md here.)

Each pair is the jittered square's triangles / the cube's tetrahedra of
mpbench (target about --cells cells, Source 0.8 times as many, shifted a
little) with a mid node added on every edge (straight second-order cells),
given two ways:
  * as second-order cells (VTK_QUADRATIC_TRIANGLE / _TETRA): the filter reads
    and projects a point field in the cells' own space;
  * as the same nodes' linear split (4 triangles / 8 tetrahedra per cell,
    the cells the filter cuts): the linear projection, P1 on the split.
and, in the same run, each pair shuffled (points and cells numbered at
random, as a reader without locality would give them). One smooth point
field; best of three runs on one thread, and on two. Columns: the filter's
total, its input, search (with assembly) and solve stages in seconds, and
the second-order total's ratio to the linear split's. Prints Markdown.
"""
import argparse
import sys

import numpy as np
from mpbench import best_run, cube_mesh, shifted_pair, shuffled, to_grid

# The simplices of each cell on its own nodes (VTK's node order).
TRIANGLE6_SPLIT = np.array([[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]])
# Corner tetrahedra, then the octahedron of the mid-edge nodes about its diagonal 5-7 (edges 1-2 and 0-3).
TETRA10_SPLIT = np.array([[0, 4, 6, 7], [4, 1, 5, 8], [6, 5, 2, 9], [7, 8, 9, 3],
                          [4, 5, 6, 7], [4, 5, 7, 8], [5, 6, 7, 9], [5, 7, 8, 9]])
EDGES = {3: [(0, 1), (1, 2), (2, 0)], 4: [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]}


def with_mid_nodes(points, cells):
    """The linear cells with a node at the middle of every edge, shared by
    the cells around it: (points, cells in VTK's second-order order)."""
    pairs = np.concatenate([cells[:, [a, b]] for a, b in EDGES[cells.shape[1]]])
    pairs.sort(axis=1)
    unique, inverse = np.unique(pairs, axis=0, return_inverse=True)
    mid = 0.5 * (points[unique[:, 0]] + points[unique[:, 1]])
    edge_nodes = (len(points) + inverse.reshape(len(EDGES[cells.shape[1]]), len(cells))).T
    return np.concatenate([points, mid]), np.concatenate([cells, edge_nodes], axis=1)


def linear_split(points, cells):
    """Every second-order cell as its simplices on its own nodes, each
    oriented as its cell."""
    pattern = TRIANGLE6_SPLIT if cells.shape[1] == 6 else TETRA10_SPLIT
    simplices = cells[:, pattern].reshape(-1, pattern.shape[1])
    d = pattern.shape[1] - 1
    edges = np.stack([points[simplices[:, k], :d] - points[simplices[:, 0], :d] for k in range(1, d + 1)], axis=1)
    parent = np.repeat(cells[:, :d + 1], len(pattern), axis=0)
    parent_edges = np.stack([points[parent[:, k], :d] - points[parent[:, 0], :d] for k in range(1, d + 1)], axis=1)
    flip = np.sign(np.linalg.det(edges)) != np.sign(np.linalg.det(parent_edges))
    simplices[flip, 0], simplices[flip, 1] = simplices[flip, 1], simplices[flip, 0].copy()
    return simplices


def field(x):
    return np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + x[:, 2] ** 2


def grids(mesh, seed=None):
    """(second-order grid, linear split grid) of a (points, cells, kind) mesh, shuffled with `seed`."""
    from vtkmodules.vtkCommonDataModel import VTK_QUADRATIC_TETRA, VTK_QUADRATIC_TRIANGLE, VTK_TETRA, VTK_TRIANGLE
    points, cells = with_mid_nodes(mesh[0], mesh[1])
    if seed is not None:
        points, cells, _ = shuffled((points, cells, None), seed)
    quadratic = VTK_QUADRATIC_TRIANGLE if cells.shape[1] == 6 else VTK_QUADRATIC_TETRA
    linear = VTK_TRIANGLE if cells.shape[1] == 6 else VTK_TETRA
    u = field(points)
    return to_grid(points, cells, quadratic, u), to_grid(points, linear_split(points, cells), linear, u)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cells", default="2e5,1e5", help="target cells: 2D,3D (default 2e5 triangles, 1e5 tetrahedra)")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    sizes = [int(float(s)) for s in args.cells.split(",")]
    print("| pair | numbering | cells (second order) | simplices (split) | threads | second order (s) | input | search | solve "
          "| linear split (s) | ratio |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for dim, cells in zip((2, 3), sizes):
        target, source = shifted_pair(dim, cells)
        for numbering, seed in (("as generated", None), ("shuffled", 7)):
            t2, t1 = grids(target, seed)
            s2, s1 = grids(source, None if seed is None else seed + 1)
            for threads in (1, 2):
                second = best_run(t2, s2, threads, args.runs)
                linear = best_run(t1, s1, threads, args.runs)
                print("| %s %dD | %s | %d | %d | %d | %.3f | %.3f | %.3f | %.3f | %.3f | %.2f |" % (
                    "tri6" if dim == 2 else "tet10", dim, numbering, t2.GetNumberOfCells(), t1.GetNumberOfCells(),
                    threads, second[0], second[1], second[3], second[4], linear[0], second[0] / linear[0]))
                sys.stdout.flush()


if __name__ == "__main__":
    main()
