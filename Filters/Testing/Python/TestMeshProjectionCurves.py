"""Curves through the VTK filter, on pairs of Gmsh meshes of a circle, the
boundary of a square (corners), a B-spline in space and a curved interface
y = 0.2 sin(2 pi x) at two sizes, as two 2D subdomains meshed apart see it
(the classic mortar case). Checks:
front == brute force, the pieces tile every target segment, linear fields
exact on straight pieces (across the square's corners), second-order rates
on curves, conservation on the target, and a polyline cell."""
import math

import numpy as np

import meshprojection
from mpsupport import gmshmeshes
from mpsupport.testing import check, finish, mortar
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData


def smooth(x, y, z):
    return np.sin(2.0 * x) + y * y + 0.5 * z


def linear(x, y, z):
    return 1.0 + 2.0 * x - 3.0 * y + 0.5 * z


project = mortar  # the filter on two datasets (mpsupport.testing)


def points(mesh):
    return vtk_to_numpy(mesh.GetPoints().GetData())


def segments(mesh):
    return vtk_to_numpy(mesh.GetLines().GetConnectivityArray()).reshape(-1, 2)


def lengths(mesh):
    x = points(mesh)
    s = segments(mesh)
    return np.linalg.norm(x[s[:, 1]] - x[s[:, 0]], axis=1)


def values(output, name="f"):
    return vtk_to_numpy(output.GetPointData().GetArray(name))


# --- Front == brute force, tiling, every point valid -------------------------
for shape, h, closed in (("circle", 0.1, True), ("square", 0.07, True), ("spline", 0.1, False),
                         ("wave", 0.05, False)):
    target = gmshmeshes.curve(shape, h)
    source = gmshmeshes.with_point_field(gmshmeshes.curve(shape, 1.37 * h), "f", smooth)
    front = project(target, source)
    brute = project(target, source, brute=True)
    uf, ub = values(front.GetOutput()), values(brute.GetOutput())
    check(np.allclose(uf, ub, rtol=0, atol=1e-12), "%s: front == brute force (%g)" % (shape, np.max(np.abs(uf - ub))))
    check(front.GetOutput(1).GetNumberOfLines() == brute.GetOutput(1).GetNumberOfLines(),
          "%s: same pieces" % shape)
    pieces = front.GetOutput(1)
    covered = np.zeros(target.GetNumberOfCells())
    np.add.at(covered, vtk_to_numpy(pieces.GetCellData().GetArray("TargetCellId")),
              vtk_to_numpy(pieces.GetCellData().GetArray("Length")))
    ell = lengths(target)
    over = np.max((covered - ell) / ell)
    check(over < 1e-12, "%s: pieces never overlap (%g)" % (shape, over))
    if closed:
        under = np.max((ell - covered) / ell)
        check(under < 1e-12, "%s: pieces tile every segment (%g)" % (shape, under))
    mask = vtk_to_numpy(front.GetOutput().GetPointData().GetArray("vtkValidPointMask"))
    check(mask.all(), "%s: every point valid (%d of %d)" % (shape, mask.sum(), len(mask)))
    print("%-7s %4d <- %4d segments, %5d pieces" % (shape, target.GetNumberOfCells(), source.GetNumberOfCells(),
                                                    pieces.GetNumberOfLines()))

# --- Linear fields exact on straight pieces, across corners ------------------
target = gmshmeshes.curve("square", 0.07)
source = gmshmeshes.with_point_field(gmshmeshes.curve("square", 0.09), "f", linear)
out = project(target, source).GetOutput()
x = points(out)
error = np.max(np.abs(values(out) - linear(x[:, 0], x[:, 1], x[:, 2])))
check(error < 1e-12, "square: linear field exact across the corners (%g)" % error)

# --- Second order on curves --------------------------------------------------
for shape, h in (("circle", 0.2), ("spline", 0.2), ("wave", 0.1)):
    sizes = [h / 2 ** k for k in range(3)]
    errors = []
    for hh in sizes:
        out = project(gmshmeshes.curve(shape, hh), gmshmeshes.with_point_field(gmshmeshes.curve(shape, 1.37 * hh), "f", smooth)).GetOutput()
        x = points(out)
        e = values(out) - smooth(x[:, 0], x[:, 1], x[:, 2])
        errors.append(math.sqrt(np.mean(e * e)))
    rate = np.polyfit(np.log(sizes), np.log(errors), 1)[0]
    print("%-7s rms errors %s: rate %.2f" % (shape, " ".join("%.3e" % e for e in errors), rate))
    check(rate > 1.7, "%s: second-order rate (%.2f)" % (shape, rate))

# --- Conservation on the target, a polyline cell -----------------------------
target = gmshmeshes.curve("circle", 0.1)
source = gmshmeshes.with_point_field(gmshmeshes.curve("circle", 0.137), "f", lambda x, y, z: 2 + smooth(x, y, z))
out = project(target, source).GetOutput()
u = values(out)
s = segments(out)
integral = float(np.sum(lengths(out) * 0.5 * (u[s[:, 0]] + u[s[:, 1]])))
reported = out.GetFieldData().GetArray("TargetIntegral_f").GetValue(0)
check(abs(integral - reported) < 1e-12 * abs(integral), "circle: int u_t = TargetIntegral (%.15g, %.15g)" % (integral, reported))
# The same target as one VTK_POLY_LINE cell: the same values.
chain = [int(s[0, 0])]
remaining = {int(a): int(b) for a, b in s}
while len(chain) <= len(s):
    chain.append(remaining[chain[-1]])
polyline = vtkPolyData()
polyline.SetPoints(target.GetPoints())
cells = vtkCellArray()
cells.InsertNextCell(len(chain))
for p in chain:
    cells.InsertCellPoint(p)
polyline.SetLines(cells)
out_poly = project(polyline, source).GetOutput()
difference = np.max(np.abs(values(out_poly) - u))
check(difference < 1e-12, "circle as one polyline cell: the same values (%g)" % difference)
pieces = project(polyline, source).GetOutput(1)
check(set(vtk_to_numpy(pieces.GetCellData().GetArray("TargetCellId")).tolist()) == {0},
      "a polyline's pieces all name its one cell")

# --- The kept operator follows SurfaceReach ----------------------------------
# A line 0.01 beside the target: within the default reach, not within 0.05.
target = gmshmeshes.curve("wave", 0.05)
source_wave = gmshmeshes.with_point_field(gmshmeshes.curve("wave", 0.07), "f", smooth)
lifted = gmshmeshes.moved(source_wave, translate=(0, 0, 0.01))
f = meshprojection.vtkMeshProjectionFilter()  # CacheOperator on (default)
f.SetInputData(target)
f.SetSourceData(lifted)
valid = []
for reach in (0.5, 0.05, 0.5):
    f.SetSurfaceReach(reach)
    f.Update()
    valid.append(int(vtk_to_numpy(f.GetOutput().GetPointData().GetArray("vtkValidPointMask")).sum()))
check(valid == [target.GetNumberOfPoints(), 0, target.GetNumberOfPoints()],
      "the kept operator follows SurfaceReach: %s valid points" % valid)

finish()
