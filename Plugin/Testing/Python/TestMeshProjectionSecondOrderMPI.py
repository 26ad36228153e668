"""Second-order cells on several MPI processes (run under mpiexec with
pvbatch --mpi --symmetric): a Gmsh tet10 cube as
Input, in blocks along x, and a Gmsh hex20 cube moved to overlap it in
part as Source, its cells dealt at random, projected by
vtkPMeshProjectionFilter; the gathered Source and the Input's halo carry
the quadratic cells whole (their mid nodes too). On every process, for its
points (by their original ids):
 - the valid mask is the serial one, and the values of a smooth field
   (given at every node) equal the serial ones to 1e-10 of its range;
 - a linear field is exact at every valid node (1e-9 of its range);
 - the integral over the covered part (a total over the processes) equals
   the serial one (1e-12);
 - a mixed Input whose first part is linear tetrahedra (that process has no
   second-order cell) and the rest tet10, inside a Source that covers it,
   with MassMatrix Lumped and PreserveBounds, and with PreserveBounds alone
   (both in the Bernstein form of the cells' space): every process solves
   alike, ends, and gives the serial values (1e-10 of the range), within
   the Source's range, with the serial integral (1e-12); its point labels
   (a region id given at the Source's nodes: the lumped, bounded
   Bernstein weights) are the serial ones; the same with the whole Input
   on the first process (the others' parts empty);
 - a mixed Input of linear hexahedra (the first part) and hex20 (signed
   form: BernsteinForm.h, its lumped coefficients always clipped, so
   every process clips alike, the first with no signed cell), with
   MassMatrix Lumped alone and with PreserveBounds: the serial values
   (1e-10 of the range), within the Source's range, the serial integral
   (1e-12);
 - CurvedCellSubdivision 2 and 3 on curved tri6 and quad9 disks and tet10
   balls, as Input and as Source, with the fringe: the serial values,
   masks, integrals and warnings (mpsupport.secondorder.check_curved_levels).
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy

from mpsupport import gmshmeshes, meshes, mpi
from mpsupport.mpi import add
from mpsupport.secondorder import check_curved_levels, project
from mpsupport.secondorder import point_array as array

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)


def smooth(x):
    return np.sin(3.0 * x[:, 0]) + x[:, 1] ** 2 + np.cos(2.0 * x[:, 2])


def linear(x):
    return 1.0 + 2.0 * x[:, 0] - 3.0 * x[:, 1] + 0.5 * x[:, 2]


def run(filter_class, target, source, lumped_bounded=False, bounded=False, lumped=False):
    options = dict(MassMatrix=1) if lumped_bounded or lumped else {}
    if lumped_bounded or bounded:
        options["PreserveBounds"] = True
    return project(target, source, filter_class, CacheOperator=False, **options)


tets = gmshmeshes.second_order("cube", 0.3)
target = meshes.extract(tets, np.ones(tets.GetNumberOfCells(), bool))
ids = numpy_to_vtkIdTypeArray(np.arange(target.GetNumberOfPoints(), dtype=np.int64), deep=True)
ids.SetName("origId")
target.GetPointData().AddArray(ids)
hexes = gmshmeshes.second_order("hexes", 0.26, False, True)
source = meshes.extract(gmshmeshes.moved(hexes, translate=(0.27, 0.13, -0.21)),
                        np.ones(hexes.GetNumberOfCells(), bool))
x = vtk_to_numpy(source.GetPoints().GetData())
add(source.GetPointData(), "s", smooth(x))
add(source.GetPointData(), "l", linear(x))

serial = run(meshprojection.vtkMeshProjectionFilter, target, source)
xt = vtk_to_numpy(serial.GetPoints().GetData())
serial_valid = array(serial, "vtkValidPointMask").astype(bool)
# This process's part: Input in blocks along x, Source at random.
n = target.GetNumberOfCells()
owner = mpi.blocks_along_x(target, size)
part = meshes.extract(target, owner == rank)
keep = np.random.default_rng(5).integers(0, size, source.GetNumberOfCells()) == rank
out = run(meshprojection.vtkPMeshProjectionFilter, part, meshes.extract(source, keep))

mine = array(out, "origId")
check(out.GetCellType(0) == 24 and out.GetNumberOfPoints() == part.GetNumberOfPoints(),
      "the output is the part of Input, quadratic tetrahedra")
valid = array(out, "vtkValidPointMask").astype(bool)
check(valid.any() and np.array_equal(valid, serial_valid[mine]), "valid mask as serial")
scale = np.ptp(array(serial, "s")[serial_valid])
off = np.max(np.abs(array(out, "s") - array(serial, "s")[mine])[valid], initial=0.0) / scale
largest = max(a[0] for a in mpi.allgather(controller, np.array([off])))
if rank == 0:
    print("tet10 <- hex20: %d processes, largest difference to serial %.3g of the range" % (size, largest))
check(off <= 1e-10, "the serial values (%.2g of the range off)" % off)
lin = np.max(np.abs(array(out, "l") - linear(xt[mine]))[valid], initial=0.0) / np.ptp(linear(xt))
check(lin <= 1e-9, "linear exact at every valid node (%.2g of its range)" % lin)
total = out.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
reference = serial.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
check(abs(total - reference) <= 1e-12 * max(1.0, abs(reference)),
      "integral %.15g, serial %.15g" % (total, reference))

# The first part's cells linear (their corners), the rest tet10; a Source
# covering the whole cube.
from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, VTK_TETRA, vtkUnstructuredGrid  # noqa: E402


def first_part_linear(grid, owner, linear, quadratic):
    """grid's cells, on their corners alone where owner is 0 (linear: its
    (type, nodes)), whole elsewhere (quadratic: (type, nodes))."""
    mixed = vtkUnstructuredGrid()
    mixed.SetPoints(grid.GetPoints())
    mixed.GetPointData().ShallowCopy(grid.GetPointData())
    for c in range(grid.GetNumberOfCells()):
        cell = grid.GetCell(c)
        kind, nodes = linear if owner[c] == 0 else quadratic
        mixed.InsertNextCell(kind, nodes, [cell.GetPointId(k) for k in range(nodes)])
    return mixed


def check_as_serial(name, serial, out, low, high):
    """A process's part `out` against the serial output: its valid mask, its
    values (1e-10 of the range), within the Source's range [low, high], the
    serial integral (1e-12). Gives the range of the serial values."""
    mine = array(out, "origId")
    valid = array(out, "vtkValidPointMask").astype(bool)  # (linear cells' mid nodes are unused)
    serial_valid = array(serial, "vtkValidPointMask").astype(bool)
    check(np.array_equal(valid, serial_valid[mine]), "%s: valid mask as serial" % name)
    scale = np.ptp(array(serial, "s")[serial_valid])
    off = np.max(np.abs(array(out, "s") - array(serial, "s")[mine])[valid], initial=0.0) / scale
    if rank == 0:
        print("%s: %.3g of the range from serial" % (name, off))
    check(valid.sum() > 0 and off <= 1e-10, "%s: the serial values (%.2g off)" % (name, off))
    u = array(out, "s")[valid]
    slack = 1e-13 * (high - low)
    check(u.min() >= low - slack and u.max() <= high + slack,
          "%s: within the Source's range (%.3g, %.3g in [%.3g, %.3g])" % (name, u.min(), u.max(), low, high))
    total = out.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
    reference = serial.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
    check(abs(total - reference) <= 1e-12 * max(1.0, abs(reference)),
          "%s: integral %.15g, serial %.15g" % (name, total, reference))
    return scale


mixed = first_part_linear(target, owner, (VTK_TETRA, 4), (24, 10))
covering = meshes.extract(hexes, np.ones(hexes.GetNumberOfCells(), bool))
grown = vtk_to_numpy(covering.GetPoints().GetData())
grown[:] = 0.5 + 1.04 * (grown - 0.5)  # (the extract's own copy of the points)
covering.GetPoints().Modified()
add(covering.GetPointData(), "s", smooth(vtk_to_numpy(covering.GetPoints().GetData())))
part_mixed = meshes.extract(mixed, owner == rank)
part_covering = meshes.extract(
    covering, np.random.default_rng(6).integers(0, size, covering.GetNumberOfCells()) == rank)
low, high = array(covering, "s").min(), array(covering, "s").max()
for how, options in (("lumped and bounded", dict(lumped_bounded=True)), ("bounded", dict(bounded=True))):
    serial_mixed = run(meshprojection.vtkMeshProjectionFilter, mixed, covering, **options)
    out = run(meshprojection.vtkPMeshProjectionFilter, part_mixed, part_covering, **options)
    scale = check_as_serial("mixed tet4 + tet10, %s" % how, serial_mixed, out, low, high)

# Point labels onto the mixed Input: the serial labels.
xs = vtk_to_numpy(covering.GetPoints().GetData())
add(covering.GetPointData(), "Region", ((xs[:, 0] > 0.45).astype(np.int32) + 2 * (xs[:, 2] > 0.6)).astype(np.int32))
part_covering = meshes.extract(
    covering, np.random.default_rng(6).integers(0, size, covering.GetNumberOfCells()) == rank)
labelled = []
for filter_class, target_part, source_part in ((meshprojection.vtkMeshProjectionFilter, mixed, covering),
                                               (meshprojection.vtkPMeshProjectionFilter, part_mixed, part_covering)):
    f = filter_class()
    f.SetInputData(target_part)
    f.SetSourceData(source_part)
    f.SetCacheOperator(False)
    f.AddCategoricalArray("Region")
    f.Update()
    labelled.append(f.GetOutput())
mine = array(labelled[1], "origId")
valid = array(labelled[1], "vtkValidPointMask").astype(bool)
same = np.array_equal(array(labelled[1], "Region")[valid], array(labelled[0], "Region")[mine][valid])
check(valid.sum() > 0 and same, "mixed tet4 + tet10: point labels as serial (%d valid)" % valid.sum())

# The whole mixed Input on the first process (the others' parts empty),
# Lumped and PreserveBounds: the empty parts take part in the bounded
# solve's collective steps, every process ends, the first gives serial.
alone = meshes.extract(mixed, np.full(n, rank == 0))
for how, options in (("lumped and bounded", dict(lumped_bounded=True)), ("bounded", dict(bounded=True))):
    serial_mixed = run(meshprojection.vtkMeshProjectionFilter, mixed, covering, **options)
    out = run(meshprojection.vtkPMeshProjectionFilter, alone, part_covering, **options)
    if rank == 0:
        valid = array(out, "vtkValidPointMask").astype(bool)
        off = np.max(np.abs(array(out, "s") - array(serial_mixed, "s"))[valid], initial=0.0)
        check(valid.any() and off <= 1e-10 * scale,
              "mixed Input on one process, %s: the serial values (%.2g off)" % (how, off))
    else:
        check(out.GetNumberOfPoints() == 0, "mixed Input on one process, %s: an empty part ends empty" % how)

# Lumped onto a mixed Input of linear hexahedra (the first part) and
# hex20, inside a tet10 Source that covers it: every process clips the
# signed form's coefficients, the first with no hex20 too.
from vtkmodules.util.numpy_support import numpy_to_vtk  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
hex_input = meshes.extract(hexes, np.ones(hexes.GetNumberOfCells(), bool))
hex_input.GetPointData().AddArray(numpy_to_vtkIdTypeArray(
    np.arange(hex_input.GetNumberOfPoints(), dtype=np.int64), deep=True))
hex_input.GetPointData().GetArray(0).SetName("origId")
hex_owner = mpi.blocks_along_x(hex_input, size)
mixed_hexes = first_part_linear(hex_input, hex_owner, (VTK_HEXAHEDRON, 8), (25, 20))
tet_cover = meshes.extract(tets, np.ones(tets.GetNumberOfCells(), bool))
grown_points = vtkPoints()  # (new points: the others' stay as they are)
grown_points.SetData(numpy_to_vtk(0.5 + 1.04 * (vtk_to_numpy(tet_cover.GetPoints().GetData()) - 0.5), deep=True))
tet_cover.SetPoints(grown_points)
add(tet_cover.GetPointData(), "s", smooth(vtk_to_numpy(tet_cover.GetPoints().GetData())))
part_hexes = meshes.extract(mixed_hexes, hex_owner == rank)
part_tets = meshes.extract(
    tet_cover, np.random.default_rng(7).integers(0, size, tet_cover.GetNumberOfCells()) == rank)
low, high = array(tet_cover, "s").min(), array(tet_cover, "s").max()
for how, options in (("lumped", dict(lumped=True)), ("lumped and bounded", dict(lumped_bounded=True))):
    serial_h = run(meshprojection.vtkMeshProjectionFilter, mixed_hexes, tet_cover, **options)
    out = run(meshprojection.vtkPMeshProjectionFilter, part_hexes, part_tets, **options)
    check_as_serial("hex8 + hex20, %s" % how, serial_h, out, low, high)

# CurvedCellSubdivision 2 and 3 on curved pairs: the serial results.
check_curved_levels(controller, check)

check.finish("%d processes, second-order cells" % size)
