"""What the fringe's aggregation and the extrapolation cost, on pairs that
overlap in part: the jittered unit square (2D, about 10^6 triangles each)
and cube (3D) meshes of mpbench, Input moved by (0.3, 0.2[, 0.1]) so that a
third or more of it lies beyond the Source.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_fringe.py [--scale 1] [--threads 1]

(PYTHONPATH: the build's `meshprojection` and `mpsupport` packages; see README.md here.)

Each row is the best of `--repeats` fresh runs (CacheOperator off) of one
point field: the plain projection (FringeThreshold 0), the default (the
fringe aggregated), and the default with Extrapolation Smooth and Nearest;
columns: the filter's total in seconds, its ratio to the plain projection,
and the invalid points (those an extrapolation fills). Prints Markdown.
"""
import argparse
import time

import numpy as np
from mpbench import cube_mesh, square_mesh, to_grid
from vtkmodules.util.numpy_support import vtk_to_numpy


def run(target, source, threads, repeats, **properties):
    import meshprojection
    best = None
    for _ in range(repeats):
        f = meshprojection.vtkMeshProjectionFilter()
        f.SetInputData(target)
        f.SetSourceData(source)
        f.SetNumberOfThreads(threads)
        f.SetCacheOperator(False)
        for name, value in properties.items():
            getattr(f, "Set" + name)(value)
        start = time.perf_counter()
        f.Update()
        seconds = time.perf_counter() - start
        if best is None or seconds < best[0]:
            best = (seconds, f)
    return best


def pair(dim, scale):
    if dim == 2:
        n = int(round(707 * np.sqrt(scale)))
        target = square_mesh(n, n, 1)
        source = square_mesh(int(n * 0.93), int(n * 0.93), 2)
        shift = (0.3, 0.2, 0.0)
    else:
        n = int(round(55 * scale ** (1 / 3)))
        target = cube_mesh(n, n, n, 1)
        source = cube_mesh(int(n * 0.93), int(n * 0.93), int(n * 0.93), 2)
        shift = (0.3, 0.2, 0.1)
    points = np.array(target[0], dtype=np.float64) + np.array(shift)
    x = np.asarray(source[0])
    field = np.sin(2 * x[:, 0]) * np.cos(3 * x[:, 1]) + x[:, 2] ** 2
    return to_grid(points, target[1], target[2]), to_grid(source[0], source[1], source[2], field)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--scale", type=float, default=1.0, help="Input cells / 10^6")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--dims", default="2,3")
    args = parser.parse_args()
    print("| pair | Input cells | case | seconds | vs plain | invalid points |")
    print("|---|---|---|---|---|---|")
    for dim in (int(d) for d in args.dims.split(",")):
        target, source = pair(dim, args.scale)
        cases = [("plain (FringeThreshold 0)", dict(FringeThreshold=0)), ("fringe aggregated (default)", {}),
                 ("+ Extrapolation Smooth", dict(Extrapolation=1)), ("+ Extrapolation Nearest", dict(Extrapolation=2))]
        plain = None
        for name, properties in cases:
            seconds, f = run(target, source, args.threads, args.repeats, **properties)
            plain = plain or seconds
            valid = vtk_to_numpy(f.GetOutput().GetPointData().GetArray("vtkValidPointMask"))
            print("| %dD | %d | %s | %.3f | %.3f | %d |" % (dim, target.GetNumberOfCells(), name, seconds,
                                                          seconds / plain, np.count_nonzero(valid == 0)))


if __name__ == "__main__":
    main()
