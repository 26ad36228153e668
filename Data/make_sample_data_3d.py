#!/usr/bin/python3
# make_sample_data_3d.py -- writes the 3D sample pair used by MeshProjection.
#
# Output (default: next to this script):
#   lshape3d_source.vtu  ~8400 tetrahedra, point data Smooth, Linear, Velocity,
#                        cell data Region
#   lshape3d_target.vtu  ~2500 tetrahedra, point data TargetId
# Run with Debian's interpreter (vtkmodules from python3-paraview):
#   /usr/bin/python3 Data/make_sample_data_3d.py [--out-dir DIR] [--seed N]
"""Generate two non-matching tetrahedral meshes of one non-convex solid with a hole.

Solid (z in [0, 1]): the L-shaped prism ([0,3]x[0,3] minus [1.5,3]x[1.5,3])
with the square hole [0.5,1]x[0.5,1] through it; volume 9 - 2.25 - 0.25 = 6.5.

Meshing (deterministic): the solid is a union of cubes of edge h (h = 1/6 for
the source, 1/4 for the target: both grids fit the solid exactly), each cube
cut into the six Kuhn tetrahedra around its main diagonal (conforming). Points
whose eight surrounding cubes all belong to the solid (interior points) move
by U(-0.15h, 0.15h) per coordinate (numpy seed), so the meshes do not match
inside; points on the boundary stay, so both cover exactly the same solid.
Every tetrahedron is checked to keep a positive volume and the total volume
is checked to be 6.5.

Fields on the SOURCE (double point data):
    Smooth   = sin(3x) cos(2y) exp(z / 2)
    Linear   = 1 + 2x - 3y + 0.5z          (reproduced exactly by the projection)
    Velocity = (-(y - 1.5), x - 1.5, 0.3)   (a rigid rotation plus a drift)
Cell data on the SOURCE (int, by the tetrahedron's centroid): Region, a
material id: 3 above the slanted plane z = 0.62 - 0.08x, else 1 for
x > 1.55, 2 for y > 1.55, 0 elsewhere (boundaries that follow neither mesh).
TARGET: TargetId = point index (int64).
"""
import argparse
import itertools
import os
import sys

import numpy as np
from vtkmodules.util import numpy_support as ns
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, vtkCellArray, vtkUnstructuredGrid

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_sample_data import add_array, write  # noqa: E402

VOLUME = 6.5


def in_solid(cx, cy):
    """Whether the cube with centre (cx, cy, .) belongs to the solid."""
    l_shape = (0 < cx < 3) & (0 < cy < 3) & ~((cx > 1.5) & (cy > 1.5))
    hole = (0.5 < cx < 1.0) & (0.5 < cy < 1.0)
    return l_shape and not hole


def build(name, h, seed):
    n = [int(round(3 / h)), int(round(3 / h)), int(round(1 / h))]
    rng = np.random.default_rng(seed)
    keep = np.zeros(n, dtype=bool)
    for i, j, k in itertools.product(range(n[0]), range(n[1]), range(n[2])):
        keep[i, j, k] = in_solid((i + 0.5) * h, (j + 0.5) * h)
    index = -np.ones([m + 1 for m in n], dtype=np.int64)
    points = []

    def point(i, j, k):
        if index[i, j, k] < 0:
            x = np.array([i * h, j * h, k * h])
            around = [(i - a, j - b, k - c) for a in (0, 1) for b in (0, 1) for c in (0, 1)]
            interior = all(0 <= p < n[0] and 0 <= q < n[1] and 0 <= r < n[2] and keep[p, q, r]
                           for p, q, r in around)
            if interior:
                x = x + rng.uniform(-0.15 * h, 0.15 * h, 3)
            index[i, j, k] = len(points)
            points.append(x)
        return index[i, j, k]

    tets = []
    for i, j, k in itertools.product(range(n[0]), range(n[1]), range(n[2])):
        if not keep[i, j, k]:
            continue
        for perm in itertools.permutations(range(3)):
            c = [i, j, k]
            tet = [point(*c)]
            for axis in perm:
                c[axis] += 1
                tet.append(point(*c))
            tets.append(tet)
    pts = np.array(points)
    tets = np.array(tets, dtype=np.int64)
    e = pts[tets[:, 1:]] - pts[tets[:, :1]]
    six = np.einsum("ij,ij->i", e[:, 0], np.cross(e[:, 1], e[:, 2]))
    tets[six < 0] = tets[six < 0][:, [0, 2, 1, 3]]   # positive orientation
    volume = np.abs(six).sum() / 6
    print(f"{name}: {len(pts)} points, {len(tets)} tetrahedra, volume {volume:.15g}, "
          f"smallest {np.abs(six).min() / 6:.3g} (h={h:.4g}, seed={seed})")
    if np.abs(six).min() <= 0 or abs(volume - VOLUME) > 1e-12 * VOLUME:
        sys.exit(f"error: {name} failed verification")

    grid = vtkUnstructuredGrid()
    vtk_points = vtkPoints()
    vtk_points.SetDataTypeToDouble()
    vtk_points.SetData(ns.numpy_to_vtk(pts, deep=True))
    grid.SetPoints(vtk_points)
    cells = vtkCellArray()
    cells.SetData(ns.numpy_to_vtkIdTypeArray(np.arange(0, 4 * len(tets) + 1, 4, dtype=np.int64), deep=True),
                  ns.numpy_to_vtkIdTypeArray(tets.ravel(), deep=True))
    grid.SetCells(VTK_TETRA, cells)
    return pts, grid


def regions(pts, grid):
    """The material id of each tetrahedron of `grid` (points `pts`), by its centroid."""
    tets = ns.vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    c = pts[tets].mean(axis=1)
    region = np.where(c[:, 0] > 1.55, 1, np.where(c[:, 1] > 1.55, 2, 0))
    return np.where(c[:, 2] > 0.62 - 0.08 * c[:, 0], 3, region).astype(np.int32)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", default=os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("--seed", type=int, default=4321, help="source seed; target uses seed + 1")
    args = ap.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)

    pts, src = build("lshape3d_source", 1 / 6, args.seed)
    x, y, z = pts[:, 0], pts[:, 1], pts[:, 2]
    pd = src.GetPointData()
    add_array(pd, "Smooth", np.sin(3 * x) * np.cos(2 * y) * np.exp(z / 2))
    add_array(pd, "Linear", 1 + 2 * x - 3 * y + 0.5 * z)
    add_array(pd, "Velocity", np.column_stack([-(y - 1.5), x - 1.5, np.full_like(x, 0.3)]))
    add_array(src.GetCellData(), "Region", regions(pts, src))
    write(src, os.path.join(args.out_dir, "lshape3d_source.vtu"))

    pts, tgt = build("lshape3d_target", 1 / 4, args.seed + 1)
    add_array(tgt.GetPointData(), "TargetId", np.arange(len(pts), dtype=np.int64))
    write(tgt, os.path.join(args.out_dir, "lshape3d_target.vtu"))


if __name__ == "__main__":
    main()
