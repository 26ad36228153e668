"""vtkPMeshProjectionFilter on 2 or 3 MPI processes (run under mpiexec with
pvbatch --mpi --symmetric, under ctest's timeout) when one process's piece
differs from the others' or is spoiled, on the Source or on the Input. Every
run ends on every process (no hang), alike on all, and no array is dropped
silently (Adapter/PieceArrays.h states the rule):

 - Source point arrays (one of doubles, one of integers) and a cell array
   missing on the last process's piece are projected where present: the output equals the serial projection of the
   whole Source with NaN where that piece alone has them (1e-10 of the
   range), and every process warns once, naming each, with the same text;
 - an array with 3 components on the last piece and 1 on the others is not
   projected, named in a warning (the same on every process); the other
   arrays still equal the serial ones;
 - an empty Source piece makes no array missing: no warning, the fields
   equal the serial projection of the other pieces;
 - a Source piece with a NaN point value: projected, no error;
 - corrupt cell ids or a NaN coordinate on the Source piece or the Input
   piece of one process: the same error on every process;
 - an empty Input piece, an Input piece without an array or with other
   components of it: the fields are projected on the others as in serial;
 - no Source on one process: the same error on every process;
 - NaN values along the border of two Source pieces (no GlobalIds), inside
   Input's bounds: the warning's counts of NaN values and left-out cells
   are the serial ones, on every process.
"""

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_TRIANGLE, vtkUnstructuredGrid

from mpsupport import meshes, mpi

controller, rank, size, check = mpi.begin()
bad = size - 1  # the process whose piece is spoiled

import meshprojection  # noqa: E402  (after MPI is up)


def copy(g):
    c = vtkUnstructuredGrid()
    c.DeepCopy(g)
    return c


def run(filter_class, target, source):
    """The filter updated on target and source; its output and the texts of
    its warnings and errors."""
    f = filter_class()
    texts = mpi.messages(f)
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.Update()
    return f.GetOutput(), texts["WarningEvent"], texts["ErrorEvent"]


def everywhere(flag):
    """Whether flag holds on every process."""
    return mpi.allreduce(controller, 1.0 if flag else 0.0, mpi.vtkCommunicator.MIN_OP) > 0


def same_everywhere(text):
    """Whether every process has the same message (compared by a hash; the
    text after VTK's "(address): " header)."""
    h = mpi.message_hash(text)
    return mpi.allreduce(controller, h) == mpi.allreduce(controller, h, mpi.vtkCommunicator.MIN_OP)


def names(data):
    return sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))


# Input: triangles of the unit square; Source: other triangles, with point
# ids (so that a point on the border of two pieces is one point) and fields.
target = mpi.numbered(meshes.grid(*meshes.triangles(20, (0, 0, 0), (1, 1, 0), 1), VTK_TRIANGLE))
whole = meshes.grid(*meshes.triangles(17, (-0.11, 0.05, 0), (0.93, 1.1, 0), 2), VTK_TRIANGLE)
x = vtk_to_numpy(whole.GetPoints().GetData())
ids = numpy_to_vtkIdTypeArray(np.arange(whole.GetNumberOfPoints(), dtype=np.int64), deep=True)
ids.SetName("GlobalIds")
whole.GetPointData().SetGlobalIds(ids)
meshes.add_array(whole.GetPointData(), "f", np.sin(3 * x[:, 0]) + x[:, 1] ** 2)
meshes.add_array(whole.GetPointData(), "p", 1 + 2 * x[:, 0] - x[:, 1])
meshes.add_array(whole.GetPointData(), "v", x[:, 0] * x[:, 1])
meshes.add_array(whole.GetCellData(), "c", np.cos(2 * meshes.triangle_centres(whole)[:, 0]))
n = numpy_to_vtk((10 * x[:, 1]).astype(np.int32), deep=True)  # integers: joined as double
n.SetName("n")
whole.GetPointData().AddArray(n)
# Source pieces: slabs along x by cell centre; Input pieces: random.
cx = meshes.triangle_centres(whole)[:, 0]
lo, hi = cx.min(), cx.max() + 1e-9
slab = np.floor((cx - lo) / (hi - lo) * size).astype(int)
mine = slab == rank
lt = meshes.extract(target, np.random.default_rng(7).integers(0, size, target.GetNumberOfCells()) == rank)

ranges = {"f": 2.0, "p": 3.0, "c": 2.0, "n": 10.0}


def compare(out, serial, fields, what):
    """The fields of this process's output equal the serial ones (by origId),
    NaN (the fill) where serial has NaN, and so do the serial masks."""
    for data, sdata in ((out.GetPointData(), serial.GetPointData()), (out.GetCellData(), serial.GetCellData())):
        if data.GetNumberOfTuples() == 0:
            continue
        # Rows of the serial output by original id (its Input may be a part).
        rows = np.full(target.GetNumberOfPoints() + target.GetNumberOfCells(), -1)
        rows[vtk_to_numpy(sdata.GetArray("origId"))] = np.arange(sdata.GetNumberOfTuples())
        at = rows[vtk_to_numpy(data.GetArray("origId"))]
        check(np.all(at >= 0), "%s: output rows not in the serial output" % what)
        for name in names(sdata):
            if name not in fields and not name.startswith("vtkValid"):
                continue
            if data.GetArray(name) is None:
                check(False, "%s: %s not projected" % (what, name))
                continue
            lv = vtk_to_numpy(data.GetArray(name)).astype(float)
            sv = vtk_to_numpy(sdata.GetArray(name)).astype(float)[at]
            same_nan = np.array_equal(np.isnan(lv), np.isnan(sv))
            finite = ~np.isnan(sv)
            err = float(np.max(np.abs(lv[finite] - sv[finite]), initial=0)) / ranges.get(name, 1.0)
            check(same_nan and err <= 1e-10, "%s: %s differs from serial (%.3g of its range, NaN alike %s)"
                  % (what, name, err, same_nan))


def source_piece(spoil=None):
    """This process's Source piece; `spoil` changes the bad process's."""
    piece = meshes.extract(whole, mine)
    if rank == bad and spoil:
        spoil(piece)
    return piece


# 1. Point array 'p' and cell array 'c' missing on the bad process's piece.
def drop(piece):
    piece.GetPointData().RemoveArray("p")
    piece.GetPointData().RemoveArray("n")
    piece.GetCellData().RemoveArray("c")


out, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, lt, source_piece(drop))
holed = copy(whole)
present = np.zeros(whole.GetNumberOfPoints(), bool)
present[vtk_to_numpy(whole.GetCells().GetConnectivityArray()).reshape(-1, 3)[~(slab == bad)].ravel()] = True
vtk_to_numpy(holed.GetPointData().GetArray("p"))[~present] = np.nan
meshes.add_array(holed.GetPointData(), "n", np.where(present, vtk_to_numpy(n), np.nan))
vtk_to_numpy(holed.GetCellData().GetArray("c"))[slab == bad] = np.nan
check(np.isnan(vtk_to_numpy(holed.GetPointData().GetArray("p"))).any(), "the reference has a hole")
serial, _, _ = run(meshprojection.vtkMeshProjectionFilter, target, holed)
check(not errors, "missing arrays: errors %s" % errors)
compare(out, serial, ("f", "p", "n", "v", "c"), "missing arrays")
for name in ("'p'", "'n'", "'c'"):
    said = [w for w in warnings if name in w and "missing on process %d" % bad in w]
    check(len(said) == 1, "missing arrays: one warning naming %s, got %s" % (name, warnings))
    check(same_everywhere(said[0] if said else ""), "missing arrays: the warning on %s differs" % name)
check(not [w for w in warnings if "NaN or infinite" in w], "missing arrays: also a NaN warning %s" % warnings)
# Said once per filter: a second run of the same filter is not asked here
# (WarnOnce's keys are the texts, Messages.h).


# 2. 'v' with 3 components on the bad process's piece, 1 on the others.
def widen(piece):
    v = vtk_to_numpy(piece.GetPointData().GetArray("v"))
    piece.GetPointData().RemoveArray("v")
    meshes.add_array(piece.GetPointData(), "v", np.stack([v, v, v], 1))


out, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, lt, source_piece(widen))
serial, _, _ = run(meshprojection.vtkMeshProjectionFilter, target, whole)
check(not errors, "other components: errors %s" % errors)
check(out.GetPointData().GetArray("v") is None, "other components: 'v' projected")
said = [w for w in warnings if "'v'" in w and "not projected" in w and "3 components" in w]
check(len(said) == 1, "other components: one warning naming 'v', got %s" % warnings)
check(same_everywhere(said[0] if said else ""), "other components: the warning differs between processes")
compare(out, serial, ("f", "p", "c"), "other components")


# 3. An empty Source piece: nothing missing; the serial result of the others.
def empty(piece):
    piece.Initialize()


out, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, lt, source_piece(empty))
others = meshes.extract(whole, slab != bad)
serial, _, _ = run(meshprojection.vtkMeshProjectionFilter, target, others)
check(not errors, "empty Source piece: errors %s" % errors)
check(not [w for w in warnings if "missing" in w or "not projected" in w],
      "empty Source piece: warnings %s" % warnings)
compare(out, serial, ("f", "p", "v", "c"), "empty Source piece")


# 4. A NaN value on the bad process's piece: projected, no error anywhere.
def nan_point(piece):
    vtk_to_numpy(piece.GetPointData().GetArray("f"))[0] = np.nan


out, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, lt, source_piece(nan_point))
check(everywhere(not errors), "NaN point: an error on some process")
check(out.GetPointData().GetNumberOfTuples() == 0 or out.GetPointData().GetArray("f") is not None,
      "NaN point: 'f' dropped")


# 5. Corrupt cell ids, then a NaN coordinate, on the bad process's Source
# piece, then Input piece: the same error on every process.
def corrupt(g):
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray())
    if len(conn):
        conn[0] = 10 ** 7
        g.GetCells().Modified()


def nan_coordinate(g):
    x = vtk_to_numpy(g.GetPoints().GetData())
    if len(x):
        x[len(x) // 2, 1] = np.nan
        g.GetPoints().Modified()


for spoil, how in ((corrupt, "corrupt"), (nan_coordinate, "NaN coordinate in a")):
    for where in ("Source", "Input"):
        s = source_piece(spoil if where == "Source" else None)
        t = copy(lt)
        if where == "Input" and rank == bad:
            spoil(t)
        out, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, t, s)
        what = "%s %s piece" % (how, where)
        check(everywhere(len(errors) > 0), "%s: no error on some process" % what)
        first = errors[0] if errors else ""
        check(where in first, "%s: the error does not name it: %s" % (what, first))
        check(same_everywhere(first.strip().split(" (on process")[0]), "%s: errors differ: %r" % (what, first))


# 6. Input pieces: empty, without an array, with other components of it on
# the bad process: the fields as in serial (of the Input without the empty
# piece) on the others.
parts = np.random.default_rng(7).integers(0, size, target.GetNumberOfCells())
for what in ("empty", "without an array", "other components"):
    serial, _, _ = run(meshprojection.vtkMeshProjectionFilter,
                       meshes.extract(target, parts != bad) if what == "empty" else target, whole)
    t = copy(lt)
    meshes.add_array(t.GetPointData(), "w", np.ones(t.GetNumberOfPoints()))
    if rank == bad:
        if what == "empty":
            t = vtkUnstructuredGrid()
        elif what == "without an array":
            t.GetPointData().RemoveArray("w")
        else:
            t.GetPointData().RemoveArray("w")
            meshes.add_array(t.GetPointData(), "w", np.ones((t.GetNumberOfPoints(), 3)))
    out, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, t, source_piece())
    check(everywhere(not errors), "Input piece %s: an error on some process: %s" % (what, errors))
    if rank != bad or what != "empty":
        compare(out, serial, ("f", "p", "v", "c"), "Input piece %s" % what)

# 7. No Source on the bad process (its Source port left empty): the same
# error on every process, no wait in the gathering.
out, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, lt,
                            None if rank == bad else source_piece())
check(everywhere(len(errors) > 0), "no Source on one process: no error on some process")
first = errors[0].strip().split(" (on process")[0] if errors else ""
check("No Source" in first, "no Source on one process: the error %r" % first)
check(same_everywhere(first), "no Source on one process: errors differ")

# 8. NaN values along the border of the Source pieces, the Source without
# GlobalIds (its border points on two pieces), Input in slabs too (each
# process gathers other Source cells): the NaN warning's counts of values
# and cells are the serial ones, the same on every process (each point and
# cell counted once over the processes).
def nan_warnings(warnings):
    return sorted(w.split("): ", 1)[-1].split(": the ")[0] + " / " + w.split(": the ")[1].split(" Source")[0]
                  for w in warnings if "NaN or infinite values" in w)


striped = copy(whole)
striped.GetPointData().RemoveArray("GlobalIds")
border = lo + (hi - lo) * max(bad, 1) / size  # a border between two pieces
# (Inside Input's bounds: a Source cell away from every part of Input is
# gathered by no process, and its NaN values are not counted there.)
band = (x[:, 1] > 0.1) & (x[:, 1] < 0.9)
vtk_to_numpy(striped.GetPointData().GetArray("f"))[(np.abs(x[:, 0] - border) < 0.09) & band] = np.nan
cy = meshes.triangle_centres(whole)[:, 1]
vtk_to_numpy(striped.GetCellData().GetArray("c"))[(np.abs(cx - border) < 0.05) & (cy > 0.1) & (cy < 0.9)] = np.nan
_, serial_warnings, _ = run(meshprojection.vtkMeshProjectionFilter, target, striped)
tx = meshes.triangle_centres(target)[:, 0]
slabs = meshes.extract(target, np.minimum((tx * size).astype(int), size - 1) == rank)
_, warnings, errors = run(meshprojection.vtkPMeshProjectionFilter, slabs, meshes.extract(striped, mine))
said, expected = nan_warnings(warnings), nan_warnings(serial_warnings)
check(len(expected) == 2, "NaN counts: the serial run's warnings %s" % serial_warnings)
check(said == expected, "NaN counts: %s, serial %s" % (said, expected))
check(same_everywhere(" ".join(said)), "NaN counts: the warnings differ between processes")

check.finish("%d processes, spoiled pieces" % size)
