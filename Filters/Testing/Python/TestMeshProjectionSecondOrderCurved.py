"""Curved second-order cells split finer (CurvedCellSubdivision, the lattice
of order 2L through each curved cell's isoparametric map), on Gmsh order-2
disks (boundary mid nodes on the circle) and balls:

    a. the Input's measure as the pieces measure it (the integral of 1 over
       an Input inside the Source) converges to the curved disk's as 1/L^2,
       within the stated bound sum |d_e| |e| / (4 L^2) over curved edges;
    b. at every level a linear field stays exact at every Input node (1e-9
       of its range), constant cell data stays constant, extensive totals
       are conserved over the covered part, and TargetIntegral_ equals
       SourceIntegral_ of a field on an Input that covers the Source;
    c. curved cells next to straight ones (Gmsh's disk and ball: the cells
       at the boundary curved, the others straight, the edges and faces
       between them refined on the curved side only) project the linear
       field exactly, with the front and brute force agreeing;
    d. level 1 is the split on the nodes (the property's effect: the measure
       differs from level 2's), and changing the level rebuilds a kept
       operator;
    e. curved 6-node triangles of a surface in 3D (a ball's boundary): the
       area nears 4 pi with the level, constant cell data stays constant;
    f. the fringe on a refined curved Input reaching beyond the Source (its
       rings read the refined simplices' parent nodes): the linear field
       exact at every valid node, every value finite;
    g. a curved mesh with hexahedra (not split finer) keeps level 1
       throughout, with one warning, and gives level 1's result.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid

import meshprojection
from mpsupport import gmshmeshes
from mpsupport.testing import check, finish, observed_filter


def linear(x):
    return 1.0 + 2.0 * x[:, 0] - 3.0 * x[:, 1] + 0.5 * x[:, 2]


def points_of(g):
    return vtk_to_numpy(g.GetPoints().GetData()).astype(float)


def scaled(g, s):
    out = vtkUnstructuredGrid()
    out.DeepCopy(g)
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(points_of(g) * s, deep=True))
    out.SetPoints(pts)
    return out


def with_arrays(g):
    g = scaled(g, 1.0)
    x = points_of(g)
    for name, values in (("Linear", linear(x)), ("One", np.ones(len(x)))):
        a = numpy_to_vtk(values, deep=True)
        a.SetName(name)
        g.GetPointData().AddArray(a)
    for name, value in (("Constant", 7.0), ("Total", 3.0)):
        a = numpy_to_vtk(np.full(g.GetNumberOfCells(), value), deep=True)
        a.SetName(name)
        g.GetCellData().AddArray(a)
    return g


def project(target, source, level, extensive=False, method=0, keep=None):
    f = keep or meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(keep is not None)
    f.SetCurvedCellSubdivision(level)
    f.SetSearchMethod(method)
    f.SetCellDataQuantity(1 if extensive else 0)
    f.Update()
    return f.GetOutput()


def field(out, name):
    return out.GetFieldData().GetArray(name).GetValue(0)


def curved_bound(g):
    """sum |d_e| |e| over the 6-node triangles' edges (each boundary edge once)."""
    x = points_of(g)
    seen = {}
    for c in range(g.GetNumberOfCells()):
        ids = [g.GetCell(c).GetPointId(k) for k in range(6)]
        for a, b, m in ((0, 1, 3), (1, 2, 4), (2, 0, 5)):
            key = tuple(sorted((ids[a], ids[b])))
            d = np.linalg.norm(x[ids[m]] - 0.5 * (x[ids[a]] + x[ids[b]]))
            seen[key] = d * np.linalg.norm(x[ids[b]] - x[ids[a]])
    return sum(seen.values())


def check_fields(name, out, source, everywhere=True):
    x = points_of(out)
    valid = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
    error = np.max(np.abs(vtk_to_numpy(out.GetPointData().GetArray("Linear")) - linear(x))[valid])
    error /= np.ptp(linear(x))
    check((valid.all() or not everywhere) and valid.any() and error <= 1e-9, "%s: linear field exact at every node (%.2g)" % (name, error))
    covered = vtk_to_numpy(out.GetCellData().GetArray("CoveredFraction")) > 1e-9
    constant = vtk_to_numpy(out.GetCellData().GetArray("Constant"))[covered]
    check(covered.any() and np.max(np.abs(constant - 7.0)) <= 1e-12,
          "%s: constant cell data stays 7 (%.3g off)" % (name, np.max(np.abs(constant - 7.0))))


# --- a, b: the curved disk's measure converges within the bound ---------------
disk = gmshmeshes.second_order("disk", 0.35)
source = with_arrays(scaled(gmshmeshes.second_order("disk", 0.25), 1.3))  # covers the Input
target = with_arrays(disk)
bound = curved_bound(disk)
measures = {}
for level in (1, 2, 3, 4, 8, 16):
    out = project(target, source, level)
    measures[level] = field(out, "TargetIntegral_One")
    if level <= 4:
        check_fields("disk, level %d" % level, out, source)
# The curved disk's measure: level 16's, extrapolated (its error ~ 1/16^2).
curved = measures[16] + (measures[16] - measures[8]) / 3.0
print("level  measure             |error| vs curved     bound sum|d||e|/(4L^2)  |measure - pi|")
for level in (1, 2, 3, 4, 8):
    error = abs(measures[level] - curved)
    print("%5d  %.15f  %.3e             %.3e              %.3e" %
          (level, measures[level], error, bound / (4 * level * level), abs(measures[level] - np.pi)))
    check(error <= bound / (4 * level * level),
          "level %d: measure within the bound (%.3g <= %.3g)" % (level, error, bound / (4 * level * level)))
for a, b in ((2, 4), (4, 8)):
    ratio = abs(measures[a] - curved) / abs(measures[b] - curved)
    check(3.0 <= ratio <= 5.0, "measure error falls as 1/L^2 from level %d to %d (%.2f)" % (a, b, ratio))
check(abs(measures[2] - np.pi) <= bound / 16 + 1e-4,
      "default level 2: measure within the bound of pi (%.3g)" % abs(measures[2] - np.pi))
check(measures[1] != measures[2], "level 1 (the polygon through the nodes) differs from level 2")
# The disk's boundary cells are curved, their inner neighbours straight
# (hanging lattice points on the edges they share): the front and brute
# force meet the same pieces.
front = project(target, source, 2)
brute = project(target, source, 2, method=1)
diff = np.max(np.abs(vtk_to_numpy(front.GetPointData().GetArray("Linear")) -
                     vtk_to_numpy(brute.GetPointData().GetArray("Linear"))))
gap = abs(field(brute, "TargetIntegral_One") - measures[2])
check(diff <= 1e-12 and gap <= 1e-13,
      "tri6 disk, level 2: front = brute force (%.3g, measures %.3g apart)" % (diff, gap))

# Integrals: an Input that covers the Source keeps its integral; extensive
# totals conserved over the covered part.
big = with_arrays(scaled(disk, 1.3))
small = with_arrays(gmshmeshes.second_order("disk", 0.25))
for level in (1, 2, 4):
    out = project(big, small, level)
    t, s = field(out, "TargetIntegral_Linear"), field(out, "SourceIntegral_Linear")
    check(abs(t - s) <= 1e-11 * abs(s), "level %d: TargetIntegral_ = SourceIntegral_ (%.3g)" % (level, abs(t - s) / abs(s)))
    out = project(big, small, level, extensive=True)
    total = np.nansum(vtk_to_numpy(out.GetCellData().GetArray("Total")))  # NaN: not covered
    expected = 3.0 * small.GetNumberOfCells()
    check(abs(total - expected) <= 1e-11 * expected,
          "level %d: extensive totals conserved (%.3g)" % (level, abs(total - expected) / expected))
    check_fields("disk onto a larger disk, level %d" % level, project(big, small, level), small,
                 everywhere=False)

# --- c. a tet10 ball: curved boundary cells next to straight ones -------------
ball = gmshmeshes.second_order("cube", 0.4)  # straight: every cell keeps its split
ball_source = with_arrays(gmshmeshes.second_order("cube", 0.3))
check_fields("straight tet10 cube, level 2", project(with_arrays(ball), ball_source, 2), ball_source)
try:
    sphere = gmshmeshes.second_order("unitball", 0.5)
except ValueError:
    sphere = None
if sphere is not None:
    src = with_arrays(scaled(gmshmeshes.second_order("unitball", 0.4), 1.3))
    front = project(with_arrays(sphere), src, 2)
    brute = project(with_arrays(sphere), src, 2, method=1)
    check_fields("tet10 ball, level 2", front, src)
    print("tet10 ball: %d cells, %d points" % (sphere.GetNumberOfCells(), sphere.GetNumberOfPoints()))
    diff = np.max(np.abs(vtk_to_numpy(front.GetPointData().GetArray("Linear")) -
                         vtk_to_numpy(brute.GetPointData().GetArray("Linear"))))
    check(diff <= 1e-12, "tet10 ball: front = brute force (%.3g)" % diff)

# --- e. curved 6-node triangles of a surface in 3D (the ball's boundary) -----
def shell(ball):
    """The boundary faces of a tet10 mesh as 6-node triangles (outward)."""
    from vtkmodules.vtkCommonDataModel import VTK_QUADRATIC_TRIANGLE
    faces = {}
    table = [((0, 1, 3), (4, 8, 7)), ((1, 2, 3), (5, 9, 8)), ((2, 0, 3), (6, 7, 9)),
             ((0, 2, 1), (6, 5, 4))]
    for c in range(ball.GetNumberOfCells()):
        ids = [ball.GetCell(c).GetPointId(k) for k in range(10)]
        for cs, ms in table:
            key = tuple(sorted(ids[k] for k in cs))
            faces.setdefault(key, []).append([ids[k] for k in cs] + [ids[k] for k in ms])
    g = vtkUnstructuredGrid()
    g.SetPoints(ball.GetPoints())
    for f in faces.values():
        if len(f) == 1:
            g.InsertNextCell(VTK_QUADRATIC_TRIANGLE, 6, f[0])
    return g


if sphere is not None:
    skin, skin_source = with_arrays(shell(sphere)), with_arrays(shell(gmshmeshes.second_order("unitball", 0.4)))
    areas = {}
    for level in (1, 2):
        out = project(skin, skin_source, level)
        areas[level] = field(out, "SourceIntegral_Constant (cell data)") / 7.0
        covered = vtk_to_numpy(out.GetCellData().GetArray("CoveredFraction")) > 1e-9
        constant = vtk_to_numpy(out.GetCellData().GetArray("Constant"))[covered]
        check(covered.any() and np.max(np.abs(constant - 7.0)) <= 1e-12,
              "sphere of 6-node triangles, level %d: constant cell data stays 7" % level)
    print("sphere of 6-node triangles: area %.6f (level 1), %.6f (level 2), 4 pi %.6f" %
          (areas[1], areas[2], 4 * np.pi))
    check(abs(areas[2] - 4 * np.pi) * 2.5 <= abs(areas[1] - 4 * np.pi),
          "sphere of 6-node triangles: level 2's area much nearer 4 pi than level 1's")

# --- d. a kept operator follows the level -----------------------------------
f = meshprojection.vtkMeshProjectionFilter()
one = field(project(target, source, 1, keep=f), "TargetIntegral_One")
two = field(project(target, source, 2, keep=f), "TargetIntegral_One")
check(one == measures[1] and two == measures[2], "the kept operator follows CurvedCellSubdivision")

# --- f. the fringe on a refined curved Input (a disk moved off it as Source) --
disk = gmshmeshes.second_order("disk", 0.35)
inner = with_arrays(gmshmeshes.moved(gmshmeshes.second_order("disk", 0.2), translate=(0.37, 0.21, 0)))
for level in (1, 2):
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(with_arrays(disk))
    f.SetSourceData(inner)
    f.SetCacheOperator(True)
    f.SetCurvedCellSubdivision(level)
    f.Update()
    out = f.GetOutput()
    check_fields("curved disk beyond a moved Source, level %d" % level, out, inner, everywhere=False)
    values = vtk_to_numpy(out.GetPointData().GetArray("Linear"))
    valid = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
    P = meshprojection.fringe_extension(f)
    aggregated = int((P.getnnz(axis=0) == 0).sum()) if P.shape[0] else 0
    print("curved disk beyond a moved Source, level %d: %d nodes aggregated" % (level, aggregated))
    check(np.isfinite(values[valid]).all() and aggregated > 0,
          "curved disk beyond a moved Source, level %d: the fringe aggregates, values finite" % level)

# --- g. curved hexahedra keep the whole mesh at level 1 ----------------------
hexes = gmshmeshes.second_order("hexes", 0.34, False, True)
x = points_of(hexes)
x += 0.04 * np.stack([np.sin(3 * x[:, 1]), np.sin(3 * x[:, 2]), np.sin(3 * x[:, 0])], 1)
bent = vtkUnstructuredGrid()
bent.DeepCopy(hexes)
bent_points = vtkPoints()
bent_points.SetData(numpy_to_vtk(x, deep=True))
bent.SetPoints(bent_points)
cube_source = with_arrays(gmshmeshes.second_order("cube", 0.3))
f, texts = observed_filter("WarningEvent")
f.SetInputData(with_arrays(bent))
f.SetSourceData(cube_source)
f.SetCurvedCellSubdivision(2)
f.Update()
said = [t for t in texts if "are not split finer" in t]
check(len(said) == 1 and "hexahedra" in said[0], "curved hex20 at level 2: one warning (%s)" % said)
plain = project(with_arrays(bent), cube_source, 1)
same = np.array_equal(vtk_to_numpy(f.GetOutput().GetPointData().GetArray("Linear")),
                      vtk_to_numpy(plain.GetPointData().GetArray("Linear")))
check(same, "curved hex20 at level 2: level 1's result")

finish()
