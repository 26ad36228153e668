"""vtkPMeshProjectionFilter on 2 or 3 MPI processes (run under mpiexec with
pvbatch --mpi --symmetric, under a timeout: a hang fails) when one process,
the first or the last (argument "first" or "last"), fails or stops alone.
Every process must end the execution alike: the same error text on every
process, naming the failing process ("(on process k)"), and the output
Input as it came (no vtkValidPointMask, no projected array) on all of them,
never one process with output while the others fail:

 - corrupt cell ids on the Source piece, then on the Input piece (the
   datasets' checks, before the gathering);
 - a NaN coordinate on the Input piece (found when the leaf wraps it, in a
   round of the leaf's agreement);
 - a 3D Input piece where the others and Source are 2D (the leaf's shape);
 - no Source on the process (its Source port left empty);
 - the user's abort (AbortExecute) on the process, while the operators are
   built: every process stops (a warning, the output Input as it came).

Each process's outcome (error text, whether the output has projected
arrays) is gathered on every process and compared there.

A solve that fails and an exception have no honest cause from outside
(the solves are collective: a system that fails, fails on every process;
MaximumIterations 0 or 1 only hands it to the direct solver, which solves
it), so the test makes them on the failing process with the test-only
MESHPROJECTION_TEST_FAULT=<stage>@<rank> (docs/testing.md):
 - "solve": its solves reported failed (the leaf's last round agrees it);
 - "local": an exception in a step of that process alone (building the
   operators: mpvtk::Guarded, agreed in the next round).
With the argument "collective" (the last process): an exception between
the solves' collectives, where the others wait; the run must end, aborted
on every process (MPI_Abort), not hang: the script then never reaches its
end, and the test passes on the filter's abort message.
"""
import os

import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE, vtkUnstructuredGrid

from mpsupport import meshes, mpi

controller, rank, size, check = mpi.begin()
which = sys.argv[1] if len(sys.argv) > 1 else "last"
bad = 0 if which == "first" else size - 1  # the process that fails alone
if which == "collective":
    # An exception inside a collective step: the run ends (MPI_Abort) on
    # every process; "FAILED" if the execution comes back on any.
    os.environ["MESHPROJECTION_TEST_FAULT"] = "collective@%d" % bad

import meshprojection  # noqa: E402  (after MPI is up)


def run(target, source, abort_at=None):
    """The parallel filter updated on this process's pieces; its output and
    the texts of its warnings and errors (`abort_at`: this process sets
    AbortExecute once the progress passes it)."""
    f = meshprojection.vtkPMeshProjectionFilter()
    texts = mpi.messages(f)
    if abort_at is not None:
        def progress(o, e):
            if o.GetProgress() >= abort_at:
                o.SetAbortExecute(1)
        f.AddObserver("ProgressEvent", progress)
    f.SetInputData(target)
    if source is not None:
        f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.Update()
    return f.GetOutput(), texts["WarningEvent"], texts["ErrorEvent"]


def outcomes(out, messages):
    """Every process's (has a message, hash of its first, projected output)."""
    projected = out.GetPointData().GetArray("vtkValidPointMask") is not None or \
        out.GetPointData().GetArray("f") is not None
    mine = [1.0 if messages else 0.0, mpi.message_hash(messages[0]) if messages else -1.0, 1.0 if projected else 0.0]
    return np.array(mpi.allgather(controller, np.array(mine)))


def expect_failure(what, out, errors, words):
    """Every process has an error, the same text, naming the process `bad`
    and `words`, and no process has projected output."""
    first = errors[0] if errors else ""
    check(("(on process %d)" % bad) in first, "%s: the error does not name process %d: %r" % (what, bad, first))
    check(words in first, "%s: the error does not say %r: %r" % (what, words, first))
    all_ = outcomes(out, errors)
    check(np.all(all_[:, 0] == 1), "%s: no error on processes %s" % (what, np.where(all_[:, 0] != 1)[0]))
    check(np.all(all_[:, 1] == all_[0, 1]), "%s: the errors differ between processes" % what)
    check(np.all(all_[:, 2] == 0), "%s: projected output on processes %s" % (what, np.where(all_[:, 2] != 0)[0]))


# Input: triangles of the unit square; Source: other triangles, with point
# ids and a field. Source pieces: slabs along x; Input pieces: random.
target = mpi.numbered(meshes.grid(*meshes.triangles(16, (0, 0, 0), (1, 1, 0), 1), VTK_TRIANGLE))
whole = meshes.grid(*meshes.triangles(13, (-0.11, 0.05, 0), (0.93, 1.1, 0), 2), VTK_TRIANGLE)
x = vtk_to_numpy(whole.GetPoints().GetData())
ids = numpy_to_vtkIdTypeArray(np.arange(whole.GetNumberOfPoints(), dtype=np.int64), deep=True)
ids.SetName("GlobalIds")
whole.GetPointData().SetGlobalIds(ids)
meshes.add_array(whole.GetPointData(), "f", np.sin(3 * x[:, 0]) + x[:, 1] ** 2)
cx = meshes.triangle_centres(whole)[:, 0]
slab = np.floor((cx - cx.min()) / (cx.max() + 1e-9 - cx.min()) * size).astype(int)
source_piece = meshes.extract(whole, slab == rank)
target_piece = meshes.extract(target, np.random.default_rng(7).integers(0, size, target.GetNumberOfCells()) == rank)


def copy(g):
    c = vtkUnstructuredGrid()
    c.DeepCopy(g)
    return c


def spoiled(g, spoil):
    """A copy of g, spoiled on the failing process."""
    c = copy(g)
    if rank == bad:
        spoil(c)
    return c


def corrupt(g):
    vtk_to_numpy(g.GetCells().GetConnectivityArray())[0] = 10 ** 7
    g.GetCells().Modified()


def nan_coordinate(g):
    vtk_to_numpy(g.GetPoints().GetData())[g.GetNumberOfPoints() // 2, 1] = np.nan
    g.GetPoints().Modified()


# 0. Nothing spoiled: every process projects (the test's own baseline).
out, warnings, errors = run(copy(target_piece), copy(source_piece))
if which == "collective":
    print("FAILED on process %d: the execution came back after an exception in a collective step "
          "(errors: %s)" % (rank, errors), file=sys.stderr, flush=True)
    os._exit(1)
all_ = outcomes(out, errors)
check(np.all(all_[:, 0] == 0) and np.all(all_[:, 2] == 1), "unspoiled: errors or no output %s" % all_)

# 1. Corrupt ids on the Source piece, then on the Input piece.
out, _, errors = run(copy(target_piece), spoiled(source_piece, corrupt))
expect_failure("corrupt Source piece", out, errors, "Source")
out, _, errors = run(spoiled(target_piece, corrupt), copy(source_piece))
expect_failure("corrupt Input piece", out, errors, "Input")

# 2. A NaN coordinate on the Input piece (the leaf's own check).
out, _, errors = run(spoiled(target_piece, nan_coordinate), copy(source_piece))
expect_failure("NaN coordinate in the Input piece", out, errors, "NaN or infinite coordinate")

# 3. A 3D Input piece on the failing process, 2D pieces elsewhere and a 2D
# Source: the leaf's shape fails there.
if rank == bad:
    volume = meshes.grid(*meshes.tetrahedra(2, (0, 0, 0), (1, 1, 1), 3), VTK_TETRA)
    out, _, errors = run(volume, copy(source_piece))
else:
    out, _, errors = run(copy(target_piece), copy(source_piece))
expect_failure("3D Input piece", out, errors, "Input")

# 4. No Source on the failing process.
out, _, errors = run(copy(target_piece), None if rank == bad else copy(source_piece))
expect_failure("no Source on one process", out, errors, "No Source")

# 5. The user's abort on the failing process, during the operators' build:
# every process stops, with Input as it came.
out, warnings, errors = run(copy(target_piece), copy(source_piece), 0.1 if rank == bad else None)
stopped = [w for w in warnings if "Aborted" in w]
all_ = outcomes(out, stopped)
check(np.all(all_[:, 0] == 1), "abort on one process: not stopped on processes %s" % np.where(all_[:, 0] != 1)[0])
check(np.all(all_[:, 2] == 0), "abort on one process: projected output on processes %s" % np.where(all_[:, 2] != 0)[0])
check(not errors, "abort on one process: errors %s" % errors)

# 6. Test faults (MESHPROJECTION_TEST_FAULT) on the failing process: a
# failed solve, an exception in a step of that process alone.
for stage, words in (("solve", "the solves failed"), ("local", "Building the operators failed")):
    os.environ["MESHPROJECTION_TEST_FAULT"] = "%s@%d" % (stage, bad)
    out, _, errors = run(copy(target_piece), copy(source_piece))
    del os.environ["MESHPROJECTION_TEST_FAULT"]
    expect_failure("test fault %s" % stage, out, errors, words)

check.finish("%d processes, the %s process fails alone" % (size, which))
