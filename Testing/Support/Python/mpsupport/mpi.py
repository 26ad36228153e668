"""What the MPI test and the MPI benchmark share (both run under
`mpiexec ... pvbatch --mpi --symmetric`): the controller and collectives
that work from Python. Their meshes are those of mpsupport.meshes."""
import os
import sys
import traceback

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
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


def begin():
    """A symmetric MPI test's start: start(), then its Checks. Returns
    (controller, rank, size, check); the test imports meshprojection after
    it (once MPI is up)."""
    controller, made_here = start()
    rank = controller.GetLocalProcessId()
    size = controller.GetNumberOfProcesses()
    return controller, rank, size, Checks(controller, made_here)


def add(data, name, values):
    """Adds `values` (a numpy array: one row per tuple) to `data` (point or
    cell data) as the array `name` (a deep copy, of values' type)."""
    a = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
    a.SetName(name)
    data.AddArray(a)


def messages(f):
    """The texts of the warnings and errors of the filter f (its executive's
    errors too), collected as they come: {"WarningEvent": [...],
    "ErrorEvent": [...]}. (The observers also keep VTK from printing them.)"""
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.vtkCommonCore import VTK_STRING
    texts = {"WarningEvent": [], "ErrorEvent": []}

    def observe(obj, event):
        @calldata_type(VTK_STRING)
        def collect(o, e, text):
            texts[event].append(str(text))
        obj.AddObserver(event, collect)
    for event in texts:
        observe(f, event)
    observe(f.GetExecutive(), "ErrorEvent")
    return texts


def message_hash(text):
    """A number for a message, the same on every process for the same words
    (the text after VTK's "(address): " header, without the white space
    around it)."""
    text = text.split("): ", 1)[-1].strip()
    return float(sum((i + 1) * ord(c) for i, c in enumerate(text)) % 1000003)


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


def numbered(g):
    """g with its original point and cell ids as arrays "origId" (extraction
    carries them: a process's part is compared with the serial result by them)."""
    from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray
    for data, n in ((g.GetPointData(), g.GetNumberOfPoints()), (g.GetCellData(), g.GetNumberOfCells())):
        a = numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True)
        a.SetName("origId")
        data.AddArray(a)
    return g


class Checks:
    """A symmetric MPI test's checks: each process records its failures (and
    prints them, with its rank); finish() counts them over the processes,
    prints the verdict on process 0 (`label`: "... all checks passed") and
    exits as the test runner expects."""

    def __init__(self, controller, made_here):
        self.controller = controller
        self.made_here = made_here
        self.rank = controller.GetLocalProcessId()
        self.failures = []

    def __call__(self, condition, what):
        if not condition:
            self.failures.append(what)
            print("FAILED on process %d: %s" % (self.rank, what), file=sys.stderr)

    def finish(self, label):
        size = self.controller.GetNumberOfProcesses()
        counts = allgather(self.controller, np.array([float(len(self.failures))]))
        bad = int(sum(counts[r][0] for r in range(size)))
        if self.rank == 0:
            print("%s: %s" % (label, "all checks passed" if bad == 0 else "%d check(s) failed" % bad))
        if self.made_here:
            self.controller.Finalize()
            sys.exit(1 if bad else 0)
        elif bad:
            sys.exit(1)  # (pvbatch finalizes its own; a SystemExit on success made it exit with 1)


def blocks_along_x(target, size):
    """Per cell of target, the process it goes to: blocks of as many cells
    along x (by the cells' centres), one per process."""
    from vtkmodules.vtkFiltersCore import vtkCellCenters
    centres = vtkCellCenters()
    centres.SetInputData(target)
    centres.Update()
    cx = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())[:, 0]
    n = target.GetNumberOfCells()
    return np.minimum((np.argsort(np.argsort(cx)) * size) // n, size - 1)
