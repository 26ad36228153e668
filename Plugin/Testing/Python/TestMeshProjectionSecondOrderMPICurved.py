"""Curved second-order pairs that overlap in part, on several MPI processes
(run under mpiexec with pvbatch --mpi --symmetric), with the fringe
(FringeThreshold at its default) and with Extrapolation Smooth: a Gmsh
tet10 ball (its boundary mid nodes on the sphere) and Gmsh hex20 and hex27
cubes bent by a smooth map (every cell curved), each way; a Gmsh tri6 disk
and a quad9 disk (mid nodes on the circle), each way; straight quad9 and
tet10 Inputs whose fringe extends nodes by root cells (the halo carries
the cells' parents). Input in blocks
along x, Source dealt at random, projected by vtkPMeshProjectionFilter
against the serial filter. On every process, for its points (by their
original ids):
 - the valid mask is the serial one, and the valid values of a smooth
   field equal the serial ones to 1e-10 of its range;
 - a linear field is exact at every valid node (1e-9 of its range);
 - the integral over the covered part (a total over the processes) equals
   the serial one (1e-12);
 - with Extrapolation Smooth (the ball's and the tri6 disk's Input) every
   node is finite and the extrapolated values equal the serial ones (1e-10
   of the range).
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid

from mpsupport import gmshmeshes, meshes, mpi
from mpsupport.fringe import linear, with_fields
from mpsupport.secondorder import point_array as array
from mpsupport.secondorder import project

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)


def grid(mesh, transform=None):
    """A copy of mesh (a vtkUnstructuredGrid of its own points), its points through transform."""
    g = vtkUnstructuredGrid()
    g.DeepCopy(meshes.extract(mesh, np.ones(mesh.GetNumberOfCells(), bool)))  # (extracting all cells shares the points)
    if transform is not None:
        x = vtk_to_numpy(g.GetPoints().GetData())
        x[:] = transform(x.copy())
        g.GetPoints().Modified()
    return g


def numbered(g):
    a = numpy_to_vtkIdTypeArray(np.arange(g.GetNumberOfPoints(), dtype=np.int64), deep=True)
    a.SetName("origId")
    g.GetPointData().AddArray(a)
    return g


def run(filter_class, target, source, **properties):
    return project(target, source, filter_class, CacheOperator=False, **properties)


def bend(x):
    return x + 0.04 * np.stack([np.sin(3 * x[:, 1]), np.sin(3 * x[:, 2]), np.sin(3 * x[:, 0])], 1)


so = gmshmeshes.second_order
ball = so("ball", 0.2)
hex20 = so("hexes", 0.25, False, True)
hex27 = so("hexes", 0.34)
disk_tri6 = so("disk", 0.2)
disk_quad9 = so("disk", 0.25, True)
pairs = [
    # (name, Input, Source, Extrapolation modes)
    ("curved tet10 ball <- bent hex20", numbered(grid(ball)),
     with_fields(grid(hex20, lambda x: bend(x) + [0.45, 0.2, -0.3])), (0, 1)),
    ("bent hex27 <- curved tet10 ball", numbered(grid(hex27, lambda x: bend(x) + [0.4, -0.3, 0.25])),
     with_fields(grid(ball)), (0,)),
    ("curved tri6 disk <- quad9 disk", numbered(grid(disk_tri6)),
     with_fields(grid(disk_quad9, lambda x: x + [0.6, -0.3, 0.0])), (0, 1)),
    ("curved quad9 disk <- tri6 disk", numbered(grid(disk_quad9, lambda x: x + [-0.5, 0.45, 0.0])),
     with_fields(grid(disk_tri6)), (0,)),
    # Straight pairs whose fringe takes root cells' own functions (FringeRoots.h), some across the parts.
    ("straight quad9 <- tri6", numbered(grid(so("square", 0.078, True), lambda x: x + [0.4, 0.1, 0.0])),
     with_fields(grid(so("square", 0.06))), (0,)),
    ("straight tet10 <- hex20", numbered(grid(so("cube", 0.14), lambda x: x + [0.27, 0.13, 0.21])),
     with_fields(grid(so("hexes", 0.14, False, True))), (0,)),
]
for name, target, source, modes in pairs:
    # This process's part: Input in blocks along x, Source at random.
    part = meshes.extract(target, mpi.blocks_along_x(target, size) == rank)
    keep = np.random.default_rng(9).integers(0, size, source.GetNumberOfCells()) == rank
    local_source = meshes.extract(source, keep)
    x = vtk_to_numpy(target.GetPoints().GetData())
    for mode in modes:
        serial = run(meshprojection.vtkMeshProjectionFilter, target, source, Extrapolation=mode)
        out = run(meshprojection.vtkPMeshProjectionFilter, part, local_source, Extrapolation=mode)
        ids = array(out, "origId")
        serial_valid = array(serial, "vtkValidPointMask").astype(bool)
        valid = array(out, "vtkValidPointMask").astype(bool)
        check(serial_valid.any() and not serial_valid.all(), "%s: the pair overlaps in part" % name)
        check(np.array_equal(valid, serial_valid[ids]), "%s, Extrapolation %d: valid mask as serial" % (name, mode))
        u = array(out, "s")
        scale = np.ptp(array(serial, "s")[serial_valid])
        both = valid & serial_valid[ids]
        off = np.max(np.abs(u - array(serial, "s")[ids])[both], initial=0.0) / scale
        largest = max(a[0] for a in mpi.allgather(controller, np.array([off])))
        if rank == 0 and mode == 0:
            print("%s: %d processes, largest difference to serial %.3g of the range" % (name, size, largest))
        check(off <= 1e-10, "%s, Extrapolation %d: the serial values (%.2g of the range off)" % (name, mode, off))
        lin = np.max(np.abs(array(out, "l") - linear(x[ids]))[valid], initial=0.0) / np.ptp(linear(x))
        check(lin <= 1e-9, "%s: linear exact at every valid node (%.2g of its range)" % (name, lin))
        if mode == 0:
            total = out.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
            reference = serial.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
            check(abs(total - reference) <= 1e-12 * max(1.0, abs(reference)),
                  "%s: integral %.15g, serial %.15g" % (name, total, reference))
        else:
            beyond = np.max(np.abs(u - array(serial, "s")[ids])[~valid], initial=0.0) / scale
            check(np.isfinite(u).all() and beyond <= 1e-10,
                  "%s: every node finite, extrapolated as serial (%.2g of the range off)" % (name, beyond))

check.finish("%d processes, curved second-order cells with the fringe" % size)
