"""The filter against MEDCoupling's remapper (SALOME's MEDCouplingRemapper,
PyPI `medcoupling`) on the same meshes in the same run: cell data to cells
(MEDCoupling's P0P0 with the IntensiveMaximum nature, the mean over the
covered part of each target cell: the filter's P0 projection).

    pip install medcoupling
    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_medcoupling.py [--sizes 2D:1e5,2D:1e6,3D:1e4,3D:1e5]

(PYTHONPATH: the build's `meshprojection` and `mpsupport` packages; see README.md here.)

Each pair is the jittered square (triangles) or cube (tetrahedra) of
mpbench, the Source about 0.8 times as many cells on a slightly shifted
box, with a smooth cell field. Times are the best of three runs: the
filter on one and on two threads (CacheOperator off: search, assembly and
solve each run), MEDCoupling's prepare() plus transferField() (one thread).
The largest difference of the two results over the target cells both
cover is printed beside them. Prints Markdown.
"""
import argparse
import time

import numpy as np
from mpbench import shifted_pair, timed_run, to_grid
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

import medcoupling as mc


def field(points, cells):
    c = points[cells].mean(axis=1)
    return np.sin(3 * c[:, 0]) * np.cos(2 * c[:, 1]) + 0.5 * c[:, 2]


def filter_run(target, source, threads):
    seconds, f = timed_run(target, source, threads)
    return seconds, vtk_to_numpy(f.GetOutput().GetCellData().GetArray("g")).copy()


def mc_mesh(points, cells, dim):
    mesh = mc.MEDCouplingUMesh("m", dim)
    mesh.setCoords(mc.DataArrayDouble(np.ascontiguousarray(points[:, :dim])))
    kind = mc.NORM_TRI3 if dim == 2 else mc.NORM_TETRA4
    width = cells.shape[1] + 1
    conn = np.empty((len(cells), width), dtype=np.int64)
    conn[:, 0] = kind
    conn[:, 1:] = cells
    mesh.setConnectivity(mc.DataArrayInt(conn.ravel()),
                         mc.DataArrayInt(np.arange(0, width * len(cells) + 1, width, dtype=np.int64)))
    return mesh


def medcoupling_run(target, source, values, dim):
    tm, sm = mc_mesh(target[0], target[1], dim), mc_mesh(source[0], source[1], dim)
    f = mc.MEDCouplingFieldDouble(mc.ON_CELLS, mc.ONE_TIME)
    f.setMesh(sm)
    f.setArray(mc.DataArrayDouble(values))
    f.setNature(mc.IntensiveMaximum)
    start = time.perf_counter()
    remapper = mc.MEDCouplingRemapper()
    remapper.prepare(sm, tm, "P0P0")
    out = remapper.transferField(f, float("nan"))
    seconds = time.perf_counter() - start
    return seconds, out.getArray().toNumPyArray().ravel().copy()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", default="2D:1e5,2D:1e6,3D:1e4,3D:1e5")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print("| pair | target cells | filter, 1 thread | filter, 2 threads | MEDCoupling | MEDCoupling / filter (1 thread) | largest difference |")
    print("|---|---|---|---|---|---|---|")
    for item in args.sizes.split(","):
        kind, size = item.split(":")
        dim = 2 if kind == "2D" else 3
        target, source = shifted_pair(dim, float(size))
        values = field(source[0], source[1])
        tg = to_grid(*target)
        sg = to_grid(*source)
        g = numpy_to_vtk(values, deep=1)
        g.SetName("g")
        sg.GetCellData().AddArray(g)
        one = min(filter_run(tg, sg, 1) for _ in range(args.repeat))
        two = min(filter_run(tg, sg, 2)[0] for _ in range(args.repeat))
        peer = min(medcoupling_run(target, source, values, dim) for _ in range(args.repeat))
        both = np.isfinite(one[1]) & np.isfinite(peer[1])
        difference = float(np.max(np.abs(one[1][both] - peer[1][both]))) if both.any() else float("nan")
        print("| %s | %d | %.3f s | %.3f s | %.3f s | %.1f | %.1e |" %
              (kind, len(target[1]), one[0], two, peer[0], peer[0] / one[0], difference))


if __name__ == "__main__":
    main()
