#!/usr/bin/python3
# make_sample_data.py -- writes the sample mesh pair used by MeshProjection.
#
# Output (default: next to this script):
#   lshape_source.vtu  ~3500 triangles, point data Smooth, Linear, Velocity,
#                      cell data Region
#   lshape_target.vtu  ~2350 triangles, point data TargetId
# Both meshes triangulate exactly the same polygon (L-shape with a square
# hole) but are non-matching, in the interior and on the boundary.
# Run with Debian's interpreter (it has vtkmodules from python3-paraview):
#   /usr/bin/python3 Data/make_sample_data.py [--out-dir DIR] [--h-source H]
#                                             [--h-target H] [--seed N]
"""Generate two non-matching triangle meshes of one L-shaped domain with a hole.

Domain (all edges straight, z = 0):
    Omega = ([0,2]x[0,2] minus [1,2]x[1,2]) minus [0.35,0.65]x[0.35,0.65]
    area(Omega) = 4 - 1 - 0.09 = 2.91

Meshing (deterministic for fixed arguments):
  * boundary points: every polygon edge of length L is cut into ceil(L/h)
    equal parts, polygon corners included; since all edges are axis-parallel,
    the points lie exactly on the boundary lines;
  * interior points: a grid of spacing h jittered by U(-0.3h, 0.3h) with a
    fixed numpy seed, keeping only points inside Omega at distance >= 0.6h
    from every boundary edge;
  * scipy.spatial.Delaunay of all points; triangles whose centroid is outside
    Omega are dropped (the boundary edges are Gabriel edges, so they are part
    of the triangulation and every triangle is wholly inside or outside);
  * triangles are oriented counterclockwise, unused points are dropped.
The source uses h_source and seed, the target h_target and seed + 1.

Fields on the SOURCE mesh (double point data unless noted):
    Smooth   = sin(3x) * cos(2y) + 0.5 x
    Linear   = 1 + 2x - 3y                (a P1 projection must reproduce it)
    Velocity = (-(y - 1), x - 1, 0)       (rigid rotation about (1, 1))
    Region   (int cell data, by centroid) = 0 in [0,1]x[0,1], 1 for x > 1,
                                            2 for y > 1
Fields on the TARGET mesh:
    TargetId = point index (int64), to show that the Input's arrays are kept.

Each mesh is verified before writing (exit status 1 on failure): positive
areas and minimum angle > 10 degrees, total area = 2.91 to relative 1e-12,
every edge used by at most two triangles, all boundary edges on the domain
boundary, and a single edge-connected component.
"""
import argparse
import math
import os
import sys

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import Delaunay
from vtkmodules.util import numpy_support as ns
from vtkmodules.util.vtkConstants import VTK_TRIANGLE
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

OUTER = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]   # counterclockwise
HOLE = [(0.35, 0.35), (0.35, 0.65), (0.65, 0.65), (0.65, 0.35)]  # clockwise
EXACT_AREA = 2.91
MIN_ANGLE_DEG = 10.0


def loops_to_segments(*loops):
    """Closed polygon loops -> list of segments ((x0, y0), (x1, y1))."""
    return [(p[i], p[(i + 1) % len(p)]) for p in loops for i in range(len(p))]


SEGMENTS = loops_to_segments(OUTER, HOLE)


def inside(x, y):
    """True where (x, y) lies strictly inside Omega (vectorized)."""
    in_l = (x > 0) & (x < 2) & (y > 0) & (y < 2) & ~((x >= 1) & (y >= 1))
    in_hole = (x >= 0.35) & (x <= 0.65) & (y >= 0.35) & (y <= 0.65)
    return in_l & ~in_hole


def on_segment(p, q, seg):
    """True where both p and q lie exactly on the axis-parallel segment seg."""
    (x0, y0), (x1, y1) = seg
    ok = np.ones(len(p), bool)
    for r in (p, q):
        if x0 == x1:   # vertical segment: x exact, y within range
            ok &= (r[:, 0] == x0) & (r[:, 1] >= min(y0, y1)) & (r[:, 1] <= max(y0, y1))
        else:          # horizontal segment
            ok &= (r[:, 1] == y0) & (r[:, 0] >= min(x0, x1)) & (r[:, 0] <= max(x0, x1))
    return ok


def make_points(h, seed):
    """Boundary points (exactly on the edges) plus jittered interior points."""
    pts = []
    for (x0, y0), (x1, y1) in SEGMENTS:
        n = math.ceil(math.hypot(x1 - x0, y1 - y0) / h - 1e-9)
        t = np.arange(n) / n          # start corner included, end excluded
        # axis-parallel edges: the constant coordinate is copied, not computed
        xs = np.full(n, float(x0)) if x0 == x1 else x0 + t * (x1 - x0)
        ys = np.full(n, float(y0)) if y0 == y1 else y0 + t * (y1 - y0)
        pts.append(np.column_stack([xs, ys]))
    rng = np.random.default_rng(seed)
    g = np.arange(0.0, 2.0 + h, h)
    gx, gy = np.meshgrid(g, g)
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    grid += rng.uniform(-0.3 * h, 0.3 * h, grid.shape)
    keep = inside(grid[:, 0], grid[:, 1])
    for (x0, y0), (x1, y1) in SEGMENTS:  # distance to each boundary segment
        a, d = np.array([x0, y0], float), np.array([x1 - x0, y1 - y0], float)
        t = np.clip((grid - a) @ d / (d @ d), 0.0, 1.0)
        keep &= np.linalg.norm(grid - a - t[:, None] * d, axis=1) >= 0.6 * h
    pts.append(grid[keep])
    return np.vstack(pts)


def triangulate(h, seed):
    """Return (points Nx2, triangles Mx3) of a CCW triangulation of Omega."""
    pts = make_points(h, seed)
    tri = Delaunay(pts).simplices
    c = pts[tri].mean(axis=1)
    tri = tri[inside(c[:, 0], c[:, 1])]
    a, b, cc = (pts[tri[:, k]] for k in range(3))
    cross = (b - a)[:, 0] * (cc - a)[:, 1] - (b - a)[:, 1] * (cc - a)[:, 0]
    tri[cross < 0] = tri[cross < 0][:, [0, 2, 1]]          # make all CCW
    used, tri = np.unique(tri, return_inverse=True)         # drop unused points
    return pts[used], tri.reshape(-1, 3)


def verify(pts, tri):
    """Check the mesh; return (area, min angle in degrees, list of errors)."""
    errors = []
    a, b, c = (pts[tri[:, k]] for k in range(3))
    cross = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    if np.any(cross <= 0):
        errors.append(f"{np.sum(cross <= 0)} triangles with area <= 0")
    area = math.fsum(0.5 * cross)
    if abs(area - EXACT_AREA) > 1e-12 * EXACT_AREA:
        errors.append(f"total area {area!r} != {EXACT_AREA}")
    angles = []
    for p, q, r in ((a, b, c), (b, c, a), (c, a, b)):   # angle at vertex p
        u, v = q - p, r - p
        cosang = np.sum(u * v, 1) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1)
        angles.append(np.degrees(np.arccos(np.clip(cosang, -1, 1))))
    min_angle = float(np.min(angles))
    if min_angle <= MIN_ANGLE_DEG:
        errors.append(f"minimum angle {min_angle:.2f} <= {MIN_ANGLE_DEG}")
    # edges: (sorted vertex pair) for each of the 3 edges of each triangle
    edges = np.sort(np.vstack([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    owner = np.tile(np.arange(len(tri)), 3)
    uniq, inv, count = np.unique(edges, axis=0, return_inverse=True, return_counts=True)
    inv = inv.ravel()
    if np.any(count > 2):
        errors.append(f"{np.sum(count > 2)} edges shared by more than 2 triangles")
    bnd = uniq[count == 1]
    p, q = pts[bnd[:, 0]], pts[bnd[:, 1]]
    on_bnd = np.zeros(len(bnd), bool)
    for seg in SEGMENTS:
        on_bnd |= on_segment(p, q, seg)
    if not np.all(on_bnd):
        errors.append(f"{np.sum(~on_bnd)} boundary edges not on the domain boundary")
    # triangle adjacency through interior edges -> connected components
    order = np.argsort(inv, kind="stable")
    pairs = owner[order].reshape(-1)
    starts = np.concatenate([[0], np.cumsum(count)[:-1]])
    inner = starts[count == 2]
    adj = coo_matrix((np.ones(len(inner)), (pairs[inner], pairs[inner + 1])),
                     shape=(len(tri), len(tri)))
    ncomp = connected_components(adj, directed=False)[0]
    if ncomp != 1:
        errors.append(f"{ncomp} edge-connected components")
    return area, min_angle, errors


def to_grid(pts, tri):
    """Build a vtkUnstructuredGrid of VTK_TRIANGLE cells, z = 0, double points."""
    xyz = np.column_stack([pts, np.zeros(len(pts))])
    points = vtkPoints()
    points.SetDataTypeToDouble()
    points.SetData(ns.numpy_to_vtk(xyz, deep=True))
    cells = vtkCellArray()
    offsets = ns.numpy_to_vtkIdTypeArray(np.arange(0, 3 * len(tri) + 1, 3, dtype=np.int64), deep=True)
    conn = ns.numpy_to_vtkIdTypeArray(tri.astype(np.int64).ravel(), deep=True)
    cells.SetData(offsets, conn)
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    grid.SetCells(VTK_TRIANGLE, cells)
    return grid


def add_array(data, name, values):
    arr = ns.numpy_to_vtk(np.ascontiguousarray(values), deep=True)
    arr.SetName(name)
    data.AddArray(arr)


def write(grid, path):
    w = vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(grid)
    # Inline base64 ("binary" mode), not an appended block: VTK 9.2 cannot read
    # appended data back with Debian 12's patched expat (2.5.0-1+deb12u5 defers
    # reparsing, which breaks how vtkXMLDataParser finds the appended block).
    w.SetDataModeToBinary()
    w.SetCompressorTypeToZLib()
    w.SetHeaderTypeToUInt64()
    if not w.Write():
        sys.exit(f"error: could not write {path}")


def build(name, h, seed):
    pts, tri = triangulate(h, seed)
    area, min_angle, errors = verify(pts, tri)
    print(f"{name}: {len(pts)} points, {len(tri)} triangles, area {area:.15g}, "
          f"min angle {min_angle:.2f} deg (h={h}, seed={seed})")
    if errors:
        sys.exit(f"error: {name} failed verification: " + "; ".join(errors))
    return pts, tri, to_grid(pts, tri)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", default=os.path.dirname(os.path.abspath(__file__)))
    # defaults cut the edges of length 2 / 1 / 0.3 into 50/25/8 (source) and
    # 41/21/7 (target) parts: coprime counts, so only polygon corners coincide
    ap.add_argument("--h-source", type=float, default=0.04)
    ap.add_argument("--h-target", type=float, default=0.0495)
    ap.add_argument("--seed", type=int, default=1234, help="source seed; target uses seed + 1")
    args = ap.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)

    pts, tri, src = build("lshape_source", args.h_source, args.seed)
    x, y = pts[:, 0], pts[:, 1]
    pd = src.GetPointData()
    add_array(pd, "Smooth", np.sin(3 * x) * np.cos(2 * y) + 0.5 * x)
    add_array(pd, "Linear", 1 + 2 * x - 3 * y)
    add_array(pd, "Velocity", np.column_stack([-(y - 1), x - 1, np.zeros_like(x)]))
    c = pts[tri].mean(axis=1)
    region = np.where(c[:, 0] > 1, 1, np.where(c[:, 1] > 1, 2, 0)).astype(np.int32)
    add_array(src.GetCellData(), "Region", region)
    write(src, os.path.join(args.out_dir, "lshape_source.vtu"))

    pts, tri, tgt = build("lshape_target", args.h_target, args.seed + 1)
    add_array(tgt.GetPointData(), "TargetId", np.arange(len(pts), dtype=np.int64))
    write(tgt, os.path.join(args.out_dir, "lshape_target.vtu"))


if __name__ == "__main__":
    main()
