"""The fringe and extrapolation on several MPI processes (run under mpiexec
with pvbatch --mpi --symmetric), on pairs that overlap in part (Gmsh's 2D
triangles, 3D tetrahedra and hexahedra; jittered Kuhn tetrahedra with a
corner poking out of the Source; Gmsh sphere caps, straight polylines in
3D, and a Gmsh sphere and an arc half out of a box, traces): Input split in blocks
along x, Source at random.

Each process finds the fringe's stencils in the target's halo (the other
processes' cells within FringeSearchRings (6) rings of its points), as the
serial run finds them in the whole target: the result is the serial one. Checked on
every process, for its points:
 - the valid points' values equal the serial ones to 1e-10 of the field's
   range, and the valid mask is the serial one;
 - the worst error at a valid point within 5x the worst at interior points
   (the interior measured by the serial run), the linear field exact
   (but between the two facetizations of the caps);
 - the masks: vtkExtrapolatedPointMask exactly where not valid
   (Extrapolation 1), and every point then finite, within the range of
   the valid values (over all processes) and equal to the serial value
   (the creep fill);
 - shared points: one value on every process (bit for bit away from the
   fringe; an aggregated point's extension is summed in each process's
   order of its stencil, to 1e-14 of the range);
 - the integral over the covered part (a total over the processes) equals
   the serial one.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_LINE, VTK_TETRA
from vtkmodules.vtkFiltersCore import vtkCellCenters

from mpsupport import gmshmeshes, meshes, mpi
from mpsupport.mpi import add
from mpsupport.fringe import fully_covered, linear, point_cells, smooth
from mpsupport.secondorder import point_array as array
from mpsupport.secondorder import project

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)


def grid(mesh, numbered=True):
    """mesh as a vtkUnstructuredGrid, with origId on its points when numbered."""
    g = meshes.extract(mesh, np.ones(mesh.GetNumberOfCells(), bool))
    if not numbered:
        return g
    a = numpy_to_vtkIdTypeArray(np.arange(g.GetNumberOfPoints(), dtype=np.int64), deep=True)
    a.SetName("origId")
    g.GetPointData().AddArray(a)
    return g


def with_fields(g):
    x = vtk_to_numpy(g.GetPoints().GetData())
    add(g.GetPointData(), "s", smooth(x))
    add(g.GetPointData(), "l", linear(x))
    return g


def run(filter_class, target, source, **props):
    return project(target, source, filter_class, CacheOperator=False, **props)


def interior_points(out):
    return fully_covered(vtk_to_numpy(out.GetCellData().GetArray("CoveredFraction")), point_cells(out))


def kuhn(n):
    """The unit cube as a jittered n^3 grid of cubes, six tetrahedra each."""
    return meshes.grid(*meshes.tetrahedra(n, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), n), VTK_TETRA)


def segment(t0, t1, n, seed):
    """A straight polyline in 3D, its inner points jittered along it."""
    t = np.linspace(t0, t1, n + 1)
    t[1:-1] += np.random.default_rng(seed).uniform(-0.3, 0.3, n - 1) * (t1 - t0) / n
    x = np.stack([0.2 + 0.6 * t, 0.1 + 0.3 * t, 0.4 - 0.5 * t], 1)
    return meshes.grid(x, np.stack([np.arange(n), np.arange(1, n + 1)], 1), VTK_LINE)


def arc(t0, t1, n, seed, tilt):
    """An arc of the unit circle about the origin in a plane tilted about x, its inner points jittered."""
    t = np.linspace(t0, t1, n + 1)
    t[1:-1] += np.random.default_rng(seed).uniform(-0.3, 0.3, n - 1) * (t1 - t0) / n
    x = np.stack([np.cos(t), np.sin(t) * np.cos(tilt), np.sin(t) * np.sin(tilt)], 1)
    return meshes.grid(x, np.stack([np.arange(n), np.arange(1, n + 1)], 1), VTK_LINE)


pairs = [
    # (name, Input, Source, a linear field exact)
    ("2D triangles", grid(gmshmeshes.moved(gmshmeshes.planar(0.05), translate=(0.31, 0.17, 0))),
     with_fields(grid(gmshmeshes.planar(0.065), False)), True),
    ("3D tetrahedra", grid(gmshmeshes.moved(gmshmeshes.volume("box", 0.1), translate=(0.27, 0.13, 0.21))),
     with_fields(grid(gmshmeshes.volume("box", 0.13), False)), True),
    # A corner whose points find stencils only beyond FringeRings rings:
    # the halo reaches FringeSearchRings rings.
    ("3D tetrahedra, corner", grid(gmshmeshes.moved(kuhn(10), translate=(-0.2, 0.33, 0.11))),
     with_fields(grid(kuhn(8), False)), True),
    # Surfaces, curves and traces: stencils fitted in each point's tangent
    # frame, from the cells around it in the halo. (Two facetizations of
    # the sphere: a linear field is not exact between them.)
    ("sphere caps", grid(gmshmeshes.moved(gmshmeshes.surface("cap", 0.08, 6), rotate_x=20)),
     with_fields(grid(gmshmeshes.surface("cap", 0.1, 5), False)), False),
    ("straight polylines", grid(segment(0.0, 1.0, 30, 1)), with_fields(grid(segment(0.37, 1.4, 23, 2), False)), True),
    ("trace: a sphere half out of a box", grid(gmshmeshes.surface("sphere", 0.08)),
     with_fields(grid(gmshmeshes.volume("box", 0.1), False)), True),
    # A curved curve leaving the box: its end extended through the normal
    # offsets of points up to FringeSearchRings rings back (linear exact).
    ("trace: an arc leaving a box", grid(arc(0.3, 2.2, 25, 2, 0.9)),
     with_fields(grid(gmshmeshes.volume("box", 0.1), False)), True),
    # Hexahedra without GlobalIds: each process splits its cells by its own
    # point ids, as the serial run does (by ids made across the processes
    # the cells on a border between parts were split otherwise: 0.35% of
    # the range off).
    ("3D hexahedra", grid(gmshmeshes.moved(gmshmeshes.hexahedra(0.1, False), translate=(0.27, -0.19, 0.13))),
     with_fields(grid(gmshmeshes.hexahedra(0.13, False), False)), True),
]
for name, target, source, linear_exact in pairs:
    serial = run(meshprojection.vtkMeshProjectionFilter, target, source)
    x = vtk_to_numpy(serial.GetPoints().GetData())
    serial_valid = array(serial, "vtkValidPointMask").astype(bool)
    inside = interior_points(serial) & serial_valid
    interior_error = np.max(np.abs(array(serial, "s") - smooth(x))[inside])
    # This process's part: Input in blocks along x, Source at random.
    centres = vtkCellCenters()
    centres.SetInputData(target)
    centres.Update()
    cx = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())[:, 0]
    n = target.GetNumberOfCells()
    owner = np.minimum((np.argsort(np.argsort(cx)) * size) // n, size - 1)
    part = meshes.extract(target, owner == rank)
    keep = np.random.default_rng(8).integers(0, size, source.GetNumberOfCells()) == rank
    local_source = meshes.extract(source, keep)
    for mode in (0, 1):
        out = run(meshprojection.vtkPMeshProjectionFilter, part, local_source, Extrapolation=mode)
        serial = run(meshprojection.vtkMeshProjectionFilter, target, source, Extrapolation=mode)
        serial_valid = array(serial, "vtkValidPointMask").astype(bool)
        ids = array(out, "origId")
        # Points on several processes (by their original ids).
        counts = np.zeros(target.GetNumberOfPoints())
        for r, theirs in enumerate(mpi.allgather(controller, ids.astype(np.float64))):
            counts[np.asarray(theirs, dtype=np.int64)] += 1
        shared = counts[ids] > 1
        valid = array(out, "vtkValidPointMask").astype(bool)
        u = array(out, "s")
        error = np.abs(u - smooth(x[ids]))
        worst = np.max(error[valid], initial=0.0) / interior_error
        check(worst <= 5, "%s: fringe error %.2f x the interior's" % (name, worst))
        exact = linear(x[ids])
        lin = np.max(np.abs(array(out, "l") - exact)[valid], initial=0.0) / np.ptp(linear(x))
        check(lin < 1e-8 or not linear_exact, "%s: linear exact (%.2g of its range)" % (name, lin))
        check(np.array_equal(valid, serial_valid[ids]), "%s: valid mask as serial" % name)
        both_valid = valid & serial_valid[ids]
        scale = np.ptp(array(serial, "s")[serial_valid])
        off = np.max(np.abs(u - array(serial, "s")[ids])[both_valid], initial=0.0) / scale
        largest = max(a[0] for a in mpi.allgather(controller, np.array([off])))
        if rank == 0 and mode == 0:
            print("%s: %d processes, largest difference to serial %.3g of the range" % (name, size, largest))
        check(off <= 1e-10, "%s: the serial values (%.2g of the range off)" % (name, off))
        # Shared points: one value on every process (bit for bit away from the fringe).
        mine = np.full(target.GetNumberOfPoints(), -np.inf)
        mine[ids] = u
        for theirs_ids, theirs_u in zip(mpi.allgather(controller, ids.astype(np.float64)),
                                        mpi.allgather(controller, u)):
            t_ids = np.asarray(theirs_ids, dtype=np.int64)
            both = np.isin(t_ids, ids)
            same = np.asarray(theirs_u)[both]
            here = mine[t_ids[both]]
            away = inside[t_ids[both]]
            check(np.array_equal(np.isnan(same), np.isnan(here)) and
                  np.array_equal(same[away & ~np.isnan(same)], here[away & ~np.isnan(here)]) and
                  np.max(np.abs(same - here)[~np.isnan(same)], initial=0.0) <= 1e-14 * scale,
                  "%s: shared points have one value" % name)
        if mode == 1:
            # A creep fill's values are means of valid ones: within their range.
            low, high = (f(array(serial, "s")[serial_valid]) for f in (np.min, np.max))
            check(np.isfinite(u).all() and u.min() >= low - 1e-12 and u.max() <= high + 1e-12,
                  "%s: extrapolated within the valid values' range [%g, %g]: %d not finite, %g..%g, at shared %s"
                  % (name, low, high, np.count_nonzero(~np.isfinite(u)), np.nanmin(u), np.nanmax(u), shared[~np.isfinite(u)].all()))
            check(np.array_equal(array(out, "vtkExtrapolatedPointMask").astype(bool), ~valid),
                  "%s: vtkExtrapolatedPointMask marks the values not valid" % name)
            # The creep fill over the point graph (layers and means completed
            # across the processes) is the serial one.
            reference = array(serial, "s")[ids]
            beyond = np.max(np.abs(u - reference)[~valid], initial=0.0) / scale
            check(beyond <= 1e-10, "%s: extrapolated values as serial (%.2g of the range off)" % (name, beyond))
        else:
            total = out.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
            reference = serial.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
            check(abs(total - reference) <= 1e-12 * max(1.0, abs(reference)),
                  "%s: integral %.15g, serial %.15g" % (name, total, reference))

check.finish("%d processes, fringe" % size)
