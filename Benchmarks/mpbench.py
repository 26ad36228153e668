"""What the benchmark scripts share: the filter timed on a pair, as docs/performance.md
reports it, and the jittered pairs of the unit square and cube (the meshes of
mpsupport.meshes, shared with the tests) as numpy arrays and VTK grids."""
import time

import numpy as np
from mpsupport import meshes
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE

UNIT = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))


def square_mesh(nx, ny, seed):
    """Triangles of a jittered nx x ny grid of the unit square: (points, cells, type)."""
    return (*meshes.triangles((nx, ny), *UNIT, seed, jitter=0.25), VTK_TRIANGLE)


def cube_mesh(nx, ny, nz, seed):
    """Tetrahedra (six per cube, conforming) of a jittered nx x ny x nz grid
    of the unit cube: (points, cells, type). Less jitter than the square's:
    tetrahedra invert sooner."""
    return (*meshes.tetrahedra((nx, ny, nz), *UNIT, seed, jitter=0.15), VTK_TETRA)


def to_grid(points, cells, cell_type, field=None):
    """A vtkUnstructuredGrid wrapping the points' numpy buffer (not copied),
    with `field` as the point array "u"."""
    grid = meshes.grid(points, cells, cell_type, deep=False)
    if field is not None:
        u = numpy_to_vtk(np.ascontiguousarray(field), deep=1)
        u.SetName("u")
        grid.GetPointData().AddArray(u)
    return grid


def timed_run(target, source, threads):
    """One fresh run of the filter on `threads` threads (CacheOperator off:
    search, assembly and solve each run): (seconds, the filter)."""
    import meshprojection
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetNumberOfThreads(threads)
    f.SetCacheOperator(False)
    start = time.perf_counter()
    f.Update()
    return time.perf_counter() - start, f


def best_run(target, source, threads, repeats):
    """The best of `repeats` fresh runs of the filter on `threads` threads:
    (seconds, input, neighbours, search, solve, pieces)."""
    best = None
    for _ in range(repeats):
        seconds, f = timed_run(target, source, threads)
        if best is None or seconds < best[0]:
            best = (seconds, f.GetInputTime(), f.GetNeighborsTime(), f.GetSearchTime(), f.GetSolveTime(),
                    f.GetNumberOfIntersections())
    return best


def time_filter(target, source, threads=(1, 2), repeats=2):
    """Prints the best of `repeats` runs of the filter on each thread count,
    with its stages (input, neighbours, search, solve) and pieces."""
    for count in threads:
        print("%d thread(s): %.3f s (input %.3f, neighbours %.3f, search %.3f, solve %.3f), %d pieces" %
              ((count,) + best_run(target, source, count, repeats)))
