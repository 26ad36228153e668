"""The benchmark's pairs of meshes made outside mesh-projection-bench, written
once as .vtu files and reused: random Delaunay pairs in Qhull's order (and
sorted, shuffled) and Gmsh pairs. bench_numbering.py, bench_generators.py
and bench_compare.py take them from here; the generated pairs (jittered
grids) are made by mesh-projection-bench itself.

Every pair is named by what makes it (dimension, size, seeds), so that other
seeds and sizes make other files."""
import math
import os
import sys

import numpy as np
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

import mpbench

CELL_TYPE = {2: VTK_TRIANGLE, 3: VTK_TETRA}


def write(mesh, path):
    """Writes the (points, cells, type) mesh to the .vtu file `path`."""
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(mpbench.to_grid(*mesh))
    writer.SetDataModeToBinary()  # inline binary: Debian's expat rejects appended data
    if not writer.Write():
        raise RuntimeError("cannot write " + path)


# Random Delaunay pairs in Qhull's order.

CELLS_PER_POINT = {2: 2.0, 3: 6.5}  # Delaunay cells per point of a jittered grid (measured)
NUMBERINGS = ("as numbered", "sorted", "shuffled")


def qhull_mesh(dim, cells, seed):
    """A Delaunay mesh of about `cells` cells of a jittered grid of the unit
    square (cube), in Qhull's order, as a new user makes one: the grid's
    points (grid order) given to scipy.spatial.Delaunay, the cells kept in
    Qhull's order (a point's new cells together as Qhull inserts it, the
    points inserted in no spatial order): (points, cells, type). Cells of
    (nearly) no measure on the hull, where jittered boundary points line up,
    are left out; the others keep their order."""
    from scipy.spatial import Delaunay

    rng = np.random.default_rng(seed)
    k = max(3, int(round((cells / CELLS_PER_POINT[dim]) ** (1.0 / dim))))
    axis = np.linspace(0.0, 1.0, k)
    grid = np.stack(np.meshgrid(*([axis] * dim), indexing="ij"), -1).reshape(-1, dim)[:, ::-1]
    grid = grid + rng.uniform(-0.3, 0.3, grid.shape) / k
    simplices = Delaunay(grid).simplices.astype(np.int64)
    corners = grid[simplices]
    edges = corners[:, 1:, :] - corners[:, :1, :]
    measure = np.abs(np.linalg.det(edges))
    simplices = simplices[measure > 1e-6 * np.mean(measure)]
    points = np.zeros((len(grid), 3))
    points[:, :dim] = grid
    return points, simplices, CELL_TYPE[dim]


def morton_sorted(mesh):
    """The same mesh with cells along a Z-order curve (by their lowest
    corner's key, 2^10 steps per axis), points in the order the cells first
    use them."""
    points, cells, kind = mesh
    low, high = points.min(0), points.max(0)
    dim = int(np.count_nonzero(high > low))
    q = ((points[:, :dim] - low[:dim]) / (high[:dim] - low[:dim]) * 1023).astype(np.uint64)
    key = np.zeros(len(points), dtype=np.uint64)
    for bit in range(10):
        for a in range(dim):
            key |= ((q[:, a] >> np.uint64(bit)) & np.uint64(1)) << np.uint64(bit * dim + a)
    cells = cells[np.argsort(key[cells].min(1), kind="stable")]
    flat = cells.ravel()
    _, first = np.unique(flat, return_index=True)
    used = flat[np.sort(first)]
    order = np.concatenate([used, np.setdiff1d(np.arange(len(points)), used)])
    new_id = np.empty(len(points), dtype=np.int64)
    new_id[order] = np.arange(len(order))
    return points[order], new_id[cells], kind


def qhull_pair(directory, dim, cells, seeds=(1, 2)):
    """{numbering: (target file, source file)} of the random Delaunay pair
    of about `cells` target cells (the source about 0.8 times as many, from
    the second seed), each mesh as numbered (Qhull's order), sorted (along a
    Morton curve) and shuffled (points and cells in random orders)."""
    files = {}
    made = {}
    for role, scale, seed in (("target", 1.0, seeds[0]), ("source", 0.8, seeds[1])):
        for numbering in NUMBERINGS:
            name = os.path.join(directory, "qhull_%dd_%g_seed%d_%s_%s.vtu" % (
                dim, cells, seed, role, numbering.replace(" ", "_")))
            files.setdefault(numbering, []).append(name)
            if os.path.exists(name):
                continue
            if role not in made:
                made[role] = qhull_mesh(dim, cells * scale, seed)
            mesh = made[role]
            if numbering == "sorted":
                mesh = morton_sorted(mesh)
            elif numbering == "shuffled":
                mesh = mpbench.shuffled(mesh, seed + 10)
            write(mesh, name)
    return files


# Gmsh pairs.

HOLE = (0.2, 0.1, 0.3)  # 2D: centre and radius of the hole in the unit disk
GMSH_TYPE = {2: 2, 3: 4}  # Gmsh element type: 3-node triangle, 4-node tetrahedron


def gmsh_mesh(dim, cells, algorithm, seed):
    """Gmsh's mesh of the 2D domain (the unit disk with an off-centre hole)
    or the 3D one (the unit ball) with about `cells` cells by `algorithm`
    (Mesh.Algorithm in 2D, Mesh.Algorithm3D in 3D), in Gmsh's numbering:
    cells in element-tag order, points in node-tag order (compacted):
    (points, cells, type)."""
    import gmsh

    try:
        gmsh.initialize(interruptible=False)  # Gmsh >= 4.9: leave SIGINT to Python
    except TypeError:
        gmsh.initialize()  # Debian 12's Gmsh 4.8
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.RandomSeed", seed)
        gmsh.model.add("bench")
        occ = gmsh.model.occ
        if dim == 2:
            outer = occ.addDisk(0, 0, 0, 1, 1)
            hole = occ.addDisk(HOLE[0], HOLE[1], 0, HOLE[2], HOLE[2])
            occ.cut([(2, outer)], [(2, hole)])
            measure = math.pi * (1 - HOLE[2] ** 2)
            # Gmsh's Delaunay triangles average about 0.38 h^2 (measured).
            h = math.sqrt(measure / cells / 0.38)
            gmsh.option.setNumber("Mesh.Algorithm", algorithm)
        else:
            occ.addSphere(0, 0, 0, 1)
            measure = 4 * math.pi / 3
            # Gmsh's Delaunay tetrahedra average about h^3 / 4.8 (measured).
            h = (measure / cells * 4.8) ** (1 / 3)
            gmsh.option.setNumber("Mesh.Algorithm", 6)
            gmsh.option.setNumber("Mesh.Algorithm3D", algorithm)
        occ.synchronize()
        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.model.mesh.generate(dim)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        etags, enodes = gmsh.model.mesh.getElementsByType(GMSH_TYPE[dim])
    finally:
        gmsh.finalize()
    enodes = np.asarray(enodes, dtype=np.int64).reshape(-1, dim + 1)[np.argsort(etags)]
    tags = np.asarray(tags, dtype=np.int64)
    coords = np.asarray(coords).reshape(-1, 3)
    order = np.argsort(tags)
    tags, coords = tags[order], coords[order]
    used = np.isin(tags, enodes)  # drop nodes no cell uses (geometry vertices)
    tags, coords = tags[used], coords[used]
    ids = np.searchsorted(tags, enodes)  # node tag -> 0..n-1, in tag order
    return np.ascontiguousarray(coords), np.ascontiguousarray(ids), CELL_TYPE[dim]


def gmsh_pair(directory, dim, cells, seed=1):
    """The target and source files of the Gmsh pair of about `cells` target
    cells: 2D target by Delaunay (Mesh.Algorithm 5), source by
    Frontal-Delaunay (6) at a 7% larger size; 3D target by Delaunay
    (Mesh.Algorithm3D 1), source by HXT (10) at a 7% larger size. `seed` is
    Gmsh's Mesh.RandomSeed."""
    algorithms = (5, 6) if dim == 2 else (1, 10)
    names = []
    for role, algorithm, scale in (("target", algorithms[0], 1.0), ("source", algorithms[1], 1 / 1.07 ** dim)):
        name = os.path.join(directory, "gmsh_%dd_%g_seed%d_%s.vtu" % (dim, cells, seed, role))
        if not os.path.exists(name):
            mesh = gmsh_mesh(dim, cells * scale, algorithm, seed)
            write(mesh, name)
            print("  meshed %s: %d cells" % (os.path.basename(name), len(mesh[1])), file=sys.stderr, flush=True)
        names.append(name)
    return names
