"""Time vtkPMeshProjectionFilter on several MPI processes, with what each
process holds, receives, sends and allocates.

    PYTHONPATH=build/lib/python3/dist-packages \\
        mpiexec --allow-run-as-root --oversubscribe -n P pvbatch --mpi --symmetric \\
        Benchmarks/bench_mpi.py [--case tri|tet] [--partition blocks|random] [--scale S] \\
        [--repeat R] [--threads T] [--seed N]

Every process builds the same pair of meshes from jittered grids (the
builders of mpsupport.meshes, shared with the MPI test; no cell
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
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import VTK_STRING
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE
from vtkmodules.vtkParallelCore import vtkCommunicator

from mpsupport import meshes, mpi

controller, ours = mpi.start()  # (pvbatch --mpi finalizes its own)
rank = controller.GetLocalProcessId()
size = controller.GetNumberOfProcesses()

import meshprojection  # noqa: E402  (after MPI is up)


# ---- collectives ------------------------------------------------------------
def allreduce(value, op=vtkCommunicator.MAX_OP):
    return mpi.allreduce(controller, value, op)


def allgather(values):
    return mpi.allgather(controller, values)


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


# ---- meshes -------------------------------------------------------------------
def mesh(kind, cells, lo, hi, seed):
    """About `cells` triangles / tetrahedra of the box [lo, hi], with a point
    field "f" and a cell field "g"; and the x of the cell centres."""
    if kind == "tri":
        n = max(2, int(round(np.sqrt(cells / 2.0))))
        x, conn, ctype = (*meshes.triangles(n, lo, hi, seed), VTK_TRIANGLE)
    else:
        n = max(2, int(round((cells / 6.0) ** (1.0 / 3))))
        # (Jitter 0.2, not 0.25: that inverts a tetrahedron at these sizes.)
        x, conn, ctype = (*meshes.tetrahedra(n, lo, hi, seed, jitter=0.2), VTK_TETRA)
    centres = x[conn].mean(axis=1)
    g = meshes.grid(x, conn, ctype)
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
    local_target = meshes.extract(target, owners(args.partition, tx, args.seed) == rank)
    local_source = meshes.extract(source, owners(args.partition, sx, args.seed + 1) == rank)
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
