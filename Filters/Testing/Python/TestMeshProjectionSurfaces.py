"""Surfaces in 3D through the VTK filter, on pairs of Gmsh meshes: a sphere,
a cylinder, a torus, the faces of a box (triangles and quads), an open cap,
two flat patches with a gap, and a thin closed shell. Checks: front == brute
force, the pieces tile every target facet, linear fields exact on flat
parts (the box across its sharp edges), second-order rates on curved
surfaces, conservation on the target, nothing crossing the shell."""
import math

import numpy as np

import meshprojection
from mpsupport import gmshmeshes
from mpsupport.testing import check, covered_by_pieces, finish, mortar, observed_filter
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkReverseSense, vtkStripper


def smooth(x, y, z):
    return x * y + np.sin(2.0 * z)


def linear(x, y, z):
    return 1.0 + 2.0 * x - 3.0 * y + 0.5 * z


project = mortar  # the filter on two datasets (mpsupport.testing)


def points(mesh):
    return vtk_to_numpy(mesh.GetPoints().GetData())


def values(output, name):
    return vtk_to_numpy(output.GetPointData().GetArray(name))


def facets(mesh):
    offsets = vtk_to_numpy(mesh.GetPolys().GetOffsetsArray())
    connectivity = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray())
    return [connectivity[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]


def facet_areas(mesh):
    """Areas of the polygons (triangles or planar quads) in 3D."""
    x = points(mesh)
    areas = []
    for ids in facets(mesh):
        p = x[ids]
        s = np.zeros(3)
        for k in range(1, len(ids) - 1):
            s += np.cross(p[k] - p[0], p[k + 1] - p[0])
        areas.append(0.5 * np.linalg.norm(s))
    return np.array(areas)


def p1_integral(mesh, u):
    """Integral of the P1 field u over the facets (fanned from corner 0)."""
    x = points(mesh)
    total = 0.0
    for ids in facets(mesh):
        for k in range(1, len(ids) - 1):
            tri = [ids[0], ids[k], ids[k + 1]]
            a = 0.5 * np.linalg.norm(np.cross(x[tri[1]] - x[tri[0]], x[tri[2]] - x[tri[0]]))
            total += a * u[tri].mean()
    return total


def rms_error(output, f):
    x = points(output)
    e = values(output, "f") - f(x[:, 0], x[:, 1], x[:, 2])
    return math.sqrt(np.mean(e * e)), float(np.max(np.abs(e)))


# --- Front == brute force, pieces tiling the facets, on every shape ---------
for shape, h, closed in (("sphere", 0.2, True), ("cylinder", 0.2, False), ("torus", 0.15, True),
                         ("box", 0.2, False), ("cap", 0.15, False), ("shell", 0.2, True)):
    target = gmshmeshes.surface(shape, h, 6)
    source = gmshmeshes.with_point_field(gmshmeshes.surface(shape, 1.3 * h, 5), "f", smooth)
    front = project(target, source)
    brute = project(target, source, brute=True)
    uf = values(front.GetOutput(), "f")
    ub = values(brute.GetOutput(), "f")
    check(np.allclose(uf, ub, rtol=0, atol=1e-12), "%s: front == brute force (%g)" % (shape, np.max(np.abs(uf - ub))))
    check(front.GetOutput(1).GetNumberOfCells() == brute.GetOutput(1).GetNumberOfCells(),
          "%s: same pieces (%d, %d)" % (shape, front.GetOutput(1).GetNumberOfCells(), brute.GetOutput(1).GetNumberOfCells()))
    covered = covered_by_pieces(front, target)
    areas = facet_areas(target)
    # Never more than the facet; all of it where the surface is smooth and
    # closed (the images of the source facets tile it). At a curved rim
    # (cylinder, cap) the two meshes' chords differ: slivers stay uncovered.
    over = np.max((covered - areas) / areas)
    check(over < 1e-12, "%s: pieces overlap (%g)" % (shape, over))
    if closed or shape == "box":
        under = np.max((areas - covered) / areas)
        check(under < 1e-12, "%s: pieces tile every facet (%g)" % (shape, under))
    mask = vtk_to_numpy(front.GetOutput().GetPointData().GetArray("vtkValidPointMask"))
    check(mask.all(), "%s: every point valid (%d of %d)" % (shape, mask.sum(), len(mask)))
    print("%-8s %5d <- %5d facets, %6d pieces, uncovered %.2e of the area" % (
        shape, target.GetNumberOfCells(), source.GetNumberOfCells(), front.GetOutput(1).GetNumberOfCells(),
        1 - covered.sum() / areas.sum()))

# --- Linear fields exact on flat faces, across sharp edges, quads ----------
for quads_target, quads_source in ((False, False), (False, True), (True, False)):
    target = gmshmeshes.surface("box", 0.17, 6, quads=quads_target)
    source = gmshmeshes.with_point_field(gmshmeshes.surface("box", 0.23, 5, quads=quads_source), "f", linear)
    out = project(target, source).GetOutput()
    x = points(out)
    error = np.max(np.abs(values(out, "f") - linear(x[:, 0], x[:, 1], x[:, 2])))
    check(error < 1e-11, "box (quads: target %s, source %s): linear field exact (%g)" % (quads_target, quads_source, error))

# --- Second order on curved surfaces ----------------------------------------
# Gmsh's meshes at two sizes are not nested: the rate is the slope of the
# errors of three sizes (least squares in log-log).
for shape, h in (("sphere", 0.2), ("torus", 0.16), ("cap", 0.15)):
    errors = []
    sizes = [h / 2 ** level for level in range(3)]
    for hh in sizes:
        target = gmshmeshes.surface(shape, hh, 6)
        source = gmshmeshes.with_point_field(gmshmeshes.surface(shape, 1.3 * hh, 5), "f", smooth)
        errors.append(rms_error(project(target, source, pieces=False).GetOutput(), smooth))
    rate = np.polyfit(np.log(sizes), np.log([e[0] for e in errors]), 1)[0]
    print("%-8s rms errors %s: rate %.2f" % (shape, " ".join("%.3e" % e[0] for e in errors), rate))
    check(rate > 1.7, "%s: second-order rate (%.2f)" % (shape, rate))

# --- Conservation on the target ---------------------------------------------
# A positive field (a pressure, a heat flux).
target = gmshmeshes.surface("torus", 0.15, 6)
source = gmshmeshes.with_point_field(gmshmeshes.surface("torus", 0.2, 5), "f", lambda x, y, z: 2.0 + smooth(x, y, z))
f = project(target, source)
out = f.GetOutput()
target_integral = p1_integral(out, values(out, "f"))
field = out.GetFieldData()
projected = field.GetArray("TargetIntegral_f")
own = field.GetArray("SourceIntegral_f")
check(projected is not None and own is not None, "the integrals are reported in the field data")
if projected is not None and own is not None:
    check(abs(target_integral - projected.GetValue(0)) < 1e-10 * (1 + abs(target_integral)),
          "torus: int u_t = int of the projected source field (%.15g, %.15g)" % (target_integral, projected.GetValue(0)))
    source_integral = p1_integral(source, values(source, "f"))
    check(abs(own.GetValue(0) - source_integral) < 1e-10 * (1 + abs(source_integral)),
          "torus: the source's own integral (%.15g, %.15g)" % (own.GetValue(0), source_integral))
    # The two facetizations differ in area: the integrals differ too ...
    print("torus: integral over the target %.10f, over the source %.10f" % (target_integral, source_integral))
    check(abs(target_integral - source_integral) > 1e-4 * abs(source_integral), "torus: the facetizations' integrals differ")
    # ... unless the projection is scaled to the source's integral.
    g = meshprojection.vtkMeshProjectionFilter()
    g.SetInputData(target)
    g.SetSourceData(source)
    g.SetConserveSourceIntegral(True)
    g.Update()
    scaled = p1_integral(g.GetOutput(), values(g.GetOutput(), "f"))
    check(abs(scaled - source_integral) < 1e-10 * (1 + abs(source_integral)),
          "torus, ConserveSourceIntegral: int u_t = the source's own integral (%.15g, %.15g)" % (scaled, source_integral))
    reported = g.GetOutput().GetFieldData().GetArray("TargetIntegral_f").GetValue(0)
    check(abs(reported - source_integral) < 1e-10 * (1 + abs(source_integral)), "torus, ConserveSourceIntegral: reported")

# A field of zero mean (a fluctuation): its two integrals are round-off,
# whose ratio means nothing, so ConserveSourceIntegral leaves it unscaled
# (the values bit for bit those without it) and says why.
u = values(source, "f")
area = p1_integral(source, np.ones_like(u))
fluctuation = numpy_to_vtk(u - p1_integral(source, u) / area, deep=True)
fluctuation.SetName("df")
source.GetPointData().AddArray(fluctuation)
plain = project(target, source).GetOutput()
g, said = observed_filter("WarningEvent")
g.SetInputData(target)
g.SetSourceData(source)
g.SetConserveSourceIntegral(True)
g.Update()
own = g.GetOutput().GetFieldData().GetArray("SourceIntegral_df").GetValue(0)
check(abs(own) < 1e-12 * area * np.abs(u).max(), "torus, zero-mean field: its Source integral is round-off (%.3g)" % own)
check(np.array_equal(values(g.GetOutput(), "df"), values(plain, "df")),
      "torus, zero-mean field, ConserveSourceIntegral: the unscaled values")
scale = values(g.GetOutput(), "f") / values(plain, "f")
check(np.ptp(scale) < 1e-12 and abs(scale[0] - 1) > 1e-6,
      "torus, the same run: f (not of zero mean) scaled by one factor (%.15g)" % scale[0])
check(sum("df (component 0) is not scaled" in w and "zero to round-off" in w for w in said) == 1,
      "torus, zero-mean field: one warning says it is not scaled (%r)" % said)
source.GetPointData().RemoveArray("df")

# --- Partial coverage: the integrals over the covered parts -----------------
# Input the whole sphere, Source only the cap above z = 0.3: SourceIntegral
# is the source field's over the part of the Source the pieces cover.
target = gmshmeshes.surface("sphere", 0.15, 6)
source = gmshmeshes.with_point_field(gmshmeshes.surface("cap", 0.2, 5), "f", lambda x, y, z: 2.0 + smooth(x, y, z))
for conserve in (False, True):
    g = meshprojection.vtkMeshProjectionFilter()
    g.SetInputData(target)
    g.SetSourceData(source)
    g.SetFillWithNaN(False)
    g.SetFillValue(-999.0)
    g.SetConserveSourceIntegral(conserve)
    g.Update()
    out = g.GetOutput()
    own = out.GetFieldData().GetArray("SourceIntegral_f").GetValue(0)
    projected = out.GetFieldData().GetArray("TargetIntegral_f").GetValue(0)
    ratio = projected / own
    if conserve:
        check(abs(ratio - 1) < 1e-12, "cap onto sphere, ConserveSourceIntegral: the integrals agree (%.15g)" % ratio)
    else:
        check(0 < abs(ratio - 1) < 0.01, "cap onto sphere: the covered parts' integrals within 1%% (%.6f)" % ratio)
    mask = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask"))
    u = values(out, "f")
    check(0 < mask.sum() < len(mask) and np.all(u[mask == 0] == -999.0),
          "cap onto sphere (conserve %s): uncovered points keep the fill value" % conserve)

# --- Two planar patches in parallel planes: the 2D case (compared in the
# Input's plane at any distance, with a warning), so the values are exact ---
target = gmshmeshes.surface("patch0", 0.1, 6)
source = gmshmeshes.with_point_field(gmshmeshes.surface("patch0.01", 0.13, 5), "f", linear)
out = project(target, source).GetOutput()
x = points(out)
error = np.max(np.abs(values(out, "f") - linear(x[:, 0], x[:, 1], 0.01)))
check(error < 1e-11, "planar patches 0.01 apart: the source's linear field exact (%g)" % error)

# --- Extensive cell data from a planar mesh in a vertical plane: the totals
# (their densities use the cells' true areas, not those of their shadow on z = 0)
source = gmshmeshes.moved(gmshmeshes.surface("patch0", 0.1, 6), rotate_x=90)
mass = numpy_to_vtk(np.ones(source.GetNumberOfCells()), deep=True)
mass.SetName("mass")
source.GetCellData().AddArray(mass)
out = project(gmshmeshes.moved(gmshmeshes.surface("patch0", 0.13, 5), rotate_x=90), source, CellDataQuantity=1).GetOutput()
total = vtk_to_numpy(out.GetCellData().GetArray("mass")).sum()
check(abs(total - source.GetNumberOfCells()) < 1e-9, "vertical plane, extensive cell data: total kept (%.12g)" % total)

# --- Two curved patches with a gap of 0.01 -----------------------------------
target = gmshmeshes.surface("arc1.0", 0.1, 6)
source = gmshmeshes.with_point_field(gmshmeshes.surface("arc1.01", 0.13, 5), "f", linear)
out = project(target, source).GetOutput()
mask = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask"))
check(mask.all(), "curved patches 0.01 apart, within reach: every point valid (%d of %d)" % (mask.sum(), len(mask)))
x = points(out)
# The source's values at the radius 1.01 above each target point.
error = np.max(np.abs(values(out, "f") - linear(1.01 * x[:, 0], 1.01 * x[:, 1], x[:, 2])))
check(error < 1e-2, "curved patches: the source's field across the gap (%g; O(h^2) from the curvature)" % error)
out = project(target, source, SurfaceReach=0.05).GetOutput()  # 0.05 x about 0.1 < 0.01
mask = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask"))
check(mask.sum() == 0, "curved patches beyond reach: nothing meets (%d valid)" % mask.sum())

# --- Facing surfaces: NormalOrientation --------------------------------------
target = gmshmeshes.surface("sphere", 0.15, 6)
source = gmshmeshes.with_point_field(gmshmeshes.surface("sphere", 0.2, 5), "f", smooth)
flip = vtkReverseSense()  # the source's cells reversed: its facets face inward
flip.SetInputData(source)
flip.ReverseCellsOn()
flip.Update()
inward = flip.GetOutput()
reference = values(project(target, source).GetOutput(), "f")
for orientation, expected in ((0, 0), (1, target.GetNumberOfPoints()), (2, target.GetNumberOfPoints())):
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(inward)
    f.SetNormalOrientation(orientation)
    f.Update()
    out = f.GetOutput()
    mask = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask"))
    check(mask.sum() == expected, "inward source, NormalOrientation %d: %d valid points" % (orientation, mask.sum()))
    if expected:
        difference = np.max(np.abs(values(out, "f") - reference))
        check(difference < 1e-12, "inward source, NormalOrientation %d: the outward result (%g)" % (orientation, difference))

# --- Triangle strips (every other one runs the other way) and meshes that
# are not consistently oriented -------------------------------------------------
strips = vtkStripper()
strips.SetInputData(source)
strips.Update()
stripped = strips.GetOutput()
check(stripped.GetNumberOfStrips() > 0, "the source as triangle strips (%d)" % stripped.GetNumberOfStrips())
out = project(target, stripped).GetOutput()
difference = np.max(np.abs(values(out, "f") - reference))
check(difference < 1e-12, "the source as triangle strips: the same values (%g)" % difference)
cells = facets(source)
polys = vtkCellArray()
for i, ids in enumerate(cells):
    polys.InsertNextCell(len(ids))
    for p in (ids if i % 2 else ids[::-1]):
        polys.InsertCellPoint(int(p))
mixed = vtkPolyData()
mixed.SetPoints(source.GetPoints())
mixed.SetPolys(polys)
mixed.GetPointData().ShallowCopy(source.GetPointData())
f, warnings = observed_filter("WarningEvent")
f.SetInputData(target)
f.SetSourceData(mixed)
f.Update()
check(any("not consistently oriented" in w for w in warnings), "a source of mixed orientation is reported: %r" % warnings)
f.SetNormalOrientation(2)
f.Update()
difference = np.max(np.abs(values(f.GetOutput(), "f") - reference))
check(difference < 1e-12, "a source of mixed orientation with NormalOrientation Any: the same values (%g)" % difference)

# --- Nothing crosses a thin shell --------------------------------------------
target = gmshmeshes.surface("shell", 0.12, 6)
source = gmshmeshes.with_point_field(gmshmeshes.surface("shell", 0.15, 5), "f",
                                 lambda x, y, z: np.where(x * x + y * y + z * z > 0.985 ** 2, 1.0, -1.0))
out = project(target, source).GetOutput()
x = points(out)
side = np.where(np.sum(x * x, axis=1) > 0.985 ** 2, 1.0, -1.0)
error = np.max(np.abs(values(out, "f") - side))
check(error < 1e-12, "shell 0.03 thick: each side keeps its own value (%g)" % error)

finish()
