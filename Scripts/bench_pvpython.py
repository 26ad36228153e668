"""How much does running Mesh Projection from pvpython cost beyond the filter?

    pvpython Scripts/bench_pvpython.py --plugin PLUGIN.so --python-path DIR
                                       [--dim 2|3] [--sizes 1e4,1e5,1e6]

(DIR holds the wrapped `meshprojection` package, build/lib/python3/dist-packages,
so that the filter behind the proxy can report its own times.)

For each size it builds a pair of jittered, non-matching meshes of the unit
square (triangles) or cube (tetrahedra) with numpy, hands them to ParaView as
trivial producers (the VTK arrays wrap the numpy buffers, nothing is copied),
applies the plugin's MeshProjection proxy and times UpdatePipeline(). The
filter reports its own wall-clock time and stages (vtkMeshProjectionFilter
Get*Time); the difference is what ParaView's proxies, pipeline and data
information add. One thread (the proxy's NumberOfThreads = 1).
"""
import argparse
import sys
import time

import numpy as np
from paraview import servermanager
from paraview.simple import Delete, LoadPlugin, TrivialProducer
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE, vtkCellArray, vtkUnstructuredGrid


def jittered_points(counts, jitter, rng):
    """Grid points of the unit square/cube, interior ones moved by up to jitter cells."""
    axes = [np.linspace(0.0, 1.0, n + 1) for n in counts]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(counts))
    h = np.array([1.0 / n for n in counts])
    interior = np.all((grid > 0.0) & (grid < 1.0), axis=1)
    grid[interior] += jitter * h * rng.uniform(-1.0, 1.0, size=(interior.sum(), len(counts)))
    if grid.shape[1] == 2:
        grid = np.hstack([grid, np.zeros((grid.shape[0], 1))])
    return grid


def square_mesh(nx, ny, seed):
    rng = np.random.default_rng(seed)
    points = jittered_points((nx, ny), 0.25, rng)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    a = (i * (ny + 1) + j).ravel()
    b, c, d = a + (ny + 1), a + (ny + 1) + 1, a + 1
    cells = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return points, cells, VTK_TRIANGLE


def cube_mesh(nx, ny, nz, seed):
    rng = np.random.default_rng(seed)
    points = jittered_points((nx, ny, nz), 0.15, rng)
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    base = ((i * (ny + 1) + j) * (nz + 1) + k).ravel()
    dx, dy, dz = (ny + 1) * (nz + 1), nz + 1, 1
    corner = [base + (a & 1) * dx + ((a >> 1) & 1) * dy + ((a >> 2) & 1) * dz for a in range(8)]
    # Six tetrahedra around the diagonal 0-7 of every cube (conforming).
    paths = [(1, 3), (3, 2), (2, 6), (6, 4), (4, 5), (5, 1)]
    cells = np.concatenate([np.stack([corner[0], corner[p], corner[q], corner[7]], 1)
                            for p, q in paths])
    return points, cells, VTK_TETRA


def to_grid(points, cells, cell_type, field=None):
    grid = vtkUnstructuredGrid()
    vtk_points = vtkPoints()
    vtk_points.SetData(numpy_to_vtk(points, deep=0))
    grid.SetPoints(vtk_points)
    n, corners = cells.shape
    offsets = numpy_to_vtkIdTypeArray(np.arange(0, (n + 1) * corners, corners, dtype=np.int64), deep=1)
    connectivity = numpy_to_vtkIdTypeArray(cells.astype(np.int64).ravel(), deep=1)
    array = vtkCellArray()
    array.SetData(offsets, connectivity)
    grid.SetCells(cell_type, array)
    if field is not None:
        u = numpy_to_vtk(field, deep=1)
        u.SetName("u")
        grid.GetPointData().AddArray(u)
    return grid


def producer(grid):
    p = TrivialProducer()
    p.GetClientSideObject().SetOutput(grid)
    return p


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--python-path", required=True)
    parser.add_argument("--dim", type=int, default=2)
    parser.add_argument("--sizes", default="1e4,1e5,1e6")
    args = parser.parse_args()
    LoadPlugin(args.plugin, ns=globals())
    sys.path.insert(0, args.python_path)
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
