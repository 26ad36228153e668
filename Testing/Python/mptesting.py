"""Helpers shared by the Python tests: sample data, exact P1 integrals, image comparison."""
import os
import sys

DATA = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "Data")
BASELINES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "Baseline")

failures = []


def check(condition, what):
    """Record a failed check and go on, so one run shows every problem."""
    if not condition:
        failures.append(what)
        print("FAILED: " + what, file=sys.stderr)


def finish():
    if failures:
        print("%d check(s) failed" % len(failures), file=sys.stderr)
        sys.exit(1)
    print("all checks passed")
    sys.exit(0)


def read(name):
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(DATA, name))
    reader.Update()
    return reader.GetOutput()


def integral(grid, name, component=0):
    """Exact integral of a P1 point array over a triangle mesh (numpy, no VTK filter)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    x = vtk_to_numpy(grid.GetPoints().GetData())
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 3)
    u = vtk_to_numpy(grid.GetPointData().GetArray(name))
    if u.ndim > 1:
        u = u[:, component]
    a, b, c = x[cells[:, 0]], x[cells[:, 1]], x[cells[:, 2]]
    area = 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    return float(np.sum(area * u[cells].sum(axis=1) / 3.0)), float(area.sum())


def compare_image(png, baseline_name, temp_dir, threshold=10):
    """Compare a PNG against Baseline/<baseline_name> (alternates _1, _2 allowed)."""
    from vtkmodules.vtkTestingRendering import vtkTesting
    testing = vtkTesting()
    for argument in ("-V", os.path.join(BASELINES, baseline_name), "-T", temp_dir):
        testing.AddArgument(argument)
    return testing.RegressionTest(png, threshold) == vtkTesting.PASSED
