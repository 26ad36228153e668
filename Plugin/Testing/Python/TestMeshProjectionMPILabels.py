"""vtkPMeshProjectionFilter on several MPI processes (run under mpiexec with
pvbatch --mpi --symmetric): label arrays (Filters/Projection/Labels.h) give
the serial result.

Source: jittered triangles reaching beyond Input on two sides, with a cell
label MaterialId (int: three regions crossing the cells, and a label 9 on
Source cells that no part of Input reaches) and a point label NodeTag
(short); both go to points and cells, with their fractions. Each process
has a random part of Input and another of Source. Checked on every
process, by original ids: the labels equal the serial ones exactly, in the
Source arrays' types; the fractions' components are the serial ones (label
9 too: the labels are the whole Source's, not only those gathered) and
their values the serial ones to 1e-12; the masks equal the serial ones.
An integer array with more distinct values over the whole Source than
MaximumAutomaticLabels (but fewer in each process's part) is projected as
numbers on every process, as in serial, with the serial warning's count
of values or, where a process alone has more once it gathered, a lower
bound said "at least"; with Input in a corner of the Source only (every
process below the limit, their union above) the serial count exactly.
"""

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_DOUBLE, VTK_ID_TYPE, VTK_INT, VTK_SHORT
from vtkmodules.vtkCommonDataModel import VTK_TRIANGLE

from mpsupport import meshes, mpi

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)


def with_labels(g):
    c = meshes.triangle_centres(g)
    material = np.where((c[:, 0] - 0.55) ** 2 + (c[:, 1] - 0.6) ** 2 < 0.08, 3,
                        np.where(c[:, 1] < 0.3 + 0.25 * c[:, 0], 0, 7))
    material[(c[:, 0] < -0.06) & (c[:, 1] > 1.1)] = 9  # beyond Input: never gathered
    a = numpy_to_vtk(material.astype(np.int32), deep=True, array_type=VTK_INT)
    a.SetName("MaterialId")
    g.GetCellData().AddArray(a)
    x = vtk_to_numpy(g.GetPoints().GetData())
    tag = 1 + (x[:, 0] > 0.42) + 2 * (x[:, 1] > 0.5 - 0.3 * x[:, 0])
    t = numpy_to_vtk(tag.astype(np.int16), deep=True, array_type=VTK_SHORT)
    t.SetName("NodeTag")
    g.GetPointData().AddArray(t)
    return g


def run(filter_class, target, source):
    """The filter updated; its warnings' texts in f.warnings."""
    f = filter_class()
    f.warnings = mpi.messages(f)["WarningEvent"]
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.SetLabelFractions(True)
    f.SetPointDataTarget(f.TO_POINTS_AND_CELLS)
    f.SetCellDataTarget(f.TO_POINTS_AND_CELLS)
    f.Update()
    return f


target = mpi.numbered(meshes.grid(*meshes.triangles(23, (0, 0, 0), (1, 1, 0), 1), VTK_TRIANGLE))
source = with_labels(meshes.grid(*meshes.triangles(19, (-0.13, 0.07, 0), (0.91, 1.2, 0), 2),
                                 VTK_TRIANGLE))
serial = run(meshprojection.vtkMeshProjectionFilter, target, source).GetOutput()

rng = np.random.default_rng(11)
lt = meshes.extract(target, rng.integers(0, size, target.GetNumberOfCells()) == rank)
keep = np.random.default_rng(12).integers(0, size, source.GetNumberOfCells()) == rank
out = run(meshprojection.vtkPMeshProjectionFilter, lt, meshes.extract(source, keep)).GetOutput()

compared = 0
for assoc, mask in (("point", "vtkValidPointMask"), ("cell", "vtkValidCellMask")):
    ld = out.GetPointData() if assoc == "point" else out.GetCellData()
    sd = serial.GetPointData() if assoc == "point" else serial.GetCellData()
    if ld.GetNumberOfTuples() == 0:
        continue
    ids = vtk_to_numpy(ld.GetArray("origId"))
    check(np.array_equal(vtk_to_numpy(sd.GetArray(mask))[ids], vtk_to_numpy(ld.GetArray(mask))),
          "%s masks differ from serial" % assoc)
    for name, kind in (("MaterialId", VTK_INT), ("NodeTag", VTK_SHORT)):
        la, sa = ld.GetArray(name), sd.GetArray(name)
        if la is None or sa is None:
            check(False, "%s %s missing (parallel %s, serial %s)" % (assoc, name, la, sa))
            continue
        check(la.GetDataType() == kind, "%s %s keeps its type (%s)" % (assoc, name, la.GetClassName()))
        lv, sv = vtk_to_numpy(la), vtk_to_numpy(sa)[ids]
        check(np.array_equal(lv, sv), "%s %s: %d labels differ from serial"
              % (assoc, name, np.count_nonzero(lv != sv)))
        lf, sf = ld.GetArray(name + "_Fractions"), sd.GetArray(name + "_Fractions")
        components = [lf.GetComponentName(k) for k in range(lf.GetNumberOfComponents())]
        serial_components = [sf.GetComponentName(k) for k in range(sf.GetNumberOfComponents())]
        check(components == serial_components, "%s %s fractions' components %s, serial %s"
              % (assoc, name, components, serial_components))
        if components == serial_components:
            a, b = vtk_to_numpy(lf), vtk_to_numpy(sf)[ids]
            both = np.isfinite(b)
            err = float(np.max(np.abs(a[both] - b[both]))) if both.any() else 0.0
            check(np.array_equal(np.isfinite(a), both) and err <= 1e-12,
                  "%s %s fractions differ from serial by %.3g" % (assoc, name, err))
        compared += len(lv)
check("9" in [serial.GetCellData().GetArray("MaterialId_Fractions").GetComponentName(k) for k in range(4)],
      "the serial fractions list label 9")
check(compared > 0 or out.GetNumberOfCells() == 0, "labels compared")

# An id array: more distinct values over the whole Source (1,800) than
# MaximumAutomaticLabels, fewer in each process's part: numbers on every
# process, as in serial (the decision is the whole Source's).
fine = meshes.grid(*meshes.triangles(30, (-0.13, 0.07, 0), (0.91, 1.2, 0), 2), VTK_TRIANGLE)
n_fine = fine.GetNumberOfCells()
numbers = numpy_to_vtk(np.arange(n_fine, dtype=np.int64), deep=True, array_type=VTK_ID_TYPE)
numbers.SetName("CellNumber")
fine.GetCellData().AddArray(numbers)
serial_run = run(meshprojection.vtkMeshProjectionFilter, target, fine)
serial_ids = serial_run.GetOutput().GetCellData()
part = np.random.default_rng(13).integers(0, size, n_fine) == rank
local_run = run(meshprojection.vtkPMeshProjectionFilter, lt, meshes.extract(fine, part))
local_ids = local_run.GetOutput()


def id_count(f):
    """The count of values in f's warning that 'CellNumber' looks like an id
    array, and whether it is a lower bound ("at least"); None: no warning."""
    for w in f.warnings:
        if "'CellNumber' looks like an id array (" in w:
            words = w.split("looks like an id array (", 1)[1].split(" distinct values")[0]
            return int(words.replace("at least ", "")), words.startswith("at least ")
    return None


# The warning on every process: the serial count, or (a process alone above
# the limit once its gathered cells join its piece: decided before the
# union) a lower bound above the limit, said "at least".
said, whole = id_count(local_run), id_count(serial_run)
check(whole == (n_fine, False), "'CellNumber': the serial warning counts %d values (%s)" % (n_fine, whole))
check(said is not None and (said == whole or (said[1] and 1024 < said[0] <= n_fine)),
      "'CellNumber': the id array warning's count is the serial one or a lower bound (%s, serial %s)"
      % (said, whole))
if local_ids.GetNumberOfCells() > 0:
    la, sa = local_ids.GetCellData().GetArray("CellNumber"), serial_ids.GetArray("CellNumber")
    ids = vtk_to_numpy(local_ids.GetCellData().GetArray("origId"))
    check(n_fine > 1024 and np.count_nonzero(part) < 1024 and la is not None
          and la.GetDataType() == VTK_DOUBLE and sa.GetDataType() == VTK_DOUBLE,
          "'CellNumber' (%d values, %d here) is projected as numbers (%s, serial %s)"
          % (n_fine, np.count_nonzero(part), la.GetClassName() if la else None, sa.GetClassName()))
    if la is not None:
        lv, sv = vtk_to_numpy(la), vtk_to_numpy(sa)[ids]
        both = np.isfinite(sv)
        err = float(np.max(np.abs(lv[both] - sv[both]))) if both.any() else 0.0
        check(np.array_equal(np.isfinite(lv), both) and err <= 1e-9 * n_fine,
              "'CellNumber' differs from serial by %.3g" % err)

# The same array with the whole Source on the first process: it alone has
# more distinct values than MaximumAutomaticLabels, so every process
# decides "numbers" before the union of the values (the same result).
alone = np.full(n_fine, rank == 0)
first = run(meshprojection.vtkPMeshProjectionFilter, lt, meshes.extract(fine, alone)).GetOutput()
if first.GetNumberOfCells() > 0:
    fa = first.GetCellData().GetArray("CellNumber")
    ids = vtk_to_numpy(first.GetCellData().GetArray("origId"))
    check(fa is not None and fa.GetDataType() == VTK_DOUBLE,
          "'CellNumber' all on the first process is projected as numbers (%s)" % (fa.GetClassName() if fa else None))
    if fa is not None:
        fv, sv = vtk_to_numpy(fa), vtk_to_numpy(serial_ids.GetArray("CellNumber"))[ids]
        both = np.isfinite(sv)
        err = float(np.max(np.abs(fv[both] - sv[both]))) if both.any() else 0.0
        check(np.array_equal(np.isfinite(fv), both) and err <= 1e-9 * n_fine,
              "'CellNumber' all on the first process differs from serial by %.3g" % err)

# Every process below the limit, the union above: Input only in a corner
# of the Source (each process gathers few cells beyond its piece, a third
# or half of the Source): the processes' values are unioned, and the
# decision and the warning's count are the serial ones exactly.
tc = meshes.triangle_centres(target)
corner = mpi.numbered(meshes.extract(target, (tc[:, 0] < 0.25) & (tc[:, 1] < 0.25)))
serial_corner = run(meshprojection.vtkMeshProjectionFilter, corner, fine)
mine = np.random.default_rng(17).integers(0, size, corner.GetNumberOfCells()) == rank
local_corner = run(meshprojection.vtkPMeshProjectionFilter, meshes.extract(corner, mine), meshes.extract(fine, part))
check(id_count(local_corner) == (n_fine, False),
      "corner: the id array warning counts the serial %d values (%s)" % (n_fine, id_count(local_corner)))
out = local_corner.GetOutput()
if out.GetNumberOfCells() > 0:
    la = out.GetCellData().GetArray("CellNumber")
    check(la is not None and la.GetDataType() == VTK_DOUBLE,
          "corner: 'CellNumber' is projected as numbers (%s)" % (la.GetClassName() if la else None))
    if la is not None:
        ids = vtk_to_numpy(out.GetCellData().GetArray("origId"))
        lv = vtk_to_numpy(la)
        sv = vtk_to_numpy(serial_corner.GetOutput().GetCellData().GetArray("CellNumber"))[ids]
        both = np.isfinite(sv)
        err = float(np.max(np.abs(lv[both] - sv[both]))) if both.any() else 0.0
        check(np.array_equal(np.isfinite(lv), both) and err <= 1e-9 * n_fine,
              "corner: 'CellNumber' differs from serial by %.3g" % err)

check.finish("%d processes, labels" % size)
