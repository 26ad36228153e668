"""How much does running Mesh Projection from pvpython cost beyond the filter?

    PYTHONPATH=build/lib/python3/dist-packages \
      pvpython Benchmarks/bench_pvpython.py --plugin PLUGIN.so [--dim 2|3] [--sizes 1e4,1e5,1e6]

(PYTHONPATH: the build's `meshprojection` package, so that the filter behind
the proxy can report its own times, and `mpsupport`; see README.md here.)

For each size it builds a pair of jittered, non-matching meshes of the unit
square (triangles) or cube (tetrahedra) with numpy (mpbench), hands them to ParaView as
trivial producers (the VTK arrays wrap the numpy buffers, nothing is copied),
applies the plugin's MeshProjection proxy and times UpdatePipeline(). The
filter reports its own wall-clock time and stages (vtkMeshProjectionFilter
Get*Time); the difference is what ParaView's proxies, pipeline and data
information add. One thread (the proxy's NumberOfThreads = 1).
"""
import argparse
import time

import numpy as np
from mpbench import cube_mesh, square_mesh, to_grid
from paraview import servermanager
from paraview.simple import Delete, LoadPlugin, TrivialProducer


def producer(grid):
    p = TrivialProducer()
    p.GetClientSideObject().SetOutput(grid)
    return p


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--dim", type=int, default=2)
    parser.add_argument("--sizes", default="1e4,1e5,1e6")
    args = parser.parse_args()
    LoadPlugin(args.plugin, ns=globals())
    import meshprojection  # noqa: F401 (wraps vtkMeshProjectionFilter for GetClientSideObject)
    print("%dD: MeshProjection from pvpython, one thread (seconds)" % args.dim)
    print("%10s %10s %10s %10s %9s   filter stages: input neighbours locator search assembly solve output"
          % ("cells", "pvpython", "filter", "overhead", "ratio"))
    for size in (float(s) for s in args.sizes.split(",")):
        if args.dim == 2:
            k = max(2, int(round((size / 2) ** 0.5)))
            target = square_mesh(k, k, 7)
            source = square_mesh(k + 3, k - 1, 8)
        else:
            k = max(2, int(round((size / 6) ** (1.0 / 3.0))))
            target = cube_mesh(k, k, k, 7)
            source = cube_mesh(k + 1, k, k - 1, 8)
        x = source[0]
        field = np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + x[:, 2]
        t = producer(to_grid(*target))
        s = producer(to_grid(*source, field=field))
        projection = MeshProjection(Input=t, Source=s)  # noqa: F821 (defined by the plugin)
        projection.NumberOfThreads = 1
        start = time.perf_counter()
        projection.UpdatePipeline()
        wall = time.perf_counter() - start
        f = projection.GetClientSideObject()
        own = f.GetExecutionTime()
        out = servermanager.Fetch(projection) if size <= 1e4 else None
        if out is not None and out.GetPointData().GetArray("u") is None:
            raise SystemExit("no projected array")
        stages = (f.GetInputTime(), f.GetNeighborsTime(), f.GetLocatorTime(), f.GetSearchTime(),
                  f.GetAssemblyTime(), f.GetSolveTime(), f.GetOutputTime())
        print("%10d %10.3f %10.3f %10.3f %8.2fx   %s"
              % (len(target[1]), wall, own, wall - own, wall / own,
                 " ".join("%.3f" % v for v in stages)))
        for proxy in (projection, s, t):
            Delete(proxy)


if __name__ == "__main__":
    main()
