"""Mass-weighted projection (DensityArray) on several MPI processes (run under
mpiexec with pvbatch --mpi --symmetric): Gmsh triangles that overlap in part,
Input split in blocks along x, Source at random. On every process, for its
points and cells, against the serial filter on the whole pair:
 - q (point density, to points and cells; cell density, to cells; with
   PreserveBounds; with a density that is zero on part of the Source, the
   guard, and with it Extrapolation) equals the serial value to 1e-10 of
   its range, invalid where the serial one is (the masks, the array's own
   mask);
 - TargetIntegral_q and SourceIntegral_q (those of rho q) equal the serial
   ones to 1e-12, and each other on cells.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkCellCenters

from mpsupport import gmshmeshes, meshes, mpi
from mpsupport.mpi import add

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)


def ids(g, data, name, n):
    a = numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True)
    a.SetName(name)
    data.AddArray(a)


def centres_of(g):
    c = vtkCellCenters()
    c.SetInputData(g)
    c.Update()
    return vtk_to_numpy(c.GetOutput().GetPoints().GetData())


def rho(x):
    return 1.0 + 0.5 * np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + x[:, 0]


def q(x):
    return np.cos(2 * x[:, 0]) + x[:, 1] ** 2


def run(filter_class, target, source, **props):
    f = filter_class()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.SetDensityArray("rho")
    for k, v in props.items():
        getattr(f, "Set" + k)(v)
    f.Update()
    return f.GetOutput()


moved = gmshmeshes.moved(gmshmeshes.planar(0.05), translate=(0.31, 0.17, 0))
target = meshes.extract(moved, np.ones(moved.GetNumberOfCells(), bool))
ids(target, target.GetPointData(), "origId", target.GetNumberOfPoints())
ids(target, target.GetCellData(), "origCell", target.GetNumberOfCells())
base = gmshmeshes.planar(0.065)
base = meshes.extract(base, np.ones(base.GetNumberOfCells(), bool))
xs = vtk_to_numpy(base.GetPoints().GetData())
cs = centres_of(base)


def source_with(points=None, cells=None):
    g = base.NewInstance()
    g.DeepCopy(base)
    for name, values in (points or {}).items():
        add(g.GetPointData(), name, values)
    for name, values in (cells or {}).items():
        add(g.GetCellData(), name, values)
    return g


cases = [
    ("point density", source_with(points={"rho": rho(xs), "q": q(xs)}), {"PointDataTarget": 3}),
    ("point density, bounds", source_with(points={"rho": rho(xs), "q": np.where(xs[:, 0] > 0.6, 1.0, 0.0)}),
     {"PreserveBounds": True}),
    ("cell density", source_with(cells={"rho": rho(cs), "q": q(cs)}), {"CellDataReconstruction": 1}),
    ("cell density, guard", source_with(cells={"rho": np.where(cs[:, 0] < 0.6, 0.0, cs[:, 0] - 0.5), "q": q(cs)}),
     {}),
    ("point density, guard", source_with(points={"rho": np.where(xs[:, 0] < 0.6, 0.0, xs[:, 0] - 0.5),
                                                 "q": q(xs)}), {}),
    ("point density, guard, extrapolated",
     source_with(points={"rho": np.where(xs[:, 0] < 0.6, 0.0, xs[:, 0] - 0.5), "q": q(xs)}), {"Extrapolation": 1}),
]
cx = centres_of(target)[:, 0]
n = target.GetNumberOfCells()
owner = np.minimum((np.argsort(np.argsort(cx)) * size) // n, size - 1)
part = meshes.extract(target, owner == rank)
for name, source, props in cases:
    keep = np.random.default_rng(3).integers(0, size, source.GetNumberOfCells()) == rank
    out = run(meshprojection.vtkPMeshProjectionFilter, part, meshes.extract(source, keep), **props)
    serial = run(meshprojection.vtkMeshProjectionFilter, target, source, **props)
    for which in ("TargetIntegral_q", "SourceIntegral_q"):
        for suffix in ("", " (cell data)"):
            mine = out.GetFieldData().GetArray(which + suffix)
            theirs = serial.GetFieldData().GetArray(which + suffix)
            if theirs is None:
                continue
            a, b = mine.GetValue(0), theirs.GetValue(0)
            check(abs(a - b) <= 1e-12 * abs(b), "%s: %s %.16g, serial %.16g" % (name, which + suffix, a, b))
    cells_case = source.GetCellData().GetArray("q") is not None
    if cells_case:
        t = out.GetFieldData().GetArray("TargetIntegral_q (cell data)").GetValue(0)
        s = out.GetFieldData().GetArray("SourceIntegral_q (cell data)").GetValue(0)
        check(abs(t - s) <= 1e-12 * abs(s), "%s: the integral of rho q kept (%.16g, %.16g)" % (name, t, s))
    for data, serial_data, idname, kind in ((out.GetPointData(), serial.GetPointData(), "origId", "Point"),
                                            (out.GetCellData(), serial.GetCellData(), "origCell", "Cell")):
        if serial_data.GetArray("q") is None:
            continue
        where = vtk_to_numpy(data.GetArray(idname))
        mine = vtk_to_numpy(data.GetArray("q"))
        theirs = vtk_to_numpy(serial_data.GetArray("q"))[where]
        check(np.array_equal(np.isnan(mine), np.isnan(theirs)), "%s, %ss: invalid where serial" % (name, kind))
        ok = ~np.isnan(theirs)
        scale = np.ptp(vtk_to_numpy(serial_data.GetArray("q"))[~np.isnan(vtk_to_numpy(serial_data.GetArray("q")))])
        off = np.max(np.abs(mine[ok] - theirs[ok]), initial=0.0) / scale
        check(off <= 1e-10, "%s, %ss: the serial values (%.2g of the range off)" % (name, kind, off))
        for mask in ("vtkValid%sMask" % kind, "vtkValid%sMask_q" % kind):
            m, s = data.GetArray(mask), serial_data.GetArray(mask)
            if s is None and m is None:
                continue
            # (A process's own mask exists when its arrays' masks differ there.)
            reference = vtk_to_numpy(s)[where] if s is not None else None
            got = vtk_to_numpy(m) if m is not None else vtk_to_numpy(data.GetArray("vtkValid%sMask" % kind))
            if reference is None:
                reference = vtk_to_numpy(serial_data.GetArray("vtkValid%sMask" % kind))[where]
            check(np.array_equal(got, reference), "%s: %s as serial" % (name, mask))
        if "guard" in name and rank == 0:
            print("%s, %ss: %d invalid of %d (serial)" % (name, kind, np.count_nonzero(np.isnan(theirs)), len(theirs)))

check.finish("%d processes, mass-weighted" % size)
