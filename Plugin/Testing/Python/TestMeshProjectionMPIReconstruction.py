"""vtkPMeshProjectionFilter with CellDataReconstruction on several MPI
processes (run under mpiexec with pvbatch --mpi --symmetric): every process
gets the serial result.

The gradient of a Source cell is fitted to the cells around it, which may
live on other processes: the gathering brings them along (the neighbour
layer, Parallel/SourceGather.cxx). Checked on every process, for 2D
triangles and 3D tetrahedra, Input and Source cut at random among the
processes (Input in slabs, Source at random), modes 1 (limited) and 2 (linear), to cells and to points:
 - a smooth cell field and one with a NaN hole equal the serial results
   (1e-12 of their range; the masks equal);
 - the gathering with the layer received more Source cells than without
   it (constant cell data): without those cells the gradients at the edge
   of a process's gathered part would not be the serial ones.
"""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE

from mpsupport import meshes, mpi
from mpsupport.mpi import add

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)
F = meshprojection.vtkMeshProjectionFilter


def centres(g, k):
    x = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, k)
    return x[conn].mean(axis=1)


def run(filter_class, target, source, mode):
    f = filter_class()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.SetCellDataReconstruction(mode)
    f.SetCellDataTarget(F.TO_POINTS_AND_CELLS)
    f.Update()
    return f


for dim in (2, 3):
    if dim == 2:
        target = meshes.grid(*meshes.triangles(23, (0, 0, 0), (1, 1, 0), 1), VTK_TRIANGLE)
        source = meshes.grid(*meshes.triangles(17, (-0.1, 0.05, 0), (0.93, 1.1, 0), 2), VTK_TRIANGLE)
        k = 3
    else:
        target = meshes.grid(*meshes.tetrahedra(9, (0, 0, 0), (1, 1, 1), 1, 0.2), VTK_TETRA)
        source = meshes.grid(*meshes.tetrahedra(7, (-0.1, 0.05, 0), (0.95, 1.1, 1.05), 2, 0.2), VTK_TETRA)
        k = 4
    mpi.numbered(target)
    c = centres(source, k)
    smooth = np.sin(3 * c[:, 0]) * np.cos(2 * c[:, 1]) + c[:, 2] ** 2
    holed = smooth.copy()
    holed[np.hypot(c[:, 0] - 0.4, c[:, 1] - 0.6) < 0.15] = np.nan
    add(source.GetCellData(), "smooth", smooth)
    add(source.GetCellData(), "holed", holed)
    span = float(np.ptp(smooth))

    # Input in slabs along x (a process needs only part of Source: the
    # layer matters), Source cut at random (its points copied on each side).
    tx = centres(target, k)[:, 0]
    lt = meshes.extract(target, np.minimum(size - 1, (tx * size).astype(int)) == rank)
    ls = meshes.extract(source, np.random.default_rng(21 + dim).integers(0, size, source.GetNumberOfCells()) == rank)
    for mode in (1, 2):
        serial = run(F, target, source, mode).GetOutput()
        parallel = run(meshprojection.vtkPMeshProjectionFilter, lt, ls, mode)
        out = parallel.GetOutput()
        for assoc in ("point", "cell"):
            ld = out.GetPointData() if assoc == "point" else out.GetCellData()
            sd = serial.GetPointData() if assoc == "point" else serial.GetCellData()
            if ld.GetNumberOfTuples() == 0:
                continue
            ids = vtk_to_numpy(ld.GetArray("origId"))
            mask = "vtkValidPointMask" if assoc == "point" else "vtkValidCellMask"
            check(np.array_equal(vtk_to_numpy(ld.GetArray(mask)), vtk_to_numpy(sd.GetArray(mask))[ids]),
                  "%dD mode %d: %s masks equal serial" % (dim, mode, assoc))
            for name in ("smooth", "holed"):
                lv = vtk_to_numpy(ld.GetArray(name))
                sv = vtk_to_numpy(sd.GetArray(name))[ids]
                same_nan = np.array_equal(np.isnan(lv), np.isnan(sv))
                fin = np.isfinite(sv)
                err = float(np.max(np.abs(lv[fin] - sv[fin]), initial=0.0)) / span
                check(same_nan and err <= 1e-12, "%dD mode %d: %s %s differs from serial by %.3g of its range"
                      % (dim, mode, assoc, name, err))
        if mode == 2:
            layered = parallel.GetGlobalReceivedSourceCells()
            plain = run(meshprojection.vtkPMeshProjectionFilter, lt, ls, 0).GetGlobalReceivedSourceCells()
            check(layered > plain, "%dD: the neighbour layer brings more cells (%d, without %d)"
                  % (dim, layered, plain))

check.finish("%d processes, reconstructed cell data" % size)
