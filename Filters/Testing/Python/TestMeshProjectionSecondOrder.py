"""Second-order cells (VTK's quadratic cells, Lagrange cells of order 2),
split into simplices on their own nodes (point data in the cells' own space:
TestMeshProjectionSecondOrderSpace.py), on Gmsh order-2 meshes
(mpsupport.gmshmeshes.second_order: gmsh.model.mesh.setOrder(2)) of a
square, a disk (mid nodes on the circle: curved cells) and a cube, and on
meshes made here:

    a. a linear field given at every Source node is exact at every Input
       node (1e-9 of its range), on straight and curved pairs of every
       type, also pairs that overlap in part, surfaces in 3D and curves;
    b. the Source field keeps its integral on an Input that covers it
       (1e-11 relative): against the filter's SourceIntegral_ everywhere,
       and against the 6-node triangles' own integral (a third of the area
       times the mid nodes' values) summed here;
    c. constant cell data stays constant on every covered Input cell;
    d. Lagrange cells of order 2 give the quadratic cells' results bit for
       bit, on both ports;
    e. mixed linear and quadratic meshes and composite data;
    f. the kept operator is rebuilt when only a mid node moves or is
       renumbered, and reused when nothing changed;
    g. refusals by name: Lagrange cells of order 3, Bezier cells, other
       nonlinear types, a folded curved cell (the output is Input unchanged).
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import (VTK_BEZIER_TRIANGLE, VTK_LAGRANGE_CURVE,
                                           VTK_LAGRANGE_HEXAHEDRON, VTK_LAGRANGE_QUADRILATERAL,
                                           VTK_LAGRANGE_TETRAHEDRON, VTK_LAGRANGE_TRIANGLE,
                                           VTK_LAGRANGE_WEDGE, VTK_QUADRATIC_EDGE,
                                           VTK_QUADRATIC_LINEAR_QUAD, VTK_QUADRATIC_TETRA, VTK_TETRA,
                                           vtkMultiBlockDataSet, vtkUnstructuredGrid)

import meshprojection
from mpsupport import gmshmeshes, secondorder
from mpsupport.secondorder import copy_grid, linear, point_array, points_of
from mpsupport.testing import check, finish, observed_filter


def smooth(x):
    return np.sin(3.0 * x[:, 0]) + x[:, 1] ** 2 + np.cos(2.0 * x[:, 2])


def with_arrays(g):
    """g with point arrays Linear and Smooth and the cell array Constant."""
    return secondorder.with_fields(g, (("Linear", linear), ("Smooth", smooth)))


def project(target, source, **properties):
    return secondorder.project(target, source, CacheOperator=False, **properties)


def field(out, name):
    return out.GetFieldData().GetArray(name).GetValue(0)


def check_linear(name, target, source):
    """a and c on one pair: the linear field at every node, the constant on covered cells."""
    out = project(target, source)
    x = points_of(out)
    valid = point_array(out, "vtkValidPointMask").astype(bool)
    error = np.max(np.abs(point_array(out, "Linear") - linear(x))[valid]) / np.ptp(linear(x))
    print("%s: linear field off by %.2g of its range at %d of %d nodes" % (name, error, valid.sum(), len(valid)))
    check(valid.any() and error <= 1e-9, "%s: linear field exact at every node (%.2g of its range)" % (name, error))
    covered = vtk_to_numpy(out.GetCellData().GetArray("CoveredFraction")) > 1e-9
    constant = vtk_to_numpy(out.GetCellData().GetArray("Constant"))[covered]
    check(covered.any() and np.max(np.abs(constant - 7.0)) <= 1e-12,
          "%s: constant cell data stays 7 (%.3g off)" % (name, np.max(np.abs(constant - 7.0))))
    return out


def shifted(g, d):
    return copy_grid(g, lambda x: x + np.asarray(d))


square = {kind: gmshmeshes.second_order("square", h, quads, incomplete)
          for kind, h, quads, incomplete in (("tri6", 0.23, False, False), ("quad8", 0.27, True, True),
                                              ("quad9", 0.31, True, False))}
disk = {kind: gmshmeshes.second_order("disk", h, quads, False)
        for kind, h, quads in (("tri6", 0.29, False), ("quad9", 0.23, True))}
cube = {kind: gmshmeshes.second_order(shape, h, False, incomplete)
        for kind, shape, h, incomplete in (("tet10", "cube", 0.35, False), ("hex20", "hexes", 0.34, True),
                                           ("hex27", "hexes", 0.5, False), ("wedge15", "prisms", 0.34, True))}

# a, c: linear fields and constants, straight and curved, whole and in part.
for s in square:
    for t in square:
        check_linear("square %s -> %s" % (s, t), square[t], with_arrays(square[s]))
    check_linear("square %s -> tri6, in part" % s, shifted(square["tri6"], (0.37, 0.21, 0.0)),
                 with_arrays(square[s]))
for s in disk:
    for t in disk:
        check_linear("disk %s -> %s (curved)" % (s, t), disk[t], with_arrays(disk[s]))
    check_linear("disk %s -> quad9, in part (curved)" % s, shifted(disk["quad9"], (0.6, -0.3, 0.0)),
                 with_arrays(disk[s]))
for s in cube:
    for t in cube:
        if s != t:
            check_linear("cube %s -> %s" % (s, t), cube[t], with_arrays(cube[s]))
    check_linear("cube %s -> tet10, in part" % s, shifted(cube["tet10"], (0.41, 0.27, -0.33)),
                 with_arrays(cube[s]))


# Surfaces in 3D: the square's shells tilted out of every coordinate plane.
def tilt(x):
    c, s = np.cos(0.5), np.sin(0.5)
    y = x.copy()
    y[:, 1], y[:, 2] = c * x[:, 1] - s * x[:, 2], s * x[:, 1] + c * x[:, 2]
    y[:, 0], y[:, 2] = c * y[:, 0] + s * y[:, 2], -s * y[:, 0] + c * y[:, 2]
    return y


for s, t in (("tri6", "quad9"), ("quad8", "tri6"), ("quad9", "quad8")):
    check_linear("tilted shell %s -> %s" % (s, t), copy_grid(square[t], tilt),
                 with_arrays(copy_grid(square[s], tilt)))


# A bent shell (a quarter of a cylinder, nodes on it): constants exact.
def bend(x):
    return np.stack([np.sin(1.5 * x[:, 0]), x[:, 1], 1.0 - np.cos(1.5 * x[:, 0])], 1)


out = project(copy_grid(square["tri6"], bend), with_arrays(copy_grid(square["quad9"], bend)))
covered = vtk_to_numpy(out.GetCellData().GetArray("CoveredFraction")) > 1e-9
check(covered.sum() > 0.9 * len(covered) and
      np.max(np.abs(vtk_to_numpy(out.GetCellData().GetArray("Constant"))[covered] - 7.0)) <= 1e-12,
      "bent shell quad9 -> tri6: constant cell data stays 7")


# Curves: straight chains of 3-node edges in 3D, nodes jittered along them.
def chain(n, t0, t1, seed, cell_type=VTK_QUADRATIC_EDGE):
    t = np.linspace(t0, t1, 2 * n + 1)
    t[1:-1] += np.random.default_rng(seed).uniform(-0.2, 0.2, 2 * n - 1) * (t1 - t0) / (2 * n)
    x = np.stack([0.2 + 0.6 * t, 0.1 + 0.3 * t, 0.4 - 0.5 * t], 1)
    g = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x), deep=True))
    g.SetPoints(points)
    for k in range(n):
        g.InsertNextCell(cell_type, 3, [2 * k, 2 * k + 2, 2 * k + 1])
    return g


check_linear("curves edge3 -> edge3", chain(13, 0.0, 1.0, 1), with_arrays(chain(9, 0.0, 1.0, 2)))
check_linear("curves edge3 -> edge3, in part", chain(13, 0.4, 1.5, 3), with_arrays(chain(9, 0.0, 1.0, 4)))


# Linear meshes raised to second order here (a node at the middle of every
# edge, shared by the cells around it, in VTK's order of the quadratic
# cell): pyramids (Gmsh gives none), wedges, hexahedra; then bent by a
# smooth map (curved cells, conforming).
EDGES = {VTK_TETRA: (VTK_QUADRATIC_TETRA, [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]),
         12: (25, [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6),
                   (3, 7)]),
         13: (26, [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]),
         14: (27, [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 4), (2, 4), (3, 4)])}


def raised(g, bent=None):
    x = [tuple(p) for p in points_of(g)]
    mids = {}
    cells = []
    for c in range(g.GetNumberOfCells()):
        ids = [g.GetCell(c).GetPointId(k) for k in range(g.GetCell(c).GetNumberOfPoints())]
        quadratic, edges = EDGES[g.GetCellType(c)]
        for a, b in edges:
            key = (min(ids[a], ids[b]), max(ids[a], ids[b]))
            if key not in mids:
                mids[key] = len(x)
                x.append(tuple((np.asarray(x[ids[a]]) + np.asarray(x[ids[b]])) / 2))
            ids.append(mids[key])
        cells.append((quadratic, ids))
    out = vtkUnstructuredGrid()
    points = vtkPoints()
    y = np.asarray(x, dtype=np.float64)
    points.SetData(numpy_to_vtk(np.ascontiguousarray(bent(y) if bent else y), deep=True))
    out.SetPoints(points)
    for t, ids in cells:
        out.InsertNextCell(t, len(ids), ids)
    return out


def bulge(x):
    return x + 0.04 * np.stack([np.sin(3 * x[:, 1]), np.sin(3 * x[:, 2]), np.sin(3 * x[:, 0])], 1)


pyramids13 = raised(gmshmeshes.pyramids(1.2))
hexes20 = raised(gmshmeshes.hexahedra(0.6, False))
wedges15 = raised(gmshmeshes.wedges(0.3))
check(pyramids13.GetCellType(0) == 27 and hexes20.GetCellType(0) == 25, "raised meshes: pyramid13, hex20")
check_linear("raised pyramid13 -> hex20", hexes20, with_arrays(pyramids13))
check_linear("raised hex20 -> pyramid13", pyramids13, with_arrays(hexes20))
check_linear("raised wedge15 -> pyramid13, in part", shifted(pyramids13, (0.3, -0.2, 0.4)), with_arrays(wedges15))
check_linear("bent pyramid13 -> tet10 (curved)", raised(gmshmeshes.volume("box", 0.4), bulge),
             with_arrays(raised(gmshmeshes.pyramids(1.2), bulge)))
check_linear("bent tet10 -> hex20 (curved)", raised(gmshmeshes.hexahedra(0.6, False), bulge),
             with_arrays(raised(gmshmeshes.volume("box", 0.4), bulge)))

# b. Conservation: Inputs covering their Source (the Source scaled into them).
inner = {"square": lambda x: 0.1 + 0.8 * x, "cube": lambda x: 0.1 + 0.8 * x}
for group, meshes in (("square", square), ("cube", cube)):
    for s in meshes:
        source = with_arrays(copy_grid(meshes[s], inner[group]))
        for t in meshes:
            out = project(meshes[t], source)
            total, reference = field(out, "TargetIntegral_Smooth"), field(out, "SourceIntegral_Smooth")
            print("%s %s -> %s: integral kept to %.2g" % (group, s, t, abs(total - reference) / abs(reference)))
            check(abs(total - reference) <= 1e-11 * abs(reference),
                  "%s %s -> %s: the Source integral kept (%.17g, %.17g)" % (group, s, t, total, reference))


def tri6_integral(g, values):
    """The integral of the 6-node triangles' own quadratic interpolant of
    `values` (at every node) on straight cells: a third of the area times
    each mid node's value (the corners' functions integrate to zero)."""
    x = points_of(g)
    total = 0.0
    for c in range(g.GetNumberOfCells()):
        n = [g.GetCell(c).GetPointId(k) for k in range(6)]
        u, v = x[n[1]] - x[n[0]], x[n[2]] - x[n[0]]
        area = 0.5 * abs(u[0] * v[1] - u[1] * v[0])
        total += area / 3.0 * (values[n[3]] + values[n[4]] + values[n[5]])
    return total


# The cells' own integral on the straight square; on the curved disk (the
# functions through the true inverse map over the polygon through the
# nodes) the Source's and the Input's integrals agree.
for name, mesh in (("square", copy_grid(square["tri6"], inner["square"])), ("disk", disk["tri6"])):
    source = with_arrays(mesh)
    target = copy_grid(square["quad9"], lambda x: 2.4 * x - 1.2) if name == "disk" else square["quad8"]
    out = project(target, source)
    expected = tri6_integral(source, point_array(source, "Smooth")) if name == "square" else \
        field(out, "SourceIntegral_Smooth")
    for which in ("SourceIntegral_Smooth", "TargetIntegral_Smooth"):
        got = field(out, which)
        check(abs(got - expected) <= 1e-11 * abs(expected),
              "%s tri6: %s %.17g, the cells' own %.17g" % (name, which, got, expected))

# d. Lagrange cells of order 2 == the quadratic cells with the same nodes.
lagrange = {22: VTK_LAGRANGE_TRIANGLE, 28: VTK_LAGRANGE_QUADRILATERAL, 24: VTK_LAGRANGE_TETRAHEDRON,
            29: VTK_LAGRANGE_HEXAHEDRON, 32: VTK_LAGRANGE_WEDGE, 21: VTK_LAGRANGE_CURVE}
pairs = [("square tri6 -> quad9", square["quad9"], square["tri6"]),
         ("disk quad9 -> tri6", disk["tri6"], disk["quad9"]),
         ("cube tet10 -> hex27", cube["hex27"], cube["tet10"]),
         ("curves", chain(13, 0.0, 1.0, 1), chain(9, 0.0, 1.0, 2))]
wedges18 = gmshmeshes.second_order("prisms", 0.5, False, False)
pairs.append(("cube wedge18 -> tet10", cube["tet10"], wedges18))
for name, target, source in pairs:
    quadratic = project(target, with_arrays(source))
    as_lagrange = project(copy_grid(target, types=lagrange), with_arrays(copy_grid(source, types=lagrange)))
    same = all(np.array_equal(point_array(quadratic, a), point_array(as_lagrange, a), equal_nan=True)
               for a in ("Linear", "Smooth"))
    check(same and quadratic.GetCellType(0) != as_lagrange.GetCellType(0),
          "%s: Lagrange cells of order 2 give the quadratic cells' result bit for bit" % name)

# e. Mixed linear and quadratic cells: the tet10 cube's cells with x < 0.5
# as linear tetrahedra on their corners (the mid nodes of their faces lie
# on them: no gap); composite Input and Source.
mixed = vtkUnstructuredGrid()
mixed.SetPoints(cube["tet10"].GetPoints())
x = points_of(cube["tet10"])
for c in range(cube["tet10"].GetNumberOfCells()):
    ids = [cube["tet10"].GetCell(c).GetPointId(k) for k in range(10)]
    if x[ids[:4]].mean(axis=0)[0] < 0.5:
        mixed.InsertNextCell(VTK_TETRA, 4, ids[:4])
    else:
        mixed.InsertNextCell(VTK_QUADRATIC_TETRA, 10, ids)
check_linear("mixed tet4 + tet10 -> hex20", cube["hex20"], with_arrays(mixed))
check_linear("hex27 -> mixed tet4 + tet10", mixed, with_arrays(cube["hex27"]))
blocks_source = vtkMultiBlockDataSet()
blocks_source.SetBlock(0, with_arrays(cube["tet10"]))
blocks_source.SetBlock(1, with_arrays(shifted(cube["hex20"], (1.0, 0.0, 0.0))))
blocks_target = vtkMultiBlockDataSet()
blocks_target.SetBlock(0, shifted(cube["wedge15"], (0.5, 0.0, 0.0)))
blocks_target.SetBlock(1, shifted(cube["hex27"], (1.2, 0.0, 0.0)))
f = meshprojection.vtkMeshProjectionFilter()
f.SetInputData(blocks_target)
f.SetSourceData(blocks_source)
f.Update()
for b in range(2):
    leaf = f.GetOutputDataObject(0).GetBlock(b)
    x = points_of(leaf)
    valid = point_array(leaf, "vtkValidPointMask").astype(bool)
    error = np.max(np.abs(point_array(leaf, "Linear") - linear(x))[valid]) / np.ptp(linear(x))
    check(valid.sum() > 0.5 * len(valid) and error <= 1e-9, "composite block %d: linear exact (%.2g)" % (b, error))

# f. The kept operator: rebuilt when only a mid node moves or changes id.
target = copy_grid(cube["tet10"])
source = with_arrays(cube["hex20"])
f = meshprojection.vtkMeshProjectionFilter()
f.SetInputData(target)
f.SetSourceData(source)
f.SetCacheOperator(True)
f.Update()
before = point_array(f.GetOutput(), "Smooth").copy()
# (Inputs given as data are not time series: the second execution keeps an
# assembled operator, the third reuses it.)
for step in (2, 3):
    f.Modified()
    f.Update()
check(f.GetOperatorReused(), "kept operator reused when nothing changed")
mid = target.GetCell(0).GetPointId(7)
x = points_of(target)
x[mid] += 0.01 * np.array([1.0, -1.0, 1.0])
target.GetPoints().Modified()
target.Modified()
f.Update()
check(not f.GetOperatorReused(), "a moved mid node: the operator rebuilt")
moved_values = point_array(f.GetOutput(), "Smooth").copy()
check(not np.array_equal(moved_values, before), "a moved mid node: other values")
x[mid] -= 0.01 * np.array([1.0, -1.0, 1.0])
target.GetPoints().Modified()
# The same mid node as a new point at the same place.
copy_id = target.GetPoints().InsertNextPoint(x[mid])
cell = target.GetCell(0)
ids = [cell.GetPointId(k) for k in range(10)]
ids[7] = copy_id
target.ReplaceCell(0, 10, ids)
target.Modified()
f.Update()
check(not f.GetOperatorReused(), "a renumbered mid node: the operator rebuilt")
for step in (2, 3):
    f.Modified()
    f.Update()
check(f.GetOperatorReused(), "renumbered mid node, nothing changed since: the operator reused")

# g. Refusals by name; the output is Input unchanged.
tet20_points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)] + [tuple(np.random.default_rng(k).uniform(0.1, 0.2, 3))
                                                              for k in range(16)]


def one_cell(cell_type, points, ids=None):
    g = vtkUnstructuredGrid()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(np.asarray(points, dtype=np.float64)), deep=True))
    g.SetPoints(p)
    g.InsertNextCell(cell_type, len(ids or points), list(ids or range(len(points))))
    return with_arrays(g)


folded = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (0.5, 0, 0), (0.5, 0.5, 0), (0, 0.5, 0), (0, 0, 0.5),
          (-0.4, -0.4, -0.4), (0, 0.5, 0.5)]
refusals = [("Lagrange tetrahedron of order 3", one_cell(VTK_LAGRANGE_TETRAHEDRON, tet20_points),
             ["vtkLagrangeTetra", "has 20 nodes", "order 2"]),
            ("Bezier triangle", one_cell(VTK_BEZIER_TRIANGLE, [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0.5, 0, 0),
                                                               (0.5, 0.5, 0), (0, 0.5, 0)]),
             ["vtkBezierTriangle", "Accepted second-order cells", "Tessellate"]),
            ("quadratic-linear quad", one_cell(VTK_QUADRATIC_LINEAR_QUAD, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
                                                                          (0.5, 0, 0), (0.5, 1, 0)]),
             ["vtkQuadraticLinearQuad", "Tessellate"]),
            ("folded quadratic tetrahedron", one_cell(VTK_QUADRATIC_TETRA, folded),
             ["cell 0 (vtkQuadraticTetra) is folded"])]
for name, bad, words in refusals:
    for port in ("Source", "Input"):
        f, texts = observed_filter("ErrorEvent")
        good = cube["tet10"] if bad.GetCell(0).GetCellDimension() == 3 else square["tri6"]
        target, source = (good, bad) if port == "Source" else (bad, with_arrays(good))
        f.SetInputData(target)
        f.SetSourceData(source)
        f.Update()
        text = " ".join(texts)
        check(all(w in text for w in words) and port in text,
              "%s as %s: error naming %s (%r)" % (name, port, words, texts))
        out = f.GetOutput()
        check(out.GetNumberOfPoints() == target.GetNumberOfPoints() and
              out.GetPointData().GetArray("vtkValidPointMask") is None,
              "%s as %s: Input passed through" % (name, port))

finish()
