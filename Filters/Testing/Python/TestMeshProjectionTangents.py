"""TangentArrays through the VTK filter: vector fields tangent to a surface
or curve. Checks, on two facetizations of a sphere (points and cells), on a
tilted plane and on two polylines of a circle:
the result's normal part at every target point and cell (the target's own
normals, computed here independently) is at round-off, the tangential error
against the exact tangent field is no worse than the plain projection's,
the removed part is reported in <name>_NormalPart (what the plain
projection had there), a linear tangent field on a plane stays exact, a trace keeps the part of
a volume's vectors tangent to a sheet inside it, large removed parts are
said (10%), composite data, PreserveBounds and a kept operator work, and
a non-3-component array or a volume target is said by name and projected
as an ordinary array."""
import numpy as np

import meshprojection
from mpsupport.testing import check, finish, mortar, observed_filter
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkRegularPolygonSource, vtkSphereSource

ROUND_OFF = 1e-12


def points(mesh):
    return vtk_to_numpy(mesh.GetPoints().GetData()).astype(float)


def polygons(mesh):
    """Each cell's point ids (triangles or quads: the same count)."""
    return [[mesh.GetCell(c).GetPointId(k) for k in range(mesh.GetCell(c).GetNumberOfPoints())]
            for c in range(mesh.GetNumberOfCells())]


def cell_normals(mesh):
    """Area vectors of the polygons (Newell), or chords of the lines."""
    x = points(mesh)
    out = []
    for ids in polygons(mesh):
        p = x[ids]
        if mesh.GetCell(0).GetCellDimension() == 1:
            out.append(p[-1] - p[0])
        else:
            q = np.roll(p, -1, axis=0)
            out.append(0.5 * np.cross(p - p[0], q - p[0]).sum(axis=0))
    return np.array(out)


def point_normals(mesh, cells):
    """The sum of the area vectors (chords) of each point's cells."""
    d = np.zeros((mesh.GetNumberOfPoints(), 3))
    for c, ids in enumerate(polygons(mesh)):
        for i in ids:
            d[i] += cells[c]
    return d


def unit(d):
    return d / np.linalg.norm(d, axis=1)[:, None]


def normal_part(v, d, curve):
    """Per row: the magnitude of what is not tangent (surface: along d; curve: across d)."""
    along = np.sum(v * unit(d), axis=1)
    if curve:
        return np.linalg.norm(v - along[:, None] * unit(d), axis=1)
    return np.abs(along)


def with_field(mesh, name, values, cells=False):
    array = numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    array.SetName(name)
    (mesh.GetCellData() if cells else mesh.GetPointData()).AddArray(array)
    return mesh


def sphere(theta, phi):
    s = vtkSphereSource()
    s.SetRadius(1.0)
    s.SetThetaResolution(theta)
    s.SetPhiResolution(phi)
    s.Update()
    out = vtkPolyData()
    out.DeepCopy(s.GetOutput())
    out.GetPointData().Initialize()
    return out


def on_sphere(x):
    """The tangent field P(x) e_z + 0.5 (e_z x x): the projection of a
    constant onto the tangent plane plus a rotation, at x's radial direction."""
    r = unit(x)
    ez = np.array([0.0, 0.0, 1.0])
    return ez - r[:, 2:3] * r + 0.5 * np.cross(ez, r)


def output_array(f, name, cells=False):
    out = f.GetOutput()
    data = out.GetCellData() if cells else out.GetPointData()
    return vtk_to_numpy(data.GetArray(name)).astype(float)


def tangents(target, source, name, **properties):
    """The filter with `name` a tangent array (and any property by name)."""
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.AddTangentArray(name)
    for key, value in properties.items():
        getattr(f, "Set" + key)(value)
    f.Update()
    return f


def centroids(mesh):
    x = points(mesh)
    return np.array([x[ids].mean(axis=0) for ids in polygons(mesh)])


# --- A tangent field between two facetizations of a sphere -----------------
def remove_normal(v, d):
    """v without its part along d (per row)."""
    return v - np.sum(v * unit(d), axis=1)[:, None] * unit(d)


for cells in (False, True):
    kind = "cells" if cells else "points"
    source = sphere(24, 18)
    target = sphere(37, 29)
    # Point values: the exact field; cell values: tangent to their facets
    # (a solver's on a facetized surface).
    ns = cell_normals(source) if cells else point_normals(source, cell_normals(source))
    v = on_sphere(centroids(source)) if cells else on_sphere(points(source))
    if cells:
        v = remove_normal(v, ns)
    with_field(source, "v", v, cells)
    plain = mortar(target, source, pieces=False)
    f = tangents(target, source, "v")
    u = output_array(f, "v", cells)
    u0 = output_array(plain, "v", cells)
    n = cell_normals(target) if cells else point_normals(target, cell_normals(target))
    scale = np.max(np.linalg.norm(u, axis=1))
    normal = normal_part(u, n, False)
    normal0 = normal_part(u0, n, False)
    check(np.max(normal) < ROUND_OFF * scale,
          "sphere %s: the result's normal part is at round-off (%.2e, plain %.2e)"
          % (kind, np.max(normal) / scale, np.max(normal0) / scale))
    check(np.max(normal0) > 1e-4 * scale, "sphere %s: the plain projection leaves the surface (%.2e)"
          % (kind, np.max(normal0) / scale))
    # The tangential error (in the target's own tangent planes) against the exact field.
    exact = remove_normal(on_sphere(centroids(target) if cells else points(target)), n)
    error = np.sqrt(np.mean(np.sum((u - exact) ** 2, axis=1)))
    error0 = np.sqrt(np.mean(np.sum((remove_normal(u0, n) - exact) ** 2, axis=1)))
    # (Cells: the same up to round-off: their values are tangent to their facets.)
    check(error <= error0 * (1 + 1e-12), "sphere %s: tangential error against the exact field %.4e, plain %.4e"
          % (kind, error, error0))
    # The Source's own normal part goes first: a part along the Source's
    # normals changes nothing; what is removed on the target is reported.
    (source.GetCellData() if cells else source.GetPointData()).RemoveArray("v")
    with_field(source, "v", v + 3.0 * unit(ns), cells)
    f.Modified()
    f.Update()
    w = output_array(f, "v", cells)
    check(np.max(np.abs(w - u)) < 1e-12 * scale,
          "sphere %s: a part along the Source's normals is removed before the projection (%.2e)"
          % (kind, np.max(np.abs(w - u))))
    source_tangent = remove_normal(v, ns)
    (source.GetCellData() if cells else source.GetPointData()).RemoveArray("v")
    with_field(source, "v", source_tangent, cells)
    projected = output_array(mortar(target, source, pieces=False), "v", cells)
    reported = output_array(f, "v_NormalPart", cells)
    check(np.allclose(reported, normal_part(projected, n, False), rtol=0, atol=1e-12 * scale),
          "sphere %s: v_NormalPart is the normal part of the Source's tangential part projected "
          "(%.2e; largest %.2e)" % (kind, np.max(np.abs(reported - normal_part(projected, n, False))),
                                   np.max(reported)))
    check(np.allclose(u, remove_normal(projected, n), rtol=0, atol=1e-12 * scale),
          "sphere %s: the result is that projection without its normal part" % kind)

# --- A linear tangent field on a tilted plane stays exact -------------------
def tilted_plane(resolution, triangles):
    """The unit square in z = 0 (triangles or quads), turned in double precision."""
    p = vtkPlaneSource()
    p.SetResolution(*resolution)
    p.SetOutputPointsPrecision(1)  # double
    out = p
    if triangles:
        out = vtkTriangleFilter()
        out.SetInputConnection(p.GetOutputPort())
    out.Update()
    mesh = vtkPolyData()
    mesh.DeepCopy(out.GetOutput())
    mesh.GetPointData().Initialize()
    a, b = np.radians(30.0), np.radians(-20.0)
    turn = np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]]) @ \
        np.array([[np.cos(b), 0, np.sin(b)], [0, 1, 0], [-np.sin(b), 0, np.cos(b)]])
    x = vtkPoints()
    x.SetData(numpy_to_vtk(np.ascontiguousarray(points(mesh) @ turn.T), deep=1))
    mesh.SetPoints(x)
    return mesh


source = tilted_plane((7, 5), True)
target = tilted_plane((11, 13), False)
normal = unit(cell_normals(source)[:1])[0]
P = np.eye(3) - np.outer(normal, normal)
A = np.array([[1.0, 2.0, -0.5], [0.3, -1.0, 2.0], [0.7, 0.2, 1.5]])
b = np.array([0.5, -1.0, 2.0])


def linear_tangent(x):
    return (x @ A.T + b) @ P.T


with_field(source, "v", linear_tangent(points(source)))
f = tangents(target, source, "v", PointDataTarget=3)
u = output_array(f, "v")
exact = linear_tangent(points(target))
check(np.max(np.abs(u - exact)) < 1e-12 * np.max(np.abs(exact)),
      "plane: a linear tangent field stays exact at points (%.2e)" % np.max(np.abs(u - exact)))
check(f.GetOutput().GetCellData().GetArray("v") is not None, "plane: the point array goes to cells too")
uc = output_array(f, "v", True)
exact_cells = linear_tangent(centroids(target))
check(np.max(np.abs(uc - exact_cells)) < 1e-12 * np.max(np.abs(exact)),
      "plane: its cell means are exact (%.2e)" % np.max(np.abs(uc - exact_cells)))
check(np.max(output_array(f, "v_NormalPart")) < 1e-12 * np.max(np.abs(exact)),
      "plane: nothing to remove (%.2e)" % np.max(output_array(f, "v_NormalPart")))

# --- A circle's tangent field on two polylines --------------------------------
def circle(sides):
    p = vtkRegularPolygonSource()
    p.SetNumberOfSides(sides)
    p.SetRadius(1.0)
    p.SetGeneratePolygon(False)
    p.SetGeneratePolyline(True)
    p.Update()
    # One line cell per segment (the same as a polyline for the filter).
    out = vtkPolyData()
    out.DeepCopy(p.GetOutput())
    return out


def around(x):
    """The unit tangent of the circle at x's angle, times a varying speed."""
    r = unit(x)
    t = np.stack([-r[:, 1], r[:, 0], np.zeros(len(r))], axis=1)
    return (1.0 + 0.5 * r[:, 0:1]) * t


source = circle(50)
target = circle(73)
with_field(source, "t", around(points(source)))
plain = mortar(target, source, pieces=False)
f = tangents(target, source, "t")
u = output_array(f, "t")
u0 = output_array(plain, "t")
chords = np.array([points(target)[(i + 1) % 73] - points(target)[i] for i in range(73)])
d = np.zeros((73, 3))
for i in range(73):
    d[i] += chords[i]
    d[(i + 1) % 73] += chords[i]
scale = np.max(np.linalg.norm(u, axis=1))
across = normal_part(u, d, True)
across0 = normal_part(u0, d, True)
check(np.max(across) < ROUND_OFF * scale,
      "circle: the result is along the target's tangent (%.2e; plain %.2e)"
      % (np.max(across) / scale, np.max(across0) / scale))
exact = around(points(target))
error = np.sqrt(np.mean(np.sum((u - exact) ** 2, axis=1)))
error0 = np.sqrt(np.mean(np.sum((u0 - exact) ** 2, axis=1)))
check(error <= error0, "circle: error against the exact tangent %.3e, plain %.3e" % (error, error0))

# --- Large removed parts are said (over 10% of the field's magnitude) ---------
f, texts = observed_filter("WarningEvent")
source = sphere(24, 18)
with_field(source, "v", on_sphere(points(source)))
f.SetInputData(sphere(37, 29))
f.SetSourceData(source)
f.AddTangentArray("v")
f.Update()
check(not any("TangentArrays" in t for t in texts), "a tangent field on a fine pair: nothing said: %s" % texts)
f, texts = observed_filter("WarningEvent")
source = sphere(24, 18)
with_field(source, "v", on_sphere(points(source)) + 2.0 * unit(points(source)))
f.SetInputData(sphere(37, 29))
f.SetSourceData(source)
f.AddTangentArray("v")
f.Update()
said = [t for t in texts if "TangentArrays" in t]
check(len(said) == 1 and "'v' is not tangent to the Source" in said[0],
      "a radial part on the Source is said: %s" % said)
f, texts = observed_filter("WarningEvent")
source = sphere(6, 4)
with_field(source, "v", on_sphere(points(source)))
f.SetInputData(sphere(37, 29))
f.SetSourceData(source)
f.SetSurfaceReach(2.0)
f.SetMaximumNormalAngle(89.0)
f.AddTangentArray("v")
f.Update()
said = [t for t in texts if "TangentArrays" in t]
largest = np.nanmax(output_array(f, "v_NormalPart"))
check(len(said) == 1 and "'v' on Input had a normal part up to %f" % largest in said[0],
      "a coarse Source (6 x 4): Input's large normal part (%.3f) is said: %s" % (largest, said))

# --- Composite data, PreserveBounds, a kept operator --------------------------
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkThreshold  # noqa: E402


def halves(mesh):
    """Two blocks: the cells below and above z = 0.1 (their points copied on the cut)."""
    z = centroids(mesh)[:, 2]
    side = numpy_to_vtk((z > 0.1).astype(float), deep=1)
    side.SetName("side")
    copy = vtkPolyData()
    copy.DeepCopy(mesh)
    copy.GetCellData().AddArray(side)
    blocks = vtkMultiBlockDataSet()
    for i, (lo, hi) in enumerate(((-1.0, 0.5), (0.5, 2.0))):
        t = vtkThreshold()
        t.SetInputData(copy)
        t.SetInputArrayToProcess(0, 0, 0, 1, "side")
        t.SetLowerThreshold(lo)
        t.SetUpperThreshold(hi)
        t.Update()
        block = t.GetOutput().NewInstance()
        block.DeepCopy(t.GetOutput())
        block.GetCellData().RemoveArray("side")
        blocks.SetBlock(i, block)
    return blocks


source = sphere(24, 18)
target = sphere(37, 29)
with_field(source, "v", on_sphere(points(source)))
whole = output_array(tangents(target, source, "v"), "v")
f = tangents(target, halves(source), "v")
u = output_array(f, "v")
check(np.max(np.abs(u - whole)) < 1e-12 * np.max(np.abs(whole)),
      "composite Source: its blocks' points on the cut share their normals, the result is the "
      "whole Source's (%.2e)" % np.max(np.abs(u - whole)))
f = tangents(halves(target), source, "v")
for i in range(2):
    block = f.GetOutput().GetBlock(i)
    u = vtk_to_numpy(block.GetPointData().GetArray("v"))
    cells = vtk_to_numpy(block.GetCells().GetConnectivityArray()).reshape(-1, 3)
    x = vtk_to_numpy(block.GetPoints().GetData()).astype(float)
    area = 0.5 * np.cross(x[cells[:, 1]] - x[cells[:, 0]], x[cells[:, 2]] - x[cells[:, 0]])
    n = np.zeros_like(x)
    for k in range(3):
        np.add.at(n, cells[:, k], area)
    used = np.linalg.norm(n, axis=1) > 0
    normal = normal_part(u[used], n[used], False)
    check(np.max(normal) < ROUND_OFF * np.max(np.abs(u)),
          "composite Input block %d: the normal part (its own normals) is at round-off (%.2e)"
          % (i, np.max(normal)))

# PreserveBounds bounds the Cartesian components, then the normal part goes.
f = tangents(target, source, "v", PreserveBounds=True)
u = output_array(f, "v")
n = point_normals(target, cell_normals(target))
check(np.max(normal_part(u, n, False)) < ROUND_OFF * np.max(np.abs(u)),
      "PreserveBounds: the normal part is at round-off (%.2e)" % np.max(normal_part(u, n, False)))

# A kept operator (a time series' next step): the next field's result is a fresh filter's.
f = meshprojection.vtkMeshProjectionFilter()
f.SetInputData(target)
f.SetSourceData(source)
f.AddTangentArray("v")
f.Update()
source.GetPointData().RemoveArray("v")
with_field(source, "v", 2.0 * on_sphere(points(source)) + 0.3 * np.cross([1.0, 0, 0], points(source)))
f.Modified()
f.Update()
kept = output_array(f, "v")
fresh = output_array(tangents(target, source, "v"), "v")
check(np.max(np.abs(kept - fresh)) < 1e-10 * np.max(np.abs(fresh)),
      "kept operator: the next step's result is a fresh filter's (%.2e)" % np.max(np.abs(kept - fresh)))
check(np.max(normal_part(kept, n, False)) < ROUND_OFF * np.max(np.abs(kept)),
      "kept operator: the normal part is at round-off (%.2e)" % np.max(normal_part(kept, n, False)))

# --- Said by name: not 3 components; a volume target --------------------------
f, texts = observed_filter("WarningEvent")
source = sphere(12, 10)
with_field(source, "pair", np.ones((source.GetNumberOfPoints(), 2)))
f.SetInputData(sphere(15, 12))
f.SetSourceData(source)
f.AddTangentArray("pair")
f.Update()
check(any("'pair'" in t and "not 3" in t for t in texts),
      "a 2-component tangent array is said by name: %s" % texts)
check(f.GetOutput().GetPointData().GetArray("pair") is not None
      and f.GetOutput().GetPointData().GetArray("pair_NormalPart") is None,
      "... and projected as an ordinary array")

from vtkmodules.vtkImagingCore import vtkRTAnalyticSource  # noqa: E402
from vtkmodules.vtkFiltersCore import vtkArrayCalculator  # noqa: E402
f, texts = observed_filter("WarningEvent")
box = vtkRTAnalyticSource()
box.SetWholeExtent(0, 4, 0, 4, 0, 4)
calc = vtkArrayCalculator()
calc.SetInputConnection(box.GetOutputPort())
calc.AddCoordinateScalarVariable("x", 0)
calc.SetFunction("x*iHat + jHat")
calc.SetResultArrayName("v")
calc.Update()
box2 = vtkRTAnalyticSource()
box2.SetWholeExtent(0, 3, 0, 3, 0, 3)
box2.Update()
f.SetInputData(box2.GetOutput())
f.SetSourceData(calc.GetOutput())
f.AddTangentArray("v")
f.Update()
check(any("'v'" in t and "3D" in t for t in texts), "a volume target: said by name: %s" % texts)
check(f.GetOutput().GetPointData().GetArray("v") is not None, "... and projected as an ordinary array")

# A trace: a tilted sheet inside the volume keeps the part of the volume's
# (linear) vectors tangent to it, exactly.
sheet = tilted_plane((9, 7), True)
x = points(sheet) * 2.0 + 2.0
moved = vtkPoints()
moved.SetData(numpy_to_vtk(np.ascontiguousarray(x), deep=1))
sheet.SetPoints(moved)
f, texts = observed_filter("WarningEvent")
f.SetInputData(sheet)
f.SetSourceData(calc.GetOutput())
f.AddTangentArray("v")
f.Update()
u = vtk_to_numpy(f.GetOutput().GetPointData().GetArray("v")).astype(float)
exact = np.stack([x[:, 0], np.ones(len(x)), np.zeros(len(x))], axis=1) @ P.T
check(np.max(np.abs(u - exact)) < 1e-10 * np.max(np.abs(exact)),
      "trace: the volume's linear vectors' part tangent to a sheet inside it, exact (%.2e)"
      % np.max(np.abs(u - exact)))
check(not any("TangentArrays" in t for t in texts), "trace: nothing to say: %s" % texts)

finish()
