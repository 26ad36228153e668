"""What the MPI test and the MPI benchmark share (both run under
`mpiexec ... pvbatch --mpi --symmetric`): the controller, collectives that
work from Python, and meshes of jittered grids built with numpy."""
import os
import sys
import traceback

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkFiltersCore import vtkExtractCells
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController


def _abort(kind, value, tb):
    # One process failing must end all (the others would wait in a collective).
    traceback.print_exception(kind, value, tb)
    sys.stderr.flush()
    os._exit(1)


def start():
    """The global controller (pvbatch --mpi sets it; else an MPI controller
    made here), with an exception on any process ending all of them.
    Returns (controller, made here: then the caller finalizes it)."""
    sys.excepthook = _abort
    controller = vtkMultiProcessController.GetGlobalController()
    if controller is not None:
        return controller, False
    from vtkmodules.vtkParallelMPI import vtkMPIController
    controller = vtkMPIController()
    controller.Initialize()
    vtkMultiProcessController.SetGlobalController(controller)
    return controller, True


def allreduce(controller, value, op=vtkCommunicator.MAX_OP):
    out = numpy_to_vtk(np.zeros(1), deep=True)
    controller.AllReduce(numpy_to_vtk(np.array([float(value)]), deep=True), out, op)
    return float(vtk_to_numpy(out)[0])


def allgather(controller, values):
    """Each process's 1D float array, to every process (a list by rank).
    (AllGatherV crashes from Python: a padded AllGather.)"""
    values = np.asarray(values, dtype=np.float64)
    size = controller.GetNumberOfProcesses()
    m = int(allreduce(controller, len(values)))
    padded = np.full(m + 1, np.nan)
    padded[0] = len(values)
    padded[1:len(values) + 1] = values
    recv = numpy_to_vtk(np.zeros(size * (m + 1)), deep=True)
    controller.AllGather(numpy_to_vtk(padded, deep=True), recv)
    everything = vtk_to_numpy(recv).reshape(size, m + 1)
    return [row[1:1 + int(row[0])].copy() for row in everything]


def grid(points, cells, cell_type):
    """A vtkUnstructuredGrid of one cell type from numpy arrays."""
    g = vtkUnstructuredGrid()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    g.SetPoints(p)
    ca = vtkCellArray()
    n = cells.shape[1]
    offsets = np.arange(0, n * len(cells) + 1, n, dtype=np.int64)
    ca.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
               numpy_to_vtkIdTypeArray(np.ascontiguousarray(cells, dtype=np.int64).ravel(), deep=True))
    g.SetCells(cell_type, ca)
    return g


def structured(n, lo, hi, dim, seed, jitter=0.25):
    """Points of an n^dim grid of [lo, hi]^dim (first axis slowest), interior
    ones jittered by up to `jitter` of the spacing, one axis after the other."""
    axes = [np.linspace(lo[d], hi[d], n + 1) for d in range(dim)]
    mesh = np.meshgrid(*axes, indexing="ij")
    x = np.zeros(((n + 1) ** dim, 3))
    for d in range(dim):
        x[:, d] = mesh[d].ravel()
    rng = np.random.default_rng(seed)
    h = (np.array(hi, float) - np.array(lo, float)) / n
    inner = np.all([(x[:, d] > lo[d] + 1e-12) & (x[:, d] < hi[d] - 1e-12) for d in range(dim)], axis=0)
    for d in range(dim):
        x[inner, d] += jitter * h[d] * rng.uniform(-1, 1, inner.sum())
    return x


def quads(n, lo, hi, seed, jitter=0.25):
    """Points and quads of a jittered n x n grid."""
    x = structured(n, lo, hi, 2, seed, jitter)
    v = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    return x, np.stack([v[:-1, :-1].ravel(), v[1:, :-1].ravel(), v[1:, 1:].ravel(), v[:-1, 1:].ravel()], 1)


def triangles(n, lo, hi, seed, jitter=0.25):
    """Points and triangles (two per square) of a jittered n x n grid."""
    x, q = quads(n, lo, hi, seed, jitter)
    return x, np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])


def _cube_corners(n):
    v = np.arange((n + 1) ** 3).reshape((n + 1,) * 3)
    return [v[i:n + i, j:n + j, k:n + k].ravel() for (i, j, k) in
            [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]]


def hexahedra(n, lo, hi, seed, jitter=0.25):
    """Points and hexahedra of a jittered n^3 grid."""
    return structured(n, lo, hi, 3, seed, jitter), np.stack(_cube_corners(n), 1)


def tetrahedra(n, lo, hi, seed, jitter=0.25):
    """Points and tetrahedra (six around the diagonal 0-6 of each cube,
    conforming) of a jittered n^3 grid."""
    x = structured(n, lo, hi, 3, seed, jitter)
    c = _cube_corners(n)
    tets = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]
    return x, np.concatenate([np.stack([c[a], c[b], c[d], c[e]], 1) for (a, b, d, e) in tets])


def extract(g, keep):
    """The cells of g where `keep` is true, as a vtkUnstructuredGrid."""
    e = vtkExtractCells()
    e.SetInputData(g)
    ids = np.nonzero(keep)[0].astype(np.int64)
    e.SetCellIds(ids.tolist(), len(ids))
    e.Update()
    out = vtkUnstructuredGrid()
    out.ShallowCopy(e.GetOutput())
    return out
