"""CellDataReconstruction: what second-order cell data costs against first
order, and what it gains, on the same meshes in the same run.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_reconstruction.py \\
        [--sizes 2D:1e6,3D:1e6] [--accuracy 2D:1e4,3D:1e4] [--repeats 3]

(PYTHONPATH: the build's `meshprojection` and `mpsupport` packages; see README.md here.)

Cost: cell data to cells on jittered square (triangles) and cube
(tetrahedra) pairs of mpbench, the Source about 0.8 times as many cells on
a slightly shifted box, one smooth cell array; each pair as generated and
with both meshes' numberings shuffled. Per mode (0 constant, 1 limited,
2 linear) and thread count: the best of `repeats` fresh runs (search,
assembly, reconstruction and solve), and its ratio to mode 0 on the same
pair (the modes run in turn, round after round); then a later step with
kept operators (a time series on fixed
meshes: the reconstruction and the solve only).

Accuracy: the L1 error of the target's cell averages of
sin(2x) cos(3y) + z^2 + x/2 (exact means, quadrature exact for quadratics,
on the Source and the target), the Source 4 times coarser than the target
(per axis), at two resolutions, and the observed order. Prints Markdown.
"""
import argparse
import time

import numpy as np
from mpbench import cube_mesh, shifted_pair, shuffled, square_mesh, timed_run, to_grid
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

from mpsupport import meshes

MODES = ((0, "constant"), (1, "limited"), (2, "linear"))


def smooth(x):
    return np.sin(2 * x[..., 0]) * np.cos(3 * x[..., 1]) + x[..., 2] ** 2 + 0.5 * x[..., 0]


def with_means(mesh):
    """The grid with the cell array "u": the exact means of `smooth`; and the means and measures."""
    points, cells, kind = mesh
    corners = points[cells]
    grid = to_grid(points, cells, kind)
    means = meshes.simplex_means(corners, smooth)
    u = numpy_to_vtk(means, deep=1)
    u.SetName("u")
    grid.GetCellData().AddArray(u)
    e = corners[:, 1:] - corners[:, :1]
    if cells.shape[1] == 3:
        measure = 0.5 * np.abs(e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0])
    else:
        measure = np.abs(np.einsum("ij,ij->i", e[:, 0], np.cross(e[:, 1], e[:, 2]))) / 6
    return grid, means, measure


def later_step(target, source, mode, threads, repeats):
    """The best time of a step with kept operators (the Source's array changed in place)."""
    import meshprojection
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetNumberOfThreads(threads)
    f.SetCellDataReconstruction(mode)
    array = source.GetCellData().GetArray("u")
    values = vtk_to_numpy(array)
    best = None
    for step in range(repeats + 2):  # (the second run assembles and keeps the operators)
        values *= 1.01
        array.Modified()
        start = time.perf_counter()
        f.Update()
        seconds = time.perf_counter() - start
        if step >= 2:
            assert f.GetOperatorReused()
            best = seconds if best is None else min(best, seconds)
    return best


def cost(sizes, repeats):
    print("| pair | numbering | threads | constant (s) | limited (s) | ratio | linear (s) | ratio | later step: constant / limited (s) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for dim, cells in sizes:
        t, s = shifted_pair(dim, cells)
        for numbering in ("as generated", "shuffled"):
            tm, sm = (t, s) if numbering == "as generated" else (shuffled(t, 3), shuffled(s, 4))
            target, _, _ = with_means(tm)
            target.GetCellData().Initialize()
            source, _, _ = with_means(sm)
            for threads in (1, 2):
                # Rounds of the three modes in turn: a slower spell of the
                # machine falls on all of them alike.
                times = {mode: float("inf") for mode, _ in MODES}
                for _ in range(repeats):
                    for mode, _ in MODES:
                        times[mode] = min(times[mode], timed_run(target, source, threads, CellDataReconstruction=mode)[0])
                steps = [later_step(target, source, mode, threads, repeats) for mode in (0, 1)]
                print("| %dD %.0e cells | %s | %d | %.3f | %.3f | %.2f | %.3f | %.2f | %.3f / %.3f |" % (
                    dim, target.GetNumberOfCells(), numbering, threads, times[0], times[1],
                    times[1] / times[0], times[2], times[2] / times[0], steps[0], steps[1]))


def accuracy(sizes):
    print("| pair | Source → target cells | constant L1 | limited L1 | linear L1 |")
    print("|---|---|---|---|---|")
    for dim, cells in sizes:
        errors = []
        for scale in (1, 2):
            if dim == 2:
                n = int(round(np.sqrt(cells / 2.0))) * scale
                tm, sm = square_mesh(n, n, 5), square_mesh(n // 4, n // 4, 6)
            else:
                n = int(round((cells / 6.0) ** (1.0 / 3))) * scale
                tm, sm = cube_mesh(n, n, n, 5), cube_mesh(max(1, n // 4), max(1, n // 4), max(1, n // 4), 6)
            target, exact, measure = with_means(tm)
            target.GetCellData().Initialize()
            source, _, _ = with_means(sm)
            row = []
            for mode, _ in MODES:
                _, f = timed_run(target, source, 2, CellDataReconstruction=mode)
                got = vtk_to_numpy(f.GetOutput().GetCellData().GetArray("u"))
                row.append(float(np.sum(np.abs(got - exact) * measure)))
            errors.append(row)
            print("| %dD | %d → %d | %.3e | %.3e | %.3e |" % (
                dim, source.GetNumberOfCells(), target.GetNumberOfCells(), row[0], row[1], row[2]))
        orders = [np.log2(errors[0][k] / errors[1][k]) for k in range(3)]
        print("| %dD | observed order | %.2f | %.2f | %.2f |" % (dim, orders[0], orders[1], orders[2]))


def parse(text):
    out = []
    for item in text.split(","):
        dim, count = item.split(":")
        out.append((int(dim.rstrip("D")), int(float(count))))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="2D:1e6,3D:1e6")
    parser.add_argument("--accuracy", default="2D:2e4,3D:2e4")
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    cost(parse(args.sizes), args.repeats)
    print()
    accuracy(parse(args.accuracy))


if __name__ == "__main__":
    main()
