"""The fringe's measure, one definition for Python.Fringe, Python.FringeMPI
and Testing/Support/fringe_sweep.py.

The fields are a smooth one, sin(2x)cos(3y)+z^2 (its error at the fringe
is what the aggregation is for), and a linear one (exact at every valid
point). A valid point is interior when every cell around it is fully
covered: the fringe's errors are measured against the worst error at
interior points.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdList
from vtkmodules.vtkFiltersCore import vtkCellCenters

# A cell is fully covered when its CoveredFraction is above this.
FULLY_COVERED = 1 - 1e-9


def smooth(x):
    """sin(2x)cos(3y)+z^2 at the rows of x."""
    return np.sin(2 * x[:, 0]) * np.cos(3 * x[:, 1]) + x[:, 2] ** 2


def linear(x):
    """1 + 2x - 3y + 0.5z at the rows of x."""
    return 1 + 2 * x[:, 0] - 3 * x[:, 1] + 0.5 * x[:, 2]


def with_fields(mesh):
    """A copy of mesh with point arrays s (smooth), l (linear), cell array c (smooth at cell centres)."""
    g = mesh.NewInstance()
    g.DeepCopy(mesh)
    x = vtk_to_numpy(g.GetPoints().GetData())
    for name, f in (("s", smooth), ("l", linear)):
        a = numpy_to_vtk(f(x), deep=True)
        a.SetName(name)
        g.GetPointData().AddArray(a)
    centres = vtkCellCenters()
    centres.SetInputData(g)
    centres.Update()
    a = numpy_to_vtk(smooth(vtk_to_numpy(centres.GetOutput().GetPoints().GetData())), deep=True)
    a.SetName("c")
    g.GetCellData().AddArray(a)
    return g


def point_cells(mesh):
    """Per point of mesh, the ids of the cells around it."""
    ids = vtkIdList()
    around = []
    for p in range(mesh.GetNumberOfPoints()):
        mesh.GetPointCells(p, ids)
        around.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    return around


def fully_covered(cover, around):
    """Per point, whether every cell around it is fully covered (cover: CoveredFraction)."""
    return np.array([min(cover[c] for c in cells) > FULLY_COVERED for cells in around])


def project(target, source):
    """The fringe's run: source onto target with the default settings, cell
    data sent to points too, the operator kept (for its matrices and the
    extension); the filter, its output and the warnings it gave."""
    # (Imported here: Python.FringeMPI imports this module before MPI is up.)
    from mpsupport.testing import observed_filter
    f, texts = observed_filter("WarningEvent")
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetOutputIntersections(False)
    f.SetCellDataTarget(1)
    f.SetCacheOperator(True)
    f.Update()
    return f, f.GetOutput(), texts
