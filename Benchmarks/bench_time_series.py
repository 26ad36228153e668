"""What a later time step costs when the meshes do not move.

    PYTHONPATH=build/lib/python3/dist-packages pvpython Benchmarks/bench_time_series.py [--steps 6]

(PYTHONPATH: the build's `meshprojection` and `mpsupport` packages; see README.md here.)

On 10^5 triangles and 10^4 tetrahedra (jittered non-matching pairs of mpbench,
as in bench_pvpython.py) a time series of Source fields on fixed meshes is
projected through vtkMeshProjectionFilter, as a reader would hand it over:
every step is a new vtkUnstructuredGrid with new (equal) point and cell
arrays and a new point field and cell field, handed over with SetSourceData
(no TIME_STEPS: the filter cannot know a series is coming). Each step's
Update() is timed (wall clock, one thread) with CacheOperator on and off.
On: step 1 is a one-off run (right-hand sides summed in the search), step 2
finds the same meshes and assembles the operators, steps 3+ reuse them and
start the solve from the previous solution. (A reader that advertises time
steps, e.g. a PVD series, gets the assembled operators at step 1.) Off:
every step builds everything. Prints a Markdown table.
"""
import argparse
import statistics
import sys
import time

import numpy as np
from mpbench import cube_mesh, square_mesh, to_grid
from vtkmodules.util.numpy_support import numpy_to_vtk


def step_grid(points, cells, cell_type, t):
    """A reader's output at time t: fresh copies of the geometry, fresh fields."""
    grid = to_grid(points.copy(), cells.copy(), cell_type,
                   np.sin(4 * points[:, 0] + t) * np.cos(3 * points[:, 1]) + t)
    centroid = points[cells].mean(axis=1)
    heat = numpy_to_vtk(1 + (centroid[:, 0] > 0.5 + 0.05 * t) * (1 + t), deep=1)
    heat.SetName("heat")
    grid.GetCellData().AddArray(heat)
    return grid


def run(case, target, source, steps, cache):
    from meshprojection import vtkMeshProjectionFilter
    f = vtkMeshProjectionFilter()
    f.SetCacheOperator(cache)
    f.SetNumberOfThreads(1)  # one thread, as docs/performance.md states
    f.SetInputData(to_grid(*target))
    times, inside = [], []
    for k in range(steps):
        f.SetSourceData(step_grid(*source, 0.3 * k))
        start = time.perf_counter()
        f.Update()
        times.append(time.perf_counter() - start)
        inside.append(f.GetExecutionTime())
        if cache and k > 1 and not f.GetOperatorReused():
            raise SystemExit("%s: the operator was not reused at step %d" % (case, k))
    later = statistics.median(times[2:])
    return times[0], times[1], later, f.GetOperatorMemory() if cache else 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--steps", type=int, default=6)
    args = parser.parse_args()
    cases = [
        ("2D, %d triangles" % (2 * 224 * 224), square_mesh(224, 224, 1), square_mesh(211, 211, 2)),
        ("3D, %d tetrahedra" % (6 * 12 ** 3), cube_mesh(12, 12, 12, 3), cube_mesh(11, 11, 11, 4)),
    ]
    print("| meshes (target) | cache | step 1 (s) | step 2 (s) | steps 3+, median (s) | 3+ / 1 | operator memory (MB) |")
    print("|---|---|---|---|---|---|---|")
    for case, target, source in cases:
        for cache in (True, False):
            first, second, later, memory = run(case, target, source, args.steps, cache)
            print("| %s | %s | %.3f | %.3f | %.3f | %.2f | %.1f |"
                  % (case, "on" if cache else "off", first, second, later, later / first, memory / 1e6))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
