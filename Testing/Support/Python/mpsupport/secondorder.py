"""What the second-order tests share (Python.SecondOrder, SecondOrderSpace):
copies of a mesh with other points or cell types, the fields they give
their Sources, the projection and its arrays."""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy


def linear(x):
    """1 + 2x - 3y + 0.5z at the rows of x."""
    return 1.0 + 2.0 * x[:, 0] - 3.0 * x[:, 1] + 0.5 * x[:, 2]


def points_of(g):
    """g's points as numpy (its own array: writing to it moves them)."""
    return vtk_to_numpy(g.GetPoints().GetData())


def copy_grid(g, transform=None, types=None, cell=None):
    """A copy of g without arrays: its points through `transform`, each
    cell's type replaced (types: {old: new}) or the cell through
    cell(type, ids) -> (type, ids)."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
    out = vtkUnstructuredGrid()
    points = vtkPoints()
    x = points_of(g).copy()
    points.SetData(numpy_to_vtk(transform(x) if transform else x, deep=True))
    out.SetPoints(points)
    out.Allocate(g.GetNumberOfCells())
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        t, kept = g.GetCellType(c), [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
        t = types.get(t, t) if types else t
        if cell:
            t, kept = cell(t, kept)
        out.InsertNextCell(t, len(kept), kept)
    return out


def with_fields(g, fields):
    """A copy of g (copy_grid) with the point arrays of `fields` ((name,
    f(x)) pairs, in that order) and the cell array Constant (7)."""
    g = copy_grid(g)
    x = points_of(g)
    for name, f in fields:
        a = numpy_to_vtk(np.ascontiguousarray(f(x)), deep=True)
        a.SetName(name)
        g.GetPointData().AddArray(a)
    c = numpy_to_vtk(np.full(g.GetNumberOfCells(), 7.0), deep=True)
    c.SetName("Constant")
    g.GetCellData().AddArray(c)
    return g


def project(target, source, filter_class=None, **properties):
    """The output of a filter of filter_class (vtkMeshProjectionFilter
    unless told: vtkPMeshProjectionFilter on MPI processes) on target and
    source, with any property by name (CacheOperator=False calls
    SetCacheOperator(False))."""
    import meshprojection
    f = (filter_class or meshprojection.vtkMeshProjectionFilter)()
    f.SetInputData(target)
    f.SetSourceData(source)
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f.GetOutput()


def point_array(out, name):
    """The point array `name` of out, as numpy."""
    return vtk_to_numpy(out.GetPointData().GetArray(name))
