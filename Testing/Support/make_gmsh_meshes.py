"""Small test meshes made by the real mesh generator Gmsh, written as VTK XML.

    /usr/bin/python3 Testing/Support/make_gmsh_meshes.py [OUTPUT_DIR]

OUTPUT_DIR defaults to Testing/Data/Gmsh (relative to the repository root).
Needs Gmsh's Python API (`import gmsh`; if it is not installed, a directory
holding gmsh.py and libgmsh.so can be given in GMSH_PYTHONPATH, default
/tmp/gmshlib) and VTK's Python modules with numpy.

The meshes are taken straight from the Gmsh API (getNodes / getElements) and
keep Gmsh's numbering on purpose: points in increasing node tag order (tags
compacted to 0..n-1), cells in increasing element tag order, only the
elements of the mesh's top dimension (no boundary lines or points). The
linear Gmsh element types and VTK's share their node orderings except the
prism: Gmsh's base triangle (0, 1, 2) turns towards the top one (its normal
points into the element), VTK's wedge base turns away from it, so a prism's
nodes 0 1 2 3 4 5 become the wedge's 0 2 1 3 5 4 (as meshio does).

Every mesh gets a point array "Linear" = 1 + 2x - 3y + 0.5z and a cell array
"CellIndex" (both double). After writing, every file is read back and checked:
cell types, positive cell measures (and positive scaled Jacobians at all the
3D cells' sub-tetrahedra, so no cell is inverted and no quadrilateral face is
twisted), the total
measure against the domain's and conformity (every face or edge shared by two
cells or lying on the domain's boundary).
"""
import math
import os
import sys

sys.path.insert(0, os.environ.get("GMSH_PYTHONPATH", "/tmp/gmshlib"))
import gmsh  # noqa: E402
import numpy as np  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid  # noqa: E402
from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader, vtkXMLUnstructuredGridWriter  # noqa: E402

# Gmsh element type -> (VTK cell type, VTK node i is Gmsh node order[i]).
GMSH_TO_VTK = {
    2: (5, [0, 1, 2]),
    3: (9, [0, 1, 2, 3]),
    4: (10, [0, 1, 2, 3]),
    5: (12, [0, 1, 2, 3, 4, 5, 6, 7]),
    6: (13, [0, 2, 1, 3, 5, 4]),  # prism -> wedge: the base triangles turn the other way
    7: (14, [0, 1, 2, 3, 4]),
}
VTK_NAMES = {5: "triangle", 9: "quad", 10: "tetra", 12: "hexahedron", 13: "wedge", 14: "pyramid"}



def vtk_faces(vtk_type, n):
    """The faces of a 3D VTK cell type in its local numbering, as VTK defines them."""
    grid = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetNumberOfPoints(n)
    grid.SetPoints(points)
    grid.InsertNextCell(vtk_type, n, list(range(n)))
    cell = grid.GetCell(0)
    return [[cell.GetFace(i).GetPointId(k) for k in range(cell.GetFace(i).GetNumberOfPoints())]
            for i in range(cell.GetNumberOfFaces())]


FACES = {t: vtk_faces(t, len(order)) for t, order in GMSH_TO_VTK.values() if t in (10, 12, 13, 14)}

DISK_HOLE = (0.2, 0.1, 0.3)  # centre x, y and radius of the hole in the unit disk
DISK_AREA = math.pi * (1.0 - DISK_HOLE[2] ** 2)


def generate(dim, transform=None):
    """Meshes the model up to `dim`, converts it and closes Gmsh."""
    gmsh.model.mesh.generate(dim)
    grid = to_ugrid(transform)
    gmsh.finalize()
    return grid


def start(name):
    gmsh.initialize(interruptible=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    gmsh.option.setNumber("Mesh.RandomSeed", 1)
    gmsh.model.add(name)


def to_ugrid(transform=None):
    """The current Gmsh model's top-dimension elements as a vtkUnstructuredGrid."""
    dim = gmsh.model.getDimension()
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    coords = coords.reshape(-1, 3)
    cells = []  # (element tag, vtk type, node tags)
    for etype, etags, enodes in zip(*gmsh.model.mesh.getElements(dim)):
        vtk_type, order = GMSH_TO_VTK[int(etype)]
        enodes = np.asarray(enodes, dtype=np.int64).reshape(-1, len(order))[:, order]
        cells.extend((int(t), vtk_type, enodes[i]) for i, t in enumerate(etags))
    cells.sort(key=lambda c: c[0])
    used = np.unique(np.concatenate([c[2] for c in cells]))
    order = np.argsort(node_tags)
    node_tags, coords = np.asarray(node_tags, dtype=np.int64)[order], coords[order]
    keep = np.isin(node_tags, used)
    node_tags, coords = node_tags[keep], coords[keep]
    if transform is not None:
        coords = transform(coords)
    index = {int(t): i for i, t in enumerate(node_tags)}

    grid = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(coords, dtype=np.float64), deep=True))
    grid.SetPoints(points)
    grid.Allocate(len(cells))
    for _, vtk_type, nodes in cells:
        grid.InsertNextCell(vtk_type, len(nodes), [index[int(t)] for t in nodes])

    x, y, z = coords[:, 0], coords[:, 1], coords[:, 2]
    linear = numpy_to_vtk(1.0 + 2.0 * x - 3.0 * y + 0.5 * z, deep=True)
    linear.SetName("Linear")
    grid.GetPointData().AddArray(linear)
    cell_index = numpy_to_vtk(np.arange(len(cells), dtype=np.float64), deep=True)
    cell_index.SetName("CellIndex")
    grid.GetCellData().AddArray(cell_index)
    return grid


def write(grid, path):
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(grid)
    writer.SetDataModeToBinary()  # inline binary: no appended data (some expat builds reject it)
    writer.SetCompressorTypeToZLib()
    if not writer.Write():
        raise RuntimeError("cannot write " + path)


# ---------------------------------------------------------------------------
# Geometries and meshes


def disk_with_hole():
    """The unit disk minus the hole, as one OCC surface (returns its dimTags)."""
    occ = gmsh.model.occ
    outer = occ.addDisk(0, 0, 0, 1, 1)
    hole = occ.addDisk(DISK_HOLE[0], DISK_HOLE[1], 0, DISK_HOLE[2], DISK_HOLE[2])
    domain, _ = occ.cut([(2, outer)], [(2, hole)])
    return domain


def uniform_size(h):
    gmsh.option.setNumber("Mesh.MeshSizeMin", h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 1)


def quads_disk(transform=None):
    start("quads_disk")
    disk_with_hole()
    gmsh.model.occ.synchronize()
    uniform_size(0.065)
    gmsh.option.setNumber("Mesh.Algorithm", 8)  # Frontal-Delaunay for quads
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 3)  # blossom full-quad: no triangles left
    return generate(2, transform)


def mixed_disk():
    """Left half (x < 0) triangles, right half quads, sharing the nodes on x = 0."""
    start("mixed_disk")
    occ = gmsh.model.occ
    domain = disk_with_hole()
    rect = occ.addRectangle(-1.5, -1.5, 0, 1.5, 3.0)  # x in [-1.5, 0]
    left, _ = occ.intersect(domain, [(2, rect)], removeObject=False, removeTool=False)
    right, _ = occ.cut(domain, [(2, rect)])
    occ.fragment(left, right)
    occ.synchronize()
    uniform_size(0.085)  # 1.3 x the size of quads_disk
    gmsh.option.setNumber("Mesh.Algorithm", 8)
    gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 3)
    for _, s in gmsh.model.getEntities(2):
        if occ.getCenterOfMass(2, s)[0] > 0.0:
            gmsh.model.mesh.setRecombine(2, s)
    return generate(2)


def tris_disk():
    start("tris_disk")
    disk_with_hole()
    gmsh.model.occ.synchronize()
    uniform_size(0.08)
    gmsh.option.setNumber("Mesh.Algorithm", 5)  # Delaunay
    return generate(2)


def box_curves_by_axis(volume):
    """The curves of a volume's boundary, keyed by the axis they run along (0, 1, 2)."""
    curves = {0: set(), 1: set(), 2: set()}
    for _, s in gmsh.model.getBoundary([(3, volume)], oriented=False):
        for _, c in gmsh.model.getBoundary([(2, s)], oriented=False):
            c = abs(c)
            t0, t1 = gmsh.model.getParametrizationBounds(1, c)
            d = (np.array(gmsh.model.getValue(1, c, [t1[0]]))
                 - np.array(gmsh.model.getValue(1, c, [t0[0]])))
            axis = int(np.argmax(np.abs(d)))
            curves[axis].add((c, 1 if d[axis] > 0 else -1))
    return curves


def hexes_box():
    start("hexes_box")
    box = gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    curves = box_curves_by_axis(box)
    spec = {0: (13, "Progression", 1.15), 1: (11, "Bump", 0.3), 2: (9, "Progression", 0.88)}
    for axis, (n, kind, coef) in spec.items():
        for c, direction in curves[axis]:
            if kind == "Progression" and direction < 0:
                coef_c = 1.0 / coef  # the same distribution along the axis
            else:
                coef_c = coef
            gmsh.model.mesh.setTransfiniteCurve(c, n, kind, coef_c)
    for _, s in gmsh.model.getBoundary([(3, box)], oriented=False):
        gmsh.model.mesh.setTransfiniteSurface(s)
        gmsh.model.mesh.setRecombine(2, s)
    gmsh.model.mesh.setTransfiniteVolume(box)
    return generate(3)


def wedges_cylinder():
    start("wedges_cylinder")
    occ = gmsh.model.occ
    disk = occ.addDisk(0.5, 0.5, 0, 0.5, 0.5)
    occ.extrude([(2, disk)], 0, 0, 1, numElements=[8], recombine=True)
    occ.synchronize()
    uniform_size(0.085)
    gmsh.option.setNumber("Mesh.Algorithm", 5)
    return generate(3)


def tets_box():
    start("tets_box")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    uniform_size(0.15)
    gmsh.option.setNumber("Mesh.Algorithm", 5)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
    return generate(3)


def mixed_box():
    """[0,1]^3 in three volumes: x < 0.5, y < 0.5 transfinite hexahedra; x < 0.5,
    y > 0.5 transfinite wedges (its z = 0 and z = 1 faces triangles, its other
    faces quads); x > 0.5 Delaunay tetrahedra, which Gmsh closes with pyramids
    on the quads of the x = 0.5 interface."""
    start("mixed_box")
    occ = gmsh.model.occ
    a = occ.addBox(0, 0, 0, 0.5, 0.5, 1)
    b = occ.addBox(0, 0.5, 0, 0.5, 0.5, 1)
    c = occ.addBox(0.5, 0, 0, 0.5, 1, 1)
    occ.fragment([(3, a), (3, b)], [(3, c)])
    occ.synchronize()
    centres = {t: occ.getCenterOfMass(3, t) for _, t in gmsh.model.getEntities(3)}
    hexes = next(t for t, p in centres.items() if p[0] < 0.5 and p[1] < 0.5)
    wedges = next(t for t, p in centres.items() if p[0] < 0.5 and p[1] > 0.5)
    uniform_size(0.15)
    gmsh.option.setNumber("Mesh.Algorithm", 5)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)
    for v in (hexes, wedges):
        for _, s in gmsh.model.getBoundary([(3, v)], oriented=False):
            for _, cv in gmsh.model.getBoundary([(2, s)], oriented=False):
                gmsh.model.mesh.setTransfiniteCurve(abs(cv), 6)
            gmsh.model.mesh.setTransfiniteSurface(s)
            z = occ.getCenterOfMass(2, s)[2]
            if v == hexes or 0.01 < z < 0.99:
                gmsh.model.mesh.setRecombine(2, s)
        gmsh.model.mesh.setTransfiniteVolume(v)
    return generate(3)


# ---------------------------------------------------------------------------
# Checks


def cells_of(grid):
    types = vtk_to_numpy(grid.GetCellTypesArray())
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray())
    return [(int(types[i]), conn[offsets[i]:offsets[i + 1]]) for i in range(len(types))]


def measures(grid):
    f = vtkCellSizeFilter()
    f.SetInputData(grid)
    f.Update()
    out = f.GetOutput().GetCellData()
    name = "Volume" if grid.GetCell(0).GetCellDimension() == 3 else "Area"
    return vtk_to_numpy(out.GetArray(name))


def min_sub_tet_volume(grid):
    """The smallest volume of the tetrahedra joining a 3D cell's centroid to its faces,
    the quadrilateral faces split along both diagonals (relative to the cell's volume).
    Negative when a cell is inverted (VTK's faces turn outwards) or a face is twisted."""
    pts = vtk_to_numpy(grid.GetPoints().GetData())
    worst = math.inf
    for (vtk_type, ids), volume in zip(cells_of(grid), measures(grid)):
        p = pts[ids]
        centre = p.mean(axis=0)
        for face in FACES[vtk_type]:
            f = p[face]
            fans = [(0, 1, 2)] if len(face) == 3 else [(0, 1, 2), (0, 2, 3), (1, 2, 3), (1, 3, 0)]
            for i, j, k in fans:
                v = np.dot(np.cross(f[j] - f[i], f[k] - f[i]), f[i] - centre) / 6.0
                worst = min(worst, v / volume)
    return worst


def unmatched_sides(grid, on_boundary):
    """Faces (3D) or edges (2D) not shared by exactly two cells, except boundary ones."""
    pts = vtk_to_numpy(grid.GetPoints().GetData())
    count = {}
    for vtk_type, ids in cells_of(grid):
        if vtk_type in FACES:
            sides = [tuple(ids[list(f)]) for f in FACES[vtk_type]]
        else:
            sides = [(ids[i], ids[(i + 1) % len(ids)]) for i in range(len(ids))]
        for s in sides:
            key = tuple(sorted(int(i) for i in s))
            count[key] = count.get(key, 0) + 1
    return [k for k, n in count.items() if n > 2 or (n == 1 and not on_boundary(pts[list(k)]))]


def signed_areas(grid, normal):
    pts = vtk_to_numpy(grid.GetPoints().GetData())
    out = []
    for _, ids in cells_of(grid):
        p = pts[ids]
        v = sum(np.cross(p[i], p[(i + 1) % len(p)]) for i in range(len(p))) / 2.0
        out.append(float(np.dot(v, normal)))
    return np.array(out)


def on_disk_boundary(p):
    r_out = np.hypot(p[:, 0], p[:, 1])
    r_in = np.hypot(p[:, 0] - DISK_HOLE[0], p[:, 1] - DISK_HOLE[1])
    return np.all(np.abs(r_out - 1) < 1e-9) or np.all(np.abs(r_in - DISK_HOLE[2]) < 1e-9)


def on_box_boundary(p):
    return any(np.all(np.abs(p[:, a] - v) < 1e-9) for a in range(3) for v in (0.0, 1.0))


def on_cylinder_boundary(p):
    r = np.hypot(p[:, 0] - 0.5, p[:, 1] - 0.5)
    return (np.all(np.abs(r - 0.5) < 1e-9) or np.all(np.abs(p[:, 2]) < 1e-9)
            or np.all(np.abs(p[:, 2] - 1) < 1e-9))


def xz(c):
    return np.column_stack([c[:, 0], np.full(len(c), 0.5), c[:, 1]])


def xz_boundary(p):
    return abs(p[0, 1] - 0.5) < 1e-12 and on_disk_boundary(p[:, [0, 2, 1]])


# name: (make, expected VTK types, exact measure, boundary test, normal of 2D meshes)
MESHES = {
    "quads_disk.vtu": (quads_disk, {9}, DISK_AREA, on_disk_boundary, (0, 0, 1)),
    "mixed_disk.vtu": (mixed_disk, {5, 9}, DISK_AREA, on_disk_boundary, (0, 0, 1)),
    "quads_disk_xz.vtu": (lambda: quads_disk(xz), {9}, DISK_AREA, xz_boundary, (0, -1, 0)),
    "tris_disk.vtu": (tris_disk, {5}, DISK_AREA, on_disk_boundary, (0, 0, 1)),
    "hexes_box.vtu": (hexes_box, {12}, 1.0, on_box_boundary, None),
    "wedges_cylinder.vtu": (wedges_cylinder, {13}, math.pi * 0.25, on_cylinder_boundary, None),
    "tets_box.vtu": (tets_box, {10}, 1.0, on_box_boundary, None),
    "mixed_box.vtu": (mixed_box, {10, 12, 13, 14}, 1.0, on_box_boundary, None),
}


def check(path, types, exact, on_boundary, normal):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfCells() == 0:
        raise RuntimeError(path + ": cannot be read back")
    cell_types = vtk_to_numpy(grid.GetCellTypesArray())
    found = {int(t): int((cell_types == t).sum()) for t in np.unique(cell_types)}
    size = measures(grid)
    line = "%-20s %6d points  %-48s measure %.6f (exact %.6f)  min %.3g  %5.1f kB" % (
        os.path.basename(path), grid.GetNumberOfPoints(),
        ", ".join("%d %s" % (n, VTK_NAMES[t]) for t, n in found.items()),
        size.sum(), exact, size.min(), os.path.getsize(path) / 1024.0)
    problems = []
    if set(found) != types:
        problems.append("cell types %s, expected %s" % (sorted(found), sorted(types)))
    if size.min() <= 0:
        problems.append("non-positive cell measure")
    if abs(size.sum() - exact) > 0.01 * exact:
        problems.append("total measure off by more than 1%")
    if normal is None:
        sub = min_sub_tet_volume(grid)
        line += "  min sub-tet %.3f" % sub
        if sub <= 0:
            problems.append("inverted cells or twisted faces")
    else:
        area = signed_areas(grid, np.array(normal, dtype=float))
        if area.min() <= 0:
            problems.append("%d cells oriented against %s" % ((area <= 0).sum(), normal))
    bad = unmatched_sides(grid, on_boundary)
    line += "  conforming" if not bad else "  %d unmatched sides" % len(bad)
    if bad:
        problems.append("not conforming")
    for name in ("Linear", "CellIndex"):
        if not (grid.GetPointData().GetArray(name) or grid.GetCellData().GetArray(name)):
            problems.append("no array " + name)
    print(line)
    return problems


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "Testing", "Data", "Gmsh")
    os.makedirs(out_dir, exist_ok=True)
    print("Gmsh", gmsh.__version__)
    failed = False
    for name, (make, types, exact, on_boundary, normal) in MESHES.items():
        path = os.path.join(out_dir, name)
        write(make(), path)
        for p in check(path, types, exact, on_boundary, normal):
            print("  FAILED:", p)
            failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
