"""CellDataReconstruction: cell data made linear on each Source cell before
it is projected (VTK Python: /usr/bin/python3 with the build's python
directory on PYTHONPATH). Cell averages are exact: the mean of a field over
each cell, from the cell's own simplices (a degree-2 rule on each).

    a. mode 2 (linear) reproduces a linear field's cell averages exactly, to
       cells and to points, on every cell type: Gmsh pairs (triangles, quads,
       mixed 2D; hexahedra, tetrahedra, wedges, mixed 3D), image data,
       hexahedra split into wedges and pyramids, polyhedra, non-convex
       polygons, a tilted planar surface, a
       curve in space, a trace (a plane in tetrahedra), a composite Source
       (which, its blocks cut apart, gives the uncut Source's result);
    b. the observed order on a smooth field, modes 1 and 2, 2D, 3D and a
       curved surface (Gmsh spheres), over two resolutions, is at least 1.8
       (mode 0: about 1);
    c. integrals are conserved (every mode, intensive and extensive, to
       cells and to points);
    d. a step field stays within its bounds under the limiter (mode 1), and
       within the range of each target cell's Source cells and their
       neighbours; without it (mode 2) it does not;
    e. a NaN hole: the cells next to it use the neighbours they have (linear
       stays exact), the hole stays a hole; a Source numbered at random
       gives the same result;
    f. operators kept across a time series: a later step reuses them (and
       the reconstruction's geometry) and gives a fresh run's result, also
       once Source has moved; switching the mode builds new ones;
       GetMatrix refuses the mixed matrix of reconstructed data.
"""
import os

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_DOUBLE, vtkIdList, vtkPoints
from vtkmodules.vtkCommonDataModel import (VTK_HEXAHEDRON, VTK_LINE, VTK_POLYGON, VTK_POLYHEDRON,
                                           VTK_PYRAMID, VTK_TETRA,
                                           VTK_TRIANGLE, VTK_WEDGE, vtkImageData,
                                           vtkMultiBlockDataSet, vtkUnstructuredGrid)
from vtkmodules.vtkCommonCore import vtkIdTypeArray, vtkDoubleArray
from vtkmodules.vtkFiltersCore import vtkAppendFilter
from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter

from meshprojection import vtkMeshProjectionFilter
from mpsupport import meshes
from mpsupport.testing import GMSH, check, finish, read

CONSTANT, LIMITED, LINEAR = 0, 1, 2


def linear(x):
    return 1.0 + 2.0 * x[..., 0] - 3.0 * x[..., 1] + 0.5 * x[..., 2]


def smooth(x):
    return np.sin(2 * x[..., 0]) * np.cos(3 * x[..., 1]) + x[..., 2] ** 2 + 0.5 * x[..., 0]


def step(x):
    return np.where(x[..., 0] + 0.3 * x[..., 1] > 0.45, 2.0, -1.0)


def as_grid(ds):
    """Any dataset as a vtkUnstructuredGrid."""
    a = vtkAppendFilter()
    a.AddInputData(ds)
    a.Update()
    g = vtkUnstructuredGrid()
    g.ShallowCopy(a.GetOutput())
    if g.GetPoints() is not None and g.GetPoints().GetDataType() != VTK_DOUBLE:
        # (Image data's points come as floats: the exact ones.)
        p = vtkPoints()
        p.SetData(numpy_to_vtk(points_of(ds), deep=True))
        g.SetPoints(p)
    return g


def simplices(ds):
    """The dataset's cells as simplices (vtkDataSetTriangleFilter): their
    corners' coordinates (n, k, 3) and the original cell of each."""
    g = as_grid(ds)
    ids = vtkIdTypeArray()
    ids.SetName("cellId")
    ids.SetNumberOfTuples(g.GetNumberOfCells())
    vtk_to_numpy(ids)[:] = np.arange(g.GetNumberOfCells())
    g.GetCellData().AddArray(ids)
    t = vtkDataSetTriangleFilter()
    t.SetInputData(g)
    t.Update()
    out = t.GetOutput()
    x = vtk_to_numpy(out.GetPoints().GetData()).astype(float)
    offsets = vtk_to_numpy(out.GetCells().GetOffsetsArray())
    conn = vtk_to_numpy(out.GetCells().GetConnectivityArray())
    k = int(offsets[1] - offsets[0])
    check(np.all(np.diff(offsets) == k), "one kind of simplex per mesh")
    return x[conn.reshape(-1, k)], vtk_to_numpy(out.GetCellData().GetArray("cellId"))


def simplex_measures(p):
    e = p[:, 1:] - p[:, :1]
    if p.shape[1] == 2:
        return np.linalg.norm(e[:, 0], axis=1)
    if p.shape[1] == 3:
        return 0.5 * np.linalg.norm(np.cross(e[:, 0], e[:, 1]), axis=1)
    return np.abs(np.einsum("ij,ij->i", e[:, 0], np.cross(e[:, 1], e[:, 2]))) / 6


def averages(ds, f):
    """Per cell: the mean of f and the measure."""
    p, cell = simplices(ds)
    m = simplex_measures(p)
    n = ds.GetNumberOfCells()
    measure = np.bincount(cell, m, n)
    mean = np.bincount(cell, m * meshes.simplex_means(p, f), n) / np.where(measure > 0, measure, 1)
    return mean, measure


def points_of(ds):
    return np.array([ds.GetPoint(i) for i in range(ds.GetNumberOfPoints())], dtype=float)


def with_cell_field(ds, f, name="u"):
    mean, _ = averages(ds, f)
    a = numpy_to_vtk(mean, deep=True)
    a.SetName(name)
    ds.GetCellData().AddArray(a)
    return ds


def project(target, source, mode, **properties):
    f = vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCellDataReconstruction(mode)
    f.SetCellDataTarget(vtkMeshProjectionFilter.TO_POINTS_AND_CELLS)
    f.SetCacheOperator(properties.pop("CacheOperator", False))
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f


def cell_result(out, name="u"):
    return vtk_to_numpy(out.GetCellData().GetArray(name)).astype(float)


def point_result(out, name="u"):
    return vtk_to_numpy(out.GetPointData().GetArray(name)).astype(float)


def valid_cells(out):
    return vtk_to_numpy(out.GetCellData().GetArray("vtkValidCellMask")).astype(bool)


def whole_cells(out):
    """The target cells covered whole (a cell covered in part gets the mean over its covered part)."""
    return vtk_to_numpy(out.GetCellData().GetArray("CoveredFraction")) >= 1 - 1e-12


def valid_points(out):
    return vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask")).astype(bool)


def check_linear(target, source, what, tol=1e-10):
    """Mode 2 on the linear field: the target's cell averages and point values, exactly."""
    with_cell_field(source, linear)
    out = project(target, source, LINEAR).GetOutput()
    span = float(np.ptp(vtk_to_numpy(source.GetCellData().GetArray("u"))))
    exact, _ = averages(target, linear)
    cells = whole_cells(out)
    check(cells.sum() > 0, "%s: cells covered whole" % what)
    err = np.max(np.abs(cell_result(out)[cells] - exact[cells])) / span
    check(err <= tol, "%s: linear cell averages to cells exact (%.3g of the range)" % (what, err))
    pts = valid_points(out)
    err = np.max(np.abs(point_result(out)[pts] - linear(points_of(target))[pts])) / span
    check(err <= tol, "%s: linear cell averages to points exact (%.3g of the range)" % (what, err))
    # The constant reconstruction is not: the test can tell.
    out0 = project(target, source, CONSTANT).GetOutput()
    err0 = np.max(np.abs(cell_result(out0)[cells] - exact[cells])) / span
    check(err0 > 100 * tol, "%s: constant reconstruction is not exact (%.3g)" % (what, err0))


def gmsh(name):
    return read(os.path.join(GMSH, name + ".vtu"))


def stripped(ds):
    """A copy without data arrays."""
    g = as_grid(ds)
    g.GetPointData().Initialize()
    g.GetCellData().Initialize()
    return g


# ---------------------------------------------------------------------------
# a. Linear fields, every cell type
for t, s in (("quads_disk", "tris_disk"), ("tris_disk", "mixed_disk"), ("mixed_disk", "quads_disk"),
             ("hexes_box", "tets_box"), ("tets_box", "mixed_box"), ("mixed_box", "hexes_box"),
             ("wedges_cylinder", "mixed_box"), ("tets_box", "wedges_cylinder")):
    check_linear(stripped(gmsh(t)), stripped(gmsh(s)), "Gmsh %s <- %s" % (t, s))


def image(origin, spacing, dims):
    im = vtkImageData()
    im.SetOrigin(origin)
    im.SetSpacing(spacing)
    im.SetDimensions(dims)
    return im


check_linear(as_grid(meshes.grid(*meshes.triangles(13, (0, 0), (1, 1), 3), VTK_TRIANGLE)),
             image((-0.05, -0.07, 0), (0.09, 0.08, 1), (14, 15, 1)), "pixels <- triangles")
check_linear(as_grid(meshes.grid(*meshes.tetrahedra(5, (0, 0, 0), (1, 1, 1), 4, 0.2), VTK_TETRA)),
             image((-0.05, -0.07, -0.03), (0.13, 0.12, 0.11), (10, 11, 11)), "voxels <- tetrahedra")


def box_cells(n, kind, shear=0.2):
    """A sheared box grid (planar faces) of hexahedra, or each hexahedron as
    two wedges or six pyramids around an added centre."""
    x = meshes.structured(n, (0, 0, 0), (1, 1, 1), 3, 0, jitter=0.0)
    x = x @ np.array([[1.0, 0.0, 0.0], [shear, 1.0, 0.0], [0.1, -shear, 1.0]])
    hexes = np.stack(meshes._cube_corners((n, n, n)), 1)
    if kind == "hex":
        return meshes.grid(x, hexes, VTK_HEXAHEDRON)
    if kind == "wedge":
        w = np.concatenate([hexes[:, [0, 1, 2, 4, 5, 6]], hexes[:, [0, 2, 3, 4, 6, 7]]])
        return meshes.grid(x, w, VTK_WEDGE)
    centre = x[hexes].mean(axis=1)
    c = np.arange(len(x), len(x) + len(hexes))
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    pyr = np.concatenate([np.column_stack([hexes[:, list(f)], c]) for f in faces])
    return meshes.grid(np.concatenate([x, centre]), pyr, VTK_PYRAMID)


tets = as_grid(meshes.grid(*meshes.tetrahedra(6, (0, 0, 0), (1.2, 1.2, 1.2), 5, 0.2), VTK_TETRA))
for kind in ("hex", "wedge", "pyramid"):
    check_linear(stripped(tets), box_cells(4, kind), "tetrahedra <- sheared %ss" % kind)
    check_linear(box_cells(5, kind), stripped(tets), "sheared %ss <- tetrahedra" % kind)


def polyhedra(n):
    """The sheared box's hexahedra as polyhedra (face streams)."""
    hexes = box_cells(n, "hex")
    out = vtkUnstructuredGrid()
    out.SetPoints(hexes.GetPoints())
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    for c in range(hexes.GetNumberOfCells()):
        ids = hexes.GetCell(c).GetPointIds()
        stream = vtkIdList()
        stream.InsertNextId(len(faces))
        for f in faces:
            stream.InsertNextId(len(f))
            for k in f:
                stream.InsertNextId(ids.GetId(k))
        out.InsertNextCell(VTK_POLYHEDRON, stream)
    return out


def polygons(n):
    """A sheared grid's squares, three of each four merged into an L-shaped
    (non-convex) octagon, the fourth a square, all as polygons."""
    x = meshes.structured(n, (0, 0), (1, 1), 2, 0, jitter=0.0) @ np.array([[1, 0.2, 0], [0.1, 1, 0], [0, 0, 1.0]])
    at = lambda i, j: i * (n + 1) + j  # noqa: E731
    cells = []
    for i in range(0, n - 1, 2):
        for j in range(0, n - 1, 2):
            cells.append([at(i, j), at(i + 1, j), at(i + 2, j), at(i + 2, j + 1), at(i + 1, j + 1),
                          at(i + 1, j + 2), at(i, j + 2), at(i, j + 1)])
            cells.append([at(i + 1, j + 1), at(i + 2, j + 1), at(i + 2, j + 2), at(i + 1, j + 2)])
    g = vtkUnstructuredGrid()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(x, deep=True))
    g.SetPoints(p)
    for c in cells:
        stream = vtkIdList()
        for k in c:
            stream.InsertNextId(k)
        g.InsertNextCell(VTK_POLYGON, stream)
    return g


check_linear(stripped(tets), polyhedra(4), "tetrahedra <- polyhedra")
check_linear(as_grid(meshes.grid(*meshes.triangles(17, (0.05, 0.05), (1.1, 1.1), 19), VTK_TRIANGLE)),
             polygons(8), "triangles <- L-shaped polygons")


def tilted(grid):
    """A planar 2D grid turned into the plane through the origin with normal (1, 2, 2)/3."""
    x = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    u = np.array([2.0, -1.0, 0.0]) / np.sqrt(5)
    v = np.cross(np.array([1.0, 2.0, 2.0]) / 3, u)
    y = np.outer(x[:, 0], u) + np.outer(x[:, 1], v)
    g = vtkUnstructuredGrid()
    g.DeepCopy(grid)
    p = vtkPoints()
    p.SetData(numpy_to_vtk(y, deep=True))
    g.SetPoints(p)
    return g


check_linear(tilted(as_grid(meshes.grid(*meshes.triangles(14, (0, 0), (1, 1), 6), VTK_TRIANGLE))),
             tilted(as_grid(meshes.grid(*meshes.quads(9, (-0.1, -0.1), (1.1, 1.1), 7), 9))),
             "tilted surface: triangles <- quads")


def curve(n, seed):
    """A straight polyline in space, points jittered along it."""
    s = np.linspace(0, 1, n + 1)
    s[1:-1] += np.random.default_rng(seed).uniform(-0.2, 0.2, n - 1) / n
    x = np.outer(s, [0.8, 0.5, -0.3])
    return meshes.grid(x, np.column_stack([np.arange(n), np.arange(1, n + 1)]), VTK_LINE)


check_linear(curve(37, 8), curve(11, 9), "curve in space")


def plane_in(volume_box, n):
    """Triangles of the plane z = 0.43 inside a box."""
    x, t = meshes.triangles(n, (0.05, 0.05), (0.95, 0.95), 10)
    x[:, 2] = 0.43
    return as_grid(meshes.grid(x, t, VTK_TRIANGLE))


check_linear(plane_in(None, 9), stripped(tets), "trace: a plane in tetrahedra", tol=1e-9)

# A composite Source: the tetrahedra in two blocks.
with_cell_field(tets, linear)
centres = np.array([np.mean([tets.GetPoint(tets.GetCell(c).GetPointId(k)) for k in range(4)], axis=0)
                    for c in range(tets.GetNumberOfCells())])
composite = vtkMultiBlockDataSet()
for b, keep in enumerate((centres[:, 0] < 0.6, centres[:, 0] >= 0.6)):
    composite.SetBlock(b, meshes.extract(tets, keep))
target = box_cells(4, "hex")
out = project(target, composite, LINEAR).GetOutput()
exact, _ = averages(target, linear)
err = np.max(np.abs(cell_result(out) - exact)[whole_cells(out)]) / float(np.ptp(exact))
check(err <= 1e-10, "composite Source: linear exact (%.3g)" % err)
# Its blocks have their own copies of the points between them: neighbours
# all the same (points are their coordinates), so a smooth field gives the
# uncut Source's result.
with_cell_field(tets, smooth)
for b, keep in enumerate((centres[:, 0] < 0.6, centres[:, 0] >= 0.6)):
    composite.SetBlock(b, meshes.extract(tets, keep))
for mode in (LIMITED, LINEAR):
    cut_result = cell_result(project(target, composite, mode).GetOutput())
    whole_result = cell_result(project(target, tets, mode).GetOutput())
    diff = np.nanmax(np.abs(cut_result - whole_result))
    check(diff <= 1e-12, "composite Source, mode %d: the uncut Source's result (%.3g)" % (mode, diff))

# ---------------------------------------------------------------------------
# b. Orders on a smooth field


def l1_error(target, source, mode):
    with_cell_field(source, smooth)
    out = project(target, source, mode).GetOutput()
    exact, measure = averages(target, smooth)
    return float(np.sum(np.abs(cell_result(out) - exact) * measure))


for dim, sizes in ((2, ((10, 40), (20, 80))), (3, ((5, 12), (10, 24)))):
    def pair(ns, nt):
        if dim == 2:
            return (as_grid(meshes.grid(*meshes.triangles(nt, (0, 0), (1, 1), 2), VTK_TRIANGLE)),
                    as_grid(meshes.grid(*meshes.triangles(ns, (0, 0), (1, 1), 1), VTK_TRIANGLE)))
        return (as_grid(meshes.grid(*meshes.tetrahedra(nt, (0, 0, 0), (1, 1, 1), 2, 0.2), VTK_TETRA)),
                as_grid(meshes.grid(*meshes.tetrahedra(ns, (0, 0, 0), (1, 1, 1), 1, 0.2), VTK_TETRA)))
    pairs = [pair(*s) for s in sizes]
    for mode, least in ((CONSTANT, 0.8), (LIMITED, 1.8), (LINEAR, 1.8)):
        e = [l1_error(t, s, mode) for t, s in pairs]
        order = np.log2(e[0] / e[1])
        check(order >= least and (mode != CONSTANT or order < 1.3),
              "%dD mode %d: observed order %.2f (errors %.3g, %.3g)" % (dim, mode, order, e[0], e[1]))

# On a curved surface (Gmsh spheres): the gradients in each facet's plane.
from mpsupport import gmshmeshes  # noqa: E402
e = {mode: [] for mode in (CONSTANT, LIMITED, LINEAR)}
for hs, ht in ((0.2, 0.05), (0.1, 0.025)):
    sphere_t = gmshmeshes.surface("sphere", ht)
    sphere_s = gmshmeshes.surface("sphere", hs, algorithm=5)
    for mode in e:
        e[mode].append(l1_error(sphere_t, sphere_s, mode))
for mode, least in ((CONSTANT, 0.8), (LIMITED, 1.8), (LINEAR, 1.8)):
    order = np.log2(e[mode][0] / e[mode][1])
    check(order >= least and (mode != CONSTANT or order < 1.3),
          "sphere, mode %d: observed order %.2f (errors %.3g, %.3g)" % (mode, order, e[mode][0], e[mode][1]))

# ---------------------------------------------------------------------------
# c. Conservation
for t, s in (("quads_disk", "tris_disk"), ("hexes_box", "mixed_box"), ("mixed_box", "tets_box")):
    target, source = stripped(gmsh(t)), stripped(gmsh(s))
    with_cell_field(source, smooth)
    values, measure = averages(source, smooth)
    for mode in (CONSTANT, LIMITED, LINEAR):
        for quantity in (vtkMeshProjectionFilter.INTENSIVE, vtkMeshProjectionFilter.EXTENSIVE):
            f = project(target, source, mode, CellDataQuantity=quantity)
            out = f.GetOutput()
            _, tm = averages(target, smooth)
            cells = valid_cells(out)
            if quantity == vtkMeshProjectionFilter.INTENSIVE:
                got, want = float(np.sum((cell_result(out) * tm)[cells])), float(np.sum(values * measure))
                # (Points: the integral the filter reports of the P1 result.)
                fd = out.GetFieldData()
                src = fd.GetArray("SourceIntegral_u (cell data)")
                tgt = fd.GetArray("TargetIntegral_u (cell data)")
                check(src is not None and tgt is not None and
                      abs(src.GetValue(0) - tgt.GetValue(0)) <= 1e-12 * abs(want) + 1e-15,
                      "%s <- %s mode %d: reported integrals equal" % (t, s, mode))
            else:
                got, want = float(np.sum(cell_result(out)[cells])), float(np.sum(values))
            covered_whole = t in ("hexes_box", "mixed_box")
            if covered_whole:
                check(abs(got - want) <= 1e-12 * abs(want),
                      "%s <- %s mode %d quantity %d: integral %r == Source's %r"
                      % (t, s, mode, quantity, got, want))

# ---------------------------------------------------------------------------
# d. A step field under the limiter
for dim in (2, 3):
    if dim == 2:
        source = as_grid(meshes.grid(*meshes.triangles(12, (0, 0), (1, 1), 11), VTK_TRIANGLE))
        target = as_grid(meshes.grid(*meshes.triangles(41, (0, 0), (1, 1), 12), VTK_TRIANGLE))
    else:
        source = as_grid(meshes.grid(*meshes.tetrahedra(6, (0, 0, 0), (1, 1, 1), 11, 0.2), VTK_TETRA))
        target = as_grid(meshes.grid(*meshes.tetrahedra(13, (0, 0, 0), (1, 1, 1), 12, 0.2), VTK_TETRA))
    with_cell_field(source, step)
    su = vtk_to_numpy(source.GetCellData().GetArray("u"))
    lo, hi = float(su.min()), float(su.max())
    limited = cell_result(project(target, source, LIMITED).GetOutput())
    unlimited = cell_result(project(target, source, LINEAR).GetOutput())
    slack = 1e-13 * (hi - lo)
    check(limited.min() >= lo - slack and limited.max() <= hi + slack,
          "%dD step, limited: within [%g, %g] (got [%.17g, %.17g])" % (dim, lo, hi, limited.min(), limited.max()))
    check(unlimited.min() < lo - 1e-3 or unlimited.max() > hi + 1e-3,
          "%dD step, unlimited overshoots (the check can fail): [%g, %g]" % (dim, unlimited.min(), unlimited.max()))

# ---------------------------------------------------------------------------
# e. A NaN hole
source = as_grid(meshes.grid(*meshes.triangles(16, (0, 0), (1, 1), 13), VTK_TRIANGLE))
target = as_grid(meshes.grid(*meshes.triangles(29, (0.02, 0.03), (0.97, 0.99), 14), VTK_TRIANGLE))
with_cell_field(source, linear)
u = vtk_to_numpy(source.GetCellData().GetArray("u"))
centre = np.array([np.mean([source.GetPoint(source.GetCell(c).GetPointId(k)) for k in range(3)], axis=0)
                   for c in range(source.GetNumberOfCells())])
hole = np.hypot(centre[:, 0] - 0.5, centre[:, 1] - 0.5) < 0.2
u[hole] = np.nan
source.GetCellData().GetArray("u").Modified()
out = project(target, source, LINEAR).GetOutput()
exact, _ = averages(target, linear)
got = cell_result(out)
tc = np.array([np.mean([target.GetPoint(target.GetCell(c).GetPointId(k)) for k in range(3)], axis=0)
               for c in range(target.GetNumberOfCells())])
r = np.hypot(tc[:, 0] - 0.5, tc[:, 1] - 0.5)
outside = (r > 0.35) & whole_cells(out)  # beyond the hole's cells and the target cells they meet
err = np.max(np.abs(got - exact)[outside]) / float(np.ptp(exact))
check(err <= 1e-10, "NaN hole: linear exact next to the hole (%.3g)" % err)
check(np.all(np.isnan(got[r < 0.15])), "NaN hole: target cells inside the hole have no value")

# ---------------------------------------------------------------------------
# e'. The Source numbered at random: the same result (the gradients do not
# depend on the order of cells or points).
source = as_grid(meshes.grid(*meshes.tetrahedra(6, (0, 0, 0), (1, 1, 1), 16, 0.2), VTK_TETRA))
target = as_grid(meshes.grid(*meshes.tetrahedra(9, (0.05, 0, 0), (1, 1.05, 1), 17, 0.2), VTK_TETRA))
with_cell_field(source, smooth)
x = vtk_to_numpy(source.GetPoints().GetData()).astype(float)
conn = vtk_to_numpy(source.GetCells().GetConnectivityArray()).reshape(-1, 4)
rng = np.random.default_rng(18)
point_order, cell_order = rng.permutation(len(x)), rng.permutation(len(conn))
new_id = np.empty_like(point_order)
new_id[point_order] = np.arange(len(point_order))
shuffled = meshes.grid(x[point_order], new_id[conn][cell_order], VTK_TETRA)
u = numpy_to_vtk(vtk_to_numpy(source.GetCellData().GetArray("u"))[cell_order].copy(), deep=True)
u.SetName("u")
shuffled.GetCellData().AddArray(u)
for mode in (LIMITED, LINEAR):
    diff = np.nanmax(np.abs(cell_result(project(target, shuffled, mode).GetOutput()) -
                            cell_result(project(target, source, mode).GetOutput())))
    check(diff <= 1e-12, "mode %d: a shuffled Source numbering gives the same result (%.3g)" % (mode, diff))

# ---------------------------------------------------------------------------
# f. Kept operators across steps
source = as_grid(meshes.grid(*meshes.tetrahedra(5, (0, 0, 0), (1, 1, 1), 15, 0.2), VTK_TETRA))
target = box_cells(6, "wedge")
with_cell_field(source, smooth)
f = project(target, source, LIMITED, CacheOperator=True)
cells = valid_cells(f.GetOutput())
# (The first run sums its right-hand sides during the search; the same
# meshes coming again, the operators are assembled and kept; from then on
# they serve.)
for k in range(1, 4):
    with_cell_field(source, lambda x, k=k: smooth(x) * (1 + 0.3 * k) + k * x[..., 1])
    f.Modified()
    f.Update()
    check(f.GetOperatorReused() == (k > 1), "step %d: operators reused from the third run on" % k)
    fresh = project(target, source, LIMITED).GetOutput()
    diff = np.max(np.abs(cell_result(f.GetOutput()) - cell_result(fresh))[cells])
    check(diff <= 1e-9, "step %d: kept operators give a fresh run's result (%.3g)" % (k, diff))
# The Source moved (its kept geometry no longer serves): a fresh run's result.
moved = vtkUnstructuredGrid()
moved.DeepCopy(source)
x = vtk_to_numpy(moved.GetPoints().GetData())
x[:, 0] += 0.05 * np.sin(3 * x[:, 1])
moved.GetPoints().Modified()
f.SetSourceData(moved)
f.Update()
diff = np.nanmax(np.abs(cell_result(f.GetOutput()) - cell_result(project(target, moved, LIMITED).GetOutput())))
check(diff <= 1e-9, "moved Source: a fresh run's result (%.3g)" % diff)
f.SetSourceData(source)
f.SetCellDataReconstruction(CONSTANT)
f.Update()
check(not f.GetOperatorReused(), "another reconstruction: new operators")
constant = cell_result(f.GetOutput())
diff = np.max(np.abs(constant - cell_result(project(target, source, CONSTANT).GetOutput()))[cells])
check(diff <= 1e-9, "back to constant: the constant result (%.3g)" % diff)
f.SetCellDataReconstruction(LINEAR)
f.SetKeepMatrices(True)  # (GetMatrix reads the operators an execution kept)
f.Update()
rows, columns, values = vtkIdTypeArray(), vtkIdTypeArray(), vtkDoubleArray()
check(f.GetMatrix(vtkMeshProjectionFilter.CELLS_TO_CELLS, vtkMeshProjectionFilter.MIXED_MASS,
                  rows, columns, values) == -1, "GetMatrix refuses the mixed matrix of reconstructed data")
check(f.GetMatrix(vtkMeshProjectionFilter.CELLS_TO_CELLS, vtkMeshProjectionFilter.TARGET_MASS,
                  rows, columns, values) == target.GetNumberOfCells(), "GetMatrix gives M_tt")

finish()
