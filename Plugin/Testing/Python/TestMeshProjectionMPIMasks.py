"""vtkPMeshProjectionFilter on several MPI processes (run under mpiexec with
pvbatch --mpi --symmetric): a Source carrying the filter's own masks (as the
output of an earlier projection does) projects its real fields only, as the
serial filter does, and the gathering of Source leaves the masks out.

The masks (vtkValidPointMask, vtkValidPointMask_p on the points,
vtkValidCellMask on the cells) are not fields (Projection/ArraySelection.h).
Checked on every process:
 - the output has the serial output's arrays (no projected copy of a mask:
   no vtkValidPointMask_p), its own masks equal the serial ones, and the
   real fields (f, linear on the points, cellf on the cells) equal the
   serial ones (1e-10 of their range);
 - the gathering sent exactly the bytes and cells it sends for the same
   Source without the masks: they did not travel with the Source cells. (A
   gathered mask is not projected, since the filter lists fields by the
   same rule; a rule that kept the masks would send them, and name them to
   the others, which only the bytes show.)
"""

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_TRIANGLE, vtkUnstructuredGrid

from mpsupport import meshes, mpi
from mpsupport.mpi import add

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)


def with_fields(g):
    x = vtk_to_numpy(g.GetPoints().GetData())
    add(g.GetPointData(), "f", np.sin(3 * x[:, 0]) + x[:, 1] ** 2)
    add(g.GetPointData(), "linear", np.stack([1 + 2 * x[:, 0] - x[:, 1], x[:, 0]], 1))
    c = meshes.triangle_centres(g)
    add(g.GetCellData(), "cellf", np.cos(2 * c[:, 0]) + c[:, 1])
    return g


def with_masks(g):
    """g with masks like those an earlier projection leaves (a copy: g keeps none)."""
    m = vtkUnstructuredGrid()
    m.DeepCopy(g)
    x = vtk_to_numpy(m.GetPoints().GetData())
    add(m.GetPointData(), "vtkValidPointMask", (x[:, 0] < 0.7).astype(np.int8))
    add(m.GetPointData(), "vtkValidPointMask_p", (x[:, 1] > 0.2).astype(np.float64))
    add(m.GetCellData(), "vtkValidCellMask", (meshes.triangle_centres(m)[:, 0] < 0.5).astype(np.uint8))
    return m


def run(filter_class, target, source):
    f = filter_class()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.Update()
    return f


def names(data):
    return sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))


# Input: triangles; Source: other triangles reaching beyond it on one side.
target = mpi.numbered(meshes.grid(*meshes.triangles(24, (0, 0, 0), (1, 1, 0), 1), VTK_TRIANGLE))
plain = with_fields(meshes.grid(*meshes.triangles(19, (-0.13, 0.07, 0), (0.91, 1.2, 0), 2), VTK_TRIANGLE))
masked = with_masks(plain)
ranges = {name: float(np.ptp(vtk_to_numpy(data.GetArray(name)))) or 1.0
          for data, name in ((plain.GetPointData(), "f"), (plain.GetPointData(), "linear"),
                             (plain.GetCellData(), "cellf"))}

serial = run(meshprojection.vtkMeshProjectionFilter, target, masked).GetOutput()
# The serial filter itself leaves the masks out (the rule the processes follow).
check("vtkValidPointMask_p" not in names(serial.GetPointData()), "serial: vtkValidPointMask_p not projected")
check("cellf" in names(serial.GetCellData()), "serial: cellf projected")

# Each process: a random part of Input, another of Source (the same cells
# for both Sources).
rng = np.random.default_rng(7)
lt = meshes.extract(target, rng.integers(0, size, target.GetNumberOfCells()) == rank)
keep = np.random.default_rng(8).integers(0, size, plain.GetNumberOfCells()) == rank
parallel = run(meshprojection.vtkPMeshProjectionFilter, lt, meshes.extract(masked, keep))
reference = run(meshprojection.vtkPMeshProjectionFilter, lt, meshes.extract(plain, keep))
out = parallel.GetOutput()

# No projected copies of the masks: the serial output's arrays, no more
# (but the ids that extraction gave each process's part).
for assoc in ("point", "cell"):
    sd = serial.GetPointData() if assoc == "point" else serial.GetCellData()
    ld = out.GetPointData() if assoc == "point" else out.GetCellData()
    own = [n for n in names(ld) if n not in ("vtkOriginalPointIds", "vtkOriginalCellIds")]
    check(own == names(sd), "%s arrays %s, serial %s" % (assoc, own, names(sd)))
check(out.GetPointData().GetArray("vtkValidPointMask_p") is None, "vtkValidPointMask_p projected")

# The own masks and the real fields: the serial ones, by original ids.
for assoc, mask, fields in (("point", "vtkValidPointMask", ("f", "linear")), ("cell", "vtkValidCellMask", ("cellf",))):
    ld = out.GetPointData() if assoc == "point" else out.GetCellData()
    sd = serial.GetPointData() if assoc == "point" else serial.GetCellData()
    if ld.GetNumberOfTuples() == 0:
        continue
    ids = vtk_to_numpy(ld.GetArray("origId"))
    sm = vtk_to_numpy(sd.GetArray(mask))[ids]
    lm = vtk_to_numpy(ld.GetArray(mask))
    check(np.array_equal(sm, lm), "%d %s masks differ from serial" % (np.count_nonzero(sm != lm), assoc))
    valid = lm.astype(bool)
    check(valid.any(), "some %ss valid" % assoc)
    for name in fields:
        if ld.GetArray(name) is None:
            check(False, "%s %s not projected" % (assoc, name))
            continue
        lv = vtk_to_numpy(ld.GetArray(name))
        sv = vtk_to_numpy(sd.GetArray(name))[ids]
        err = np.max(np.abs(lv[valid] - sv[valid])) / ranges[name]
        check(err <= 1e-10, "%s %s differs from serial by %.3g of its range" % (assoc, name, err))

# The masks did not travel: the gathering sent what it sends without them.
check(parallel.GetGlobalReceivedSourceCells() == reference.GetGlobalReceivedSourceCells(),
      "Source cells received %d, without masks %d" % (parallel.GetGlobalReceivedSourceCells(),
                                                      reference.GetGlobalReceivedSourceCells()))
check(parallel.GetGlobalSentBytes() == reference.GetGlobalSentBytes(),
      "bytes sent %d with the masks in Source, %d without: the masks travelled"
      % (parallel.GetGlobalSentBytes(), reference.GetGlobalSentBytes()))
check(parallel.GetGlobalReceivedSourceCells() > 0, "Source cells gathered")

check.finish("%d processes, masks in Source" % size)
