"""vtkMeshProjectionFilter from plain VTK Python (/usr/bin/python3 with the build's
python directory on PYTHONPATH): numbers on the sample L-shape with a hole."""
import math

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkUnstructuredGrid

from meshprojection import vtkMeshProjectionFilter
from mpsupport.testing import _cells, cell_measures, check, finish, integral, read

source = read("lshape_source.vtu")
target = read("lshape_target.vtu")

f = vtkMeshProjectionFilter()
check(f.GetSearchMethod() == vtkMeshProjectionFilter.ADVANCING_FRONT, "default search method")
check(not f.GetOutputIntersections(), "OutputIntersections off by default")
check(f.GetFillWithNaN() and f.GetFillValue() == 0, "fill defaults")
f.SetInputData(target)
f.SetSourceData(source)
f.OutputIntersectionsOn()
f.Update()
out = f.GetOutput()
pd = out.GetPointData()

x = vtk_to_numpy(out.GetPoints().GetData())
linear = vtk_to_numpy(pd.GetArray("Linear"))
velocity = vtk_to_numpy(pd.GetArray("Velocity"))
err = np.max(np.abs(linear - (1 + 2 * x[:, 0] - 3 * x[:, 1])))
check(err < 1e-12, "linear field reproduced (max error %g)" % err)
check(velocity.shape == (target.GetNumberOfPoints(), 3), "vector field keeps 3 components")
err = np.max(np.abs(velocity[:, :2] - np.c_[-(x[:, 1] - 1), x[:, 0] - 1]))
check(err < 1e-12, "rotation field reproduced (max error %g)" % err)
check(pd.GetArray("TargetId") is not None, "Input's own arrays are kept")
check(np.all(vtk_to_numpy(pd.GetArray("vtkValidPointMask")) == 1), "all points valid")

for name in ("Smooth", "Linear"):
    s_int, s_area = integral(source, name)
    t_int, t_area = integral(out, name)
    check(abs(s_int - t_int) <= 1e-13 * abs(s_int), "%s conserved: %r vs %r" % (name, s_int, t_int))
check(abs(f.GetCoveredMeasure() - 2.91) < 1e-12, "covered area %r" % f.GetCoveredMeasure())

polygons = f.GetOutputDataObject(1)
check(isinstance(polygons, vtkPolyData), "output 1 is vtkPolyData")
areas = vtk_to_numpy(polygons.GetCellData().GetArray("Area"))
check(len(areas) == f.GetNumberOfIntersections(), "one polygon per intersection")
check(abs(areas.sum() - 2.91) < 1e-12, "polygons tile the target")
tcell = vtk_to_numpy(polygons.GetCellData().GetArray("TargetCellId"))
scell = vtk_to_numpy(polygons.GetCellData().GetArray("SourceCellId"))
check(tcell.max() < target.GetNumberOfCells() and scell.max() < source.GetNumberOfCells(), "cell ids in range")

# Advancing front == brute force.
brute = vtkMeshProjectionFilter()
brute.SetInputData(target)
brute.SetSourceData(source)
brute.SetSearchMethodToBruteForce()
brute.OutputIntersectionsOn()
brute.Update()
bpoly = brute.GetOutputDataObject(1)
pairs_front = set(zip(tcell.tolist(), scell.tolist()))
pairs_brute = set(zip(vtk_to_numpy(bpoly.GetCellData().GetArray("TargetCellId")).tolist(),
                      vtk_to_numpy(bpoly.GetCellData().GetArray("SourceCellId")).tolist()))
check(pairs_front == pairs_brute, "advancing front and brute force find the same pairs")
diff = np.max(np.abs(vtk_to_numpy(brute.GetOutput().GetPointData().GetArray("Smooth")) -
                     vtk_to_numpy(pd.GetArray("Smooth"))))
check(diff < 1e-13, "same projection (max difference %g)" % diff)
check(f.GetNumberOfIntersectionTests() < brute.GetNumberOfIntersectionTests() / 100,
      "front tests %d pairs, brute force %d" % (f.GetNumberOfIntersectionTests(),
                                                brute.GetNumberOfIntersectionTests()))

# A coarser target gets the L2 projection, not point samples: its error
# against the exact field is of the order of the target mesh, and the mean
# of the field over the domain is exactly that of the source.
smooth = vtk_to_numpy(pd.GetArray("Smooth"))
exact = np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + 0.5 * x[:, 0]
check(np.max(np.abs(smooth - exact)) < 0.05, "projection close to the analytic field")
check(math.isclose(integral(out, "Smooth")[0] / 2.91, integral(source, "Smooth")[0] / 2.91, rel_tol=1e-13),
      "mean value kept")

# NaN holes: SourceIntegral_ is the integral over the Source's finite part
# (the cells without a NaN corner; the cells with a NaN value), computed
# here with numpy; the projection conserves it (TargetIntegral_).
holed = vtkUnstructuredGrid()
holed.DeepCopy(source)
xs = vtk_to_numpy(holed.GetPoints().GetData())
u = vtk_to_numpy(holed.GetPointData().GetArray("Smooth"))  # (a view: written in place)
u[(xs[:, 0] > 1.2) & (xs[:, 1] < 0.6)] = np.nan
cells = _cells(holed)
area = cell_measures(holed)
mean = np.cos(xs[cells].mean(axis=1)[:, 0]) + 2.0
mean[np.arange(len(mean)) % 7 == 3] = np.inf
holed.GetCellData().AddArray(numpy_to_vtk(mean, deep=True))
holed.GetCellData().GetArray(holed.GetCellData().GetNumberOfArrays() - 1).SetName("Mean")
finite = np.isfinite(u[cells]).all(axis=1)
expected = {"Smooth": float(np.sum(area[finite] * u[cells[finite]].mean(axis=1))),
            "Mean (cell data)": float(np.sum(area[np.isfinite(mean)] * mean[np.isfinite(mean)]))}
g = vtkMeshProjectionFilter()
g.SetInputData(target)
g.SetSourceData(holed)
g.Update()
field = g.GetOutput().GetFieldData()
for name, value in expected.items():
    got = field.GetArray("SourceIntegral_" + name).GetValue(0)
    kept = field.GetArray("TargetIntegral_" + name).GetValue(0)
    check(abs(got - value) <= 1e-13 * abs(value), "NaN hole: SourceIntegral_%s %r, the finite part's %r" % (name, got, value))
    check(abs(kept - value) <= 1e-12 * abs(value), "NaN hole: TargetIntegral_%s %r, the finite part's %r" % (name, kept, value))
finish()
