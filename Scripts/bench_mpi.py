"""Time vtkPMeshProjectionFilter on several MPI processes, with what each
process holds, receives, sends and allocates.

    cd /work/main && PYTHONPATH=build/lib/python3/dist-packages:Testing/Python:Scripts \\
        mpiexec --allow-run-as-root --oversubscribe -n P pvbatch --mpi --symmetric \\
        Scripts/bench_mpi.py [--case tri|tet] [--partition blocks|random] [--scale S] \\
        [--repeat R] [--threads T] [--seed N]

Every process builds the same pair of meshes from jittered grids (the
builders of Testing/Python/TestMeshProjectionMPI.py, vectorised; no cell
inverted):
  * tri: about 10^6 target triangles of the unit square and a Source of
    about 0.8 x 10^6 triangles of a slightly shifted square;
  * tet: about 10^5 target tetrahedra of the unit cube and a Source of about
    0.8 x 10^5 tetrahedra of a slightly shifted cube;
(--scale S multiplies the cell counts by S, for quick tries), with a point
field (a sine) and a cell field on the Source. Both are partitioned alike:
blocks (equal contiguous slabs by the x of the cell centres) or random (each
cell to a random process, seeded); each process keeps its part
(vtkExtractCells) and deletes the whole meshes, so that its memory is what a
distributed run holds.

The filter (CacheOperator off, T threads per process: 1 by default, so that
P processes use P cores) is run R times (default 3), each after a Barrier;
a run's time is the maximum over the processes, the reported time the best
run. Memory: VmRSS before the filter ran, and the peak (VmHWM, reset before
each run through /proc/self/clear_refs) during the runs; "beyond" = peak -
before. CPU/wall: the process's CPU time in the best run over its wall
time (about the thread count when it computed or busy-waited in MPI all
along; less when it was preempted: check that the machine is otherwise idle,
the load average is printed). Stages (the filter's timers): input, search
(with the intersections), solve, and the rest of the process's time
(neighbours, locator, assembly, output, and in parallel the exchange of
Source cells and of shared rows). "Source cells received" is the local Source
the process works on after the exchange (its own cells that can meet its
Input included; 0 on one process: the serial filter). Process 0 prints
Markdown: one row per process, the global totals and a summary line
(processes, case, partition, time).
"""
import argparse
import ctypes
import gc
import os
import sys
import time
import traceback

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_STRING, vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE, vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkFiltersCore import vtkExtractCells
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController


def _abort(kind, value, tb):
    # One process failing must end all (the others would wait in a collective).
    traceback.print_exception(kind, value, tb)
    sys.stderr.flush()
    os._exit(1)


sys.excepthook = _abort
controller = vtkMultiProcessController.GetGlobalController()
ours = controller is None  # (pvbatch --mpi finalizes its own)
if ours:
    from vtkmodules.vtkParallelMPI import vtkMPIController
    controller = vtkMPIController()
    controller.Initialize()
    vtkMultiProcessController.SetGlobalController(controller)
rank = controller.GetLocalProcessId()
size = controller.GetNumberOfProcesses()

import meshprojection  # noqa: E402  (after MPI is up)


# ---- collectives ------------------------------------------------------------
def allreduce(value, op=vtkCommunicator.MAX_OP):
    out = numpy_to_vtk(np.zeros(1), deep=True)
    controller.AllReduce(numpy_to_vtk(np.array([float(value)]), deep=True), out, op)
    return float(vtk_to_numpy(out)[0])


def allgather(values):
    """Each process's 1D float array, to every process (a list by rank).
    (AllGatherV crashes from Python: a padded AllGather.)"""
    values = np.asarray(values, dtype=np.float64)
    m = int(allreduce(len(values)))
    padded = np.full(m + 1, np.nan)
    padded[0] = len(values)
    padded[1:len(values) + 1] = values
    recv = numpy_to_vtk(np.zeros(size * (m + 1)), deep=True)
    controller.AllGather(numpy_to_vtk(padded, deep=True), recv)
    everything = vtk_to_numpy(recv).reshape(size, m + 1)
    return [row[1:1 + int(row[0])].copy() for row in everything]


# ---- memory -----------------------------------------------------------------
def status_kb(key):
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return -1


def release():
    """Give freed memory back to the system (so VmRSS shows what is held)."""
    gc.collect()
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass


def reset_peak():
    """VmHWM := VmRSS (Linux >= 4.0); False if not allowed."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


# ---- meshes (vectorised) ------------------------------------------------------
def grid(points, cells, cell_type):
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
    ones jittered by up to `jitter` of the spacing."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    idx = np.indices((n + 1,) * dim).reshape(dim, -1).T
    h = (hi[:dim] - lo[:dim]) / n
    x = np.zeros((len(idx), 3))
    x[:, :dim] = lo[:dim] + idx * h
    inner = np.all((idx > 0) & (idx < n), axis=1)
    rng = np.random.default_rng(seed)
    x[inner, :dim] += jitter * h * rng.uniform(-1, 1, (int(inner.sum()), dim))
    return x


def triangles(n, lo, hi, seed):
    x = structured(n, lo, hi, 2, seed)
    v = np.arange((n + 1) ** 2).reshape(n + 1, n + 1)
    a, b, c, d = v[:-1, :-1].ravel(), v[1:, :-1].ravel(), v[1:, 1:].ravel(), v[:-1, 1:].ravel()
    return x, np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]), VTK_TRIANGLE


def tetrahedra(n, lo, hi, seed):
    # (Jitter 0.2, not the test's 0.25: that inverts a tetrahedron at these sizes.)
    x = structured(n, lo, hi, 3, seed, jitter=0.2)
    v = np.arange((n + 1) ** 3).reshape((n + 1,) * 3)
    c = [v[i:n + i, j:n + j, k:n + k].ravel() for (i, j, k) in
         [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]]
    # Six tetrahedra around the diagonal 0-6 of each cube (conforming).
    tets = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]
    return x, np.concatenate([np.stack([c[a], c[b], c[d], c[e]], 1) for (a, b, d, e) in tets]), VTK_TETRA


def mesh(kind, cells, lo, hi, seed):
    """About `cells` triangles / tetrahedra of the box [lo, hi], with a point
    field "f" and a cell field "g"; and the x of the cell centres."""
    if kind == "tri":
        n = max(2, int(round(np.sqrt(cells / 2.0))))
        x, conn, ctype = triangles(n, lo, hi, seed)
    else:
        n = max(2, int(round((cells / 6.0) ** (1.0 / 3))))
        x, conn, ctype = tetrahedra(n, lo, hi, seed)
    centres = x[conn].mean(axis=1)
    g = grid(x, conn, ctype)
    f = numpy_to_vtk(np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + 0.5 * x[:, 2], deep=True)
    f.SetName("f")
    g.GetPointData().AddArray(f)
    cf = numpy_to_vtk(np.cos(2 * centres[:, 0]) + centres[:, 1] * centres[:, 2] + centres[:, 1], deep=True)
    cf.SetName("g")
    g.GetCellData().AddArray(cf)
    return g, centres[:, 0].copy()


# ---- partitioning -------------------------------------------------------------
def owners(how, cx, seed):
    n = len(cx)
    if how == "blocks":
        order = np.argsort(cx, kind="stable")
        owner = np.empty(n, np.int64)
        owner[order] = np.minimum((np.arange(n) * size) // n, size - 1)
        return owner
    return np.random.default_rng(seed).integers(0, size, n)


def extract(g, keep):
    e = vtkExtractCells()
    e.SetInputData(g)
    ids = np.nonzero(keep)[0].astype(np.int64)
    e.SetCellIds(ids.tolist(), len(ids))
    e.Update()
    out = vtkUnstructuredGrid()
    out.ShallowCopy(e.GetOutput())
    return out


# ---- one run ------------------------------------------------------------------
class Messages:
    """Counts (and prints, with the process) the filter's warnings and errors."""

    def __init__(self):
        self.warnings = 0
        self.errors = 0

    def watch(self, f):
        f.AddObserver("WarningEvent", self._warning)
        f.AddObserver("ErrorEvent", self._error)

    def _warning(self, obj, event, data=None):
        self.warnings += 1
        print("process %d: filter warning: %s" % (rank, self._text(data)), file=sys.stderr, flush=True)

    def _error(self, obj, event, data=None):
        self.errors += 1
        print("process %d: filter ERROR: %s" % (rank, self._text(data)), file=sys.stderr, flush=True)

    @staticmethod
    def _text(data):
        # "Warning: In file, line N\nclass (0x...): message\n\n": the message.
        lines = [x for x in str(data).splitlines() if x.strip()]
        return " ".join(lines[1:] or lines)


for _method in ("_warning", "_error"):
    # The message text as the third argument (a char*).
    getattr(Messages, _method).CallDataType = VTK_STRING


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--case", choices=("tri", "tet"), default="tri")
    parser.add_argument("--partition", choices=("blocks", "random"), default="blocks")
    parser.add_argument("--scale", type=float, default=1.0, help="cell counts times S (default 1)")
    parser.add_argument("--repeat", type=int, default=3, help="runs, the best reported (default 3)")
    parser.add_argument("--threads", type=int, default=1, help="threads per process (default 1; 0: every core)")
    parser.add_argument("--seed", type=int, default=11, help="of the random partitioning (default 11)")
    args = parser.parse_args()

    with open("/proc/loadavg") as f:
        load = " ".join(f.read().split()[:3])
    start = time.perf_counter()
    big = 10 ** 6 if args.case == "tri" else 10 ** 5
    target, tx = mesh(args.case, args.scale * big, (0, 0, 0), (1, 1, 1), 1)
    source, sx = mesh(args.case, 0.8 * args.scale * big, (0.013, -0.011, 0.007), (1.017, 0.991, 1.009), 2)
    total_target, total_source = target.GetNumberOfCells(), source.GetNumberOfCells()
    build = time.perf_counter() - start
    start = time.perf_counter()
    local_target = extract(target, owners(args.partition, tx, args.seed) == rank)
    local_source = extract(source, owners(args.partition, sx, args.seed + 1) == rank)
    split = time.perf_counter() - start
    del target, source, tx, sx
    release()
    controller.Barrier()

    before = status_kb("VmRSS")
    peak = -1
    can_reset = reset_peak()
    messages = Messages()
    best = None
    for _ in range(max(1, args.repeat)):
        f = meshprojection.vtkPMeshProjectionFilter()
        f.SetInputData(local_target)
        f.SetSourceData(local_source)
        f.SetCacheOperator(False)
        f.SetNumberOfThreads(args.threads)
        messages.watch(f)
        controller.Barrier()
        if can_reset:
            reset_peak()
        t0, c0 = time.perf_counter(), time.process_time()
        f.Update()
        seconds = time.perf_counter() - t0
        cpu = (time.process_time() - c0) / max(seconds, 1e-9)
        peak = max(peak, status_kb("VmHWM"))
        slowest = allreduce(seconds)
        if best is None or slowest < best[0]:
            best = (slowest, [
                seconds, f.GetInputTime(), f.GetSearchTime(), f.GetSolveTime(),
                f.GetReceivedSourceCells(), f.GetSentBytes(), f.GetNumberOfIntersections(), cpu,
                f.GetNumberOfLocatorQueries(),
                seconds - sum(getattr(f, "Get%sTime" % stage)() for stage in (
                    "Input", "Neighbors", "Locator", "Search", "Assembly", "Solve", "Output"))],
                [f.GetGlobalSentBytes(), f.GetGlobalReceivedSourceCells(), f.GetGlobalNumberOfIntersections(),
                 f.GetGlobalCoveredMeasure()])
        del f
        release()

    slowest, mine, totals = best
    row = [local_target.GetNumberOfCells(), local_source.GetNumberOfCells()] + mine + [
        before, peak, messages.warnings, messages.errors, build, split]
    rows = allgather(row)
    if rank != 0:
        return
    print("\n%d process(es), case %s (Input %d cells, Source %d cells), partition %s, %d thread(s) per process, "
          "load average %s%s" % (size, args.case, total_target, total_source, args.partition, args.threads, load,
             "" if can_reset else " (VmHWM could not be reset: peaks include the mesh building)"))
    print("\n| process | Input cells | Source cells held | Source cells received | bytes sent | "
          "intersections | locator queries | own time s | CPU/wall | input s | search s | solve s | rest s | "
          "RSS before MB | peak MB | beyond inputs MB |")
    print("|" + "---|" * 16)
    for r, v in enumerate(rows):
        (nt, ns, sec, inp, search, solve, received, sent, pieces, cpu, queries, rest, rss, hwm, _w, _e, _b, _s) = v
        print("| %d | %d | %d | %d | %.0f | %d | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %.1f | %.1f |" % (
            r, nt, ns, received, sent, pieces, queries, sec, cpu, inp, search, solve, rest,
            rss / 1024, hwm / 1024, (hwm - rss) / 1024))
    warnings = int(sum(v[14] for v in rows))
    errors = int(sum(v[15] for v in rows))
    print("\nTotals: bytes sent %.0f, Source cells received %d, intersections %d, covered measure %.12g; "
          "filter warnings %d, errors %d; mesh building %.1f s, partitioning %.1f s (process 0)"
          % (totals[0], totals[1], totals[2], totals[3], warnings, errors, rows[0][16], rows[0][17]))
    print("\n**%d process(es), %s, %s: %.3f s** (best of %d, max over processes)"
          % (size, args.case, args.partition, slowest, args.repeat))
    sys.stdout.flush()


main()
if ours:
    controller.Finalize()
