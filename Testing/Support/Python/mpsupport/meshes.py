"""Meshes of jittered grids built with numpy, written once for the tests
and the benchmarks: points of a box's grid (interior points moved by up to a
fraction of the spacing), quadrilaterals, triangles, hexahedra and
tetrahedra on them, and a vtkUnstructuredGrid from such arrays.

Counts `n` are cells per side: an int (the same on every axis) or one per
axis. Points are numbered with the first axis slowest."""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkUnstructuredGrid
from vtkmodules.vtkFiltersCore import vtkExtractCells


def grid(points, cells, cell_type, deep=True):
    """A vtkUnstructuredGrid of one cell type from numpy arrays (deep=False:
    the points are not copied, the grid wraps the numpy buffer)."""
    g = vtkUnstructuredGrid()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=deep))
    g.SetPoints(p)
    ca = vtkCellArray()
    n = cells.shape[1]
    offsets = np.arange(0, n * len(cells) + 1, n, dtype=np.int64)
    ca.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
               numpy_to_vtkIdTypeArray(np.ascontiguousarray(cells, dtype=np.int64).ravel(), deep=True))
    g.SetCells(cell_type, ca)
    return g


def _counts(n, dim):
    return (n,) * dim if np.isscalar(n) else tuple(n)


def structured(n, lo, hi, dim, seed, jitter=0.25):
    """Points of an n^dim grid of [lo, hi]^dim (first axis slowest), interior
    ones jittered by up to `jitter` of the spacing, one axis after the other."""
    n = _counts(n, dim)
    axes = [np.linspace(lo[d], hi[d], n[d] + 1) for d in range(dim)]
    mesh = np.meshgrid(*axes, indexing="ij")
    x = np.zeros((int(np.prod([k + 1 for k in n])), 3))
    for d in range(dim):
        x[:, d] = mesh[d].ravel()
    rng = np.random.default_rng(seed)
    h = (np.array(hi[:dim], float) - np.array(lo[:dim], float)) / np.array(n, float)
    inner = np.all([(x[:, d] > lo[d] + 1e-12) & (x[:, d] < hi[d] - 1e-12) for d in range(dim)], axis=0)
    for d in range(dim):
        x[inner, d] += jitter * h[d] * rng.uniform(-1, 1, inner.sum())
    return x


def quads(n, lo, hi, seed, jitter=0.25):
    """Points and quads of a jittered n x n grid."""
    x = structured(n, lo, hi, 2, seed, jitter)
    n = _counts(n, 2)
    v = np.arange(len(x)).reshape(n[0] + 1, n[1] + 1)
    return x, np.stack([v[:-1, :-1].ravel(), v[1:, :-1].ravel(), v[1:, 1:].ravel(), v[:-1, 1:].ravel()], 1)


def triangles(n, lo, hi, seed, jitter=0.25):
    """Points and triangles (two per square) of a jittered n x n grid."""
    x, q = quads(n, lo, hi, seed, jitter)
    return x, np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])


def _cube_corners(n):
    """Per corner of the hexahedra (VTK's order), the point ids."""
    v = np.arange(int(np.prod([k + 1 for k in n]))).reshape(tuple(k + 1 for k in n))
    return [v[i:n[0] + i, j:n[1] + j, k:n[2] + k].ravel() for (i, j, k) in
            [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]]


def hexahedra(n, lo, hi, seed, jitter=0.25):
    """Points and hexahedra of a jittered n^3 grid."""
    return structured(n, lo, hi, 3, seed, jitter), np.stack(_cube_corners(_counts(n, 3)), 1)


def tetrahedra(n, lo, hi, seed, jitter=0.25):
    """Points and tetrahedra (six around the diagonal 0-6 of each cube,
    conforming) of a jittered n^3 grid. (At large sizes a jitter of 0.25
    can invert a tetrahedron: the benchmarks use less.)"""
    x = structured(n, lo, hi, 3, seed, jitter)
    c = _cube_corners(_counts(n, 3))
    tets = [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]
    return x, np.concatenate([np.stack([c[a], c[b], c[d], c[e]], 1) for (a, b, d, e) in tets])


def extract(g, keep):
    """The cells of g where `keep` is true, as a vtkUnstructuredGrid."""
    e = vtkExtractCells()
    e.SetInputData(g)
    ids = np.nonzero(keep)[0].astype(np.int64)
    e.SetCellIds(ids.tolist(), len(ids))
    e.Update()
    out = vtkUnstructuredGrid()
    out.ShallowCopy(e.GetOutput())
    return out


def simplex_means(corners, f):
    """The mean of f (a function of (n, 3) points) over each simplex whose
    corners are corners[i] ((n, k, 3), k = 2, 3 or 4): quadrature exact for
    quadratics (Gauss on segments, edge midpoints on triangles, the
    four-point rule on tetrahedra)."""
    p = corners
    k = p.shape[1]
    if k == 2:
        g = 0.5 / np.sqrt(3)
        return 0.5 * (f((0.5 - g) * p[:, 0] + (0.5 + g) * p[:, 1]) + f((0.5 + g) * p[:, 0] + (0.5 - g) * p[:, 1]))
    if k == 3:
        return sum(f(0.5 * (p[:, a] + p[:, b])) for a, b in ((0, 1), (1, 2), (0, 2))) / 3
    a, b = 0.5854101966249685, 0.1381966011250105
    total = 0
    for j in range(4):
        w = np.full(4, b)
        w[j] = a
        total = total + f(np.einsum("k,nkd->nd", w, p))
    return total / 4


def add_array(data, name, values):
    """`values` (numpy, converted to double) as the array `name` of `data`
    (point or cell data), copied."""
    a = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float64), deep=True)
    a.SetName(name)
    data.AddArray(a)


def triangle_centres(g):
    """The corners' mean of every cell of a grid of triangles (n x 3)."""
    x = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 3)
    return x[conn].mean(axis=1)
