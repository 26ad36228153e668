"""vtkMeshProjectionFilter on every linear cell type, every dataset type and
composite datasets (VTK Python: /usr/bin/python3 with the build's python
directory on PYTHONPATH). Meshes: Testing/Data/Gmsh (point array Linear =
1 + 2x - 3y + 0.5z, cell array CellIndex) and meshes made here.

    a. Gmsh pairs (2D and 3D, mixed cell types): Linear exact, output = Input's
       type and counts, covered volume and fractions, extensive totals kept,
       the integral of a nonlinear P1 field kept by the cell means;
    b. advancing front == brute force on mixed meshes;
    c. every vtkDataSet type on both ports (image data 3D, 2D, in the plane
       x = const; rectilinear; curved structured; polydata of quads, of
       triangle strips, of hexagons and pentagons) and pentagonal and
       hexagonal prisms;
    d. polyhedra (hexes_box as face streams, some faces reversed) == hexahedra;
    e. errors: nonlinear cells not accepted (TestMeshProjectionSecondOrder.py
       has those accepted), twisted hexahedra, 2D Source for a 3D Input,
       lower-dimensional cells left out;
    f. composites: multiblock, partitioned dataset (collection) Input leaf by
       leaf; composite Source == the uncut mesh; the pieces' TargetBlock.
"""
import math
import os
import time

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_STRING, vtkIdList, vtkPoints
from vtkmodules.vtkCommonDataModel import (VTK_HEXAGONAL_PRISM, VTK_PENTAGONAL_PRISM,
                                           VTK_POLYHEDRON, VTK_QUADRATIC_LINEAR_WEDGE,
                                           VTK_BIQUADRATIC_TRIANGLE, VTK_TRIANGLE, vtkCellArray,
                                           vtkDataSetAttributes, vtkImageData,
                                           vtkMultiBlockDataSet,
                                           vtkPartitionedDataSet,
                                           vtkPartitionedDataSetCollection, vtkPointSet, vtkPolyData,
                                           vtkRectilinearGrid, vtkStructuredGrid, vtkTable,
                                           vtkUnstructuredGrid)
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkFiltersCore import vtkStripper
from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter

from meshprojection import vtkMeshProjectionFilter
from mpsupport.testing import GMSH, check, cut, finish, integral, read

START = time.time()


def gmsh(name):
    return read(os.path.join(GMSH, name + ".vtu"))


# ---------------------------------------------------------------------------
# Helpers


def xyz(ds):
    """The points of any vtkDataSet as an (n, 3) array."""
    if isinstance(ds, vtkPointSet) and ds.GetPoints() is not None:
        return vtk_to_numpy(ds.GetPoints().GetData()).astype(float)
    return np.array([ds.GetPoint(i) for i in range(ds.GetNumberOfPoints())], dtype=float)


def lin(x):
    return 1 + 2 * x[:, 0] - 3 * x[:, 1] + 0.5 * x[:, 2]


def smooth(x):
    return np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + x[:, 2] ** 2


def set_point_array(ds, name, values):
    a = numpy_to_vtk(np.ascontiguousarray(values, dtype=float), deep=True)
    a.SetName(name)
    ds.GetPointData().AddArray(a)
    return ds


def set_cell_array(ds, name, values):
    a = numpy_to_vtk(np.ascontiguousarray(values, dtype=float), deep=True)
    a.SetName(name)
    ds.GetCellData().AddArray(a)
    return ds


def with_fields(ds):
    """Linear and U (nonlinear) on the points, computed from the coordinates."""
    x = xyz(ds)
    set_point_array(ds, "Linear", lin(x))
    set_point_array(ds, "U", smooth(x))
    return ds


def without_u(grid):
    """A deep copy of an unstructured grid without its own U (a target whose
    U can only come from Source)."""
    copy = vtkUnstructuredGrid()
    copy.DeepCopy(grid)
    copy.GetPointData().RemoveArray("U")
    return copy


def point_array(ds, name):
    a = ds.GetPointData().GetArray(name)
    return None if a is None else vtk_to_numpy(a).astype(float)


def cell_array(ds, name):
    a = ds.GetCellData().GetArray(name)
    return None if a is None else vtk_to_numpy(a).astype(float)


class Projection:
    """One run of a fresh filter, with its errors and warnings."""

    def __init__(self, target, source, **options):
        self.errors, self.warnings = [], []
        f = vtkMeshProjectionFilter()
        f.SetCacheOperator(False)

        @calldata_type(VTK_STRING)
        def on_error(obj, event, text):
            self.errors.append(str(text))

        @calldata_type(VTK_STRING)
        def on_warning(obj, event, text):
            self.warnings.append(str(text))

        # Observed messages are not printed (vtkObject::GlobalWarningDisplayOff
        # would suppress the events themselves, so it is not used).
        f.AddObserver("ErrorEvent", on_error)
        f.AddObserver("WarningEvent", on_warning)
        f.GetExecutive().AddObserver("ErrorEvent", on_error)
        for key, value in options.items():
            getattr(f, "Set" + key)(value)
        f.SetInputData(target)
        f.SetSourceData(source)
        f.Update()
        self.filter, self.target, self.source = f, target, source
        self.out = f.GetOutputDataObject(0)
        self.covered = f.GetCoveredMeasure()

    def error(self, text):
        return any(text in e for e in self.errors)

    def warning(self, text):
        return any(text in w for w in self.warnings)


def inside_points(out):
    """The points all of whose cells are covered whole (CoveredFraction 1)."""
    fraction = cell_array(out, "CoveredFraction")
    inside = np.ones(out.GetNumberOfPoints(), dtype=bool)
    ids = vtkIdList()
    for c in np.nonzero(fraction < 1 - 1e-12)[0]:
        out.GetCellPoints(int(c), ids)
        inside[[ids.GetId(i) for i in range(ids.GetNumberOfIds())]] = False
    return inside


def linear_error(out, name="Linear", inside=False):
    """Largest |projected Linear - exact| over the valid points (relative to
    max(1, |exact|)), and the number of points compared. With `inside`, only
    the points whose cells are all covered whole count."""
    values = point_array(out, name)
    mask = point_array(out, "vtkValidPointMask")
    if values is None or mask is None:
        return float("inf"), 0
    valid = mask != 0
    if inside:
        valid &= inside_points(out)
    exact = lin(xyz(out))
    scale = max(1.0, float(np.max(np.abs(exact), initial=0.0)))
    return (float(np.max(np.abs(values[valid] - exact[valid]), initial=0.0)) / scale,
            int(valid.sum()))


def relative_difference(a, b):
    """max |a - b| / max(|b|) over the finite entries, inf when the NaN
    pattern or the shapes differ."""
    if a is None or b is None or a.shape != b.shape:
        return float("inf")
    fa, fb = np.isfinite(a), np.isfinite(b)
    if not np.array_equal(fa, fb):
        return float("inf")
    if not fa.any():
        return 0.0
    scale = max(float(np.max(np.abs(b[fb]))), 1e-300)
    return float(np.max(np.abs(a[fa] - b[fb]))) / scale


def same_results(a, b, what, tol=1e-12, points=None, cells=None):
    """Every projected array of output `b` (or those named) equals `a`'s."""
    def names(attributes):
        return [attributes.GetArrayName(i) for i in range(attributes.GetNumberOfArrays())]
    points = names(b.GetPointData()) if points is None else points
    cells = names(b.GetCellData()) if cells is None else cells
    check(len(points) + len(cells) > 0, "%s: arrays to compare" % what)
    for name in points:
        d = relative_difference(point_array(a, name), point_array(b, name))
        check(d <= tol, "%s: point array %s differs by %g (relative)" % (what, name, d))
    for name in cells:
        d = relative_difference(cell_array(a, name), cell_array(b, name))
        check(d <= tol, "%s: cell array %s differs by %g (relative)" % (what, name, d))


def check_linear(p, what, expected_covered=None, min_valid=1, all_valid=False, tol=1e-12):
    out = p.out
    check(not p.errors, "%s: no error (%r)" % (what, p.errors))
    check(out.GetClassName() == p.target.GetClassName(),
          "%s: output is a %s, Input a %s" % (what, out.GetClassName(), p.target.GetClassName()))
    check(out.GetNumberOfPoints() == p.target.GetNumberOfPoints() and
          out.GetNumberOfCells() == p.target.GetNumberOfCells(),
          "%s: output counts %d/%d, Input's %d/%d" % (what, out.GetNumberOfPoints(),
                                                      out.GetNumberOfCells(),
                                                      p.target.GetNumberOfPoints(),
                                                      p.target.GetNumberOfCells()))
    err, valid = linear_error(out)
    if valid == out.GetNumberOfPoints() and np.all(cell_array(out, "CoveredFraction") == 1):
        check(err <= tol, "%s: Linear exact at valid points (error %g)" % (what, err))
    else:
        # Partly covered: exact at the points whose cells are all covered
        # whole. A point whose support barely meets Source (a sliver of 1e-7
        # of it) has a nearly singular row: its value carries the rounding
        # of the solve times that conditioning (seen: up to 2e-9).
        check(err <= 1e-7, "%s: Linear at every valid point (error %g)" % (what, err))
        err, inside = linear_error(out, inside=True)
        check(err <= tol and inside > 0, "%s: Linear exact at the %d valid points inside the "
              "overlap (error %g)" % (what, inside, err))
    check(valid >= min_valid, "%s: %d valid points (expected >= %d)" % (what, valid, min_valid))
    if all_valid:
        check(valid == out.GetNumberOfPoints(),
              "%s: all %d points valid (%d)" % (what, out.GetNumberOfPoints(), valid))
    if expected_covered is not None:
        check(abs(p.covered - expected_covered) <= 1e-12 * max(1.0, expected_covered),
              "%s: covered measure %r, expected %r" % (what, p.covered, expected_covered))


def cell_sizes(ds):
    """Areas or volumes of the cells (vtkCellSizeFilter)."""
    f = vtkCellSizeFilter()
    f.SetInputData(ds)
    f.Update()
    out = f.GetOutput()
    a = cell_array(out, "Volume")
    return a if np.any(a) else cell_array(out, "Area")


def unstructured(points, types, cells):
    """An unstructured grid of `cells` (lists of point ids) of `types`."""
    g = vtkUnstructuredGrid()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=True))
    g.SetPoints(p)
    for t, c in zip(types, cells):
        ids = vtkIdList()
        for i in c:
            ids.InsertNextId(int(i))
        g.InsertNextCell(int(t), ids)
    return g


def polydata(points, polys=None, strips=None):
    pd = vtkPolyData()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=float), deep=True))
    pd.SetPoints(p)
    for cells, setter in ((polys, pd.SetPolys), (strips, pd.SetStrips)):
        if cells is not None:
            ca = vtkCellArray()
            for c in cells:
                ca.InsertNextCell(len(c))
                for i in c:
                    ca.InsertCellPoint(int(i))
            setter(ca)
    return pd


def as_polydata(grid):
    """A planar unstructured grid's cells as polydata polys (same points, same cells)."""
    pd = vtkPolyData()
    pd.SetPoints(grid.GetPoints())
    cells = vtkCellArray()
    cells.DeepCopy(grid.GetCells())
    pd.SetPolys(cells)
    pd.GetPointData().ShallowCopy(grid.GetPointData())
    pd.GetCellData().ShallowCopy(grid.GetCellData())
    return pd


def moved(grid, transform):
    """A copy of `grid` with its points mapped by transform((n, 3) array)."""
    g = grid.NewInstance()
    g.DeepCopy(grid)
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(transform(xyz(grid)), dtype=float), deep=True))
    g.SetPoints(p)
    return with_fields(g)


# The meshes. Every Source gets U and Linear computed from its coordinates.
MESHES = {name: with_fields(gmsh(name)) for name in (
    "quads_disk", "mixed_disk", "tris_disk", "hexes_box", "wedges_cylinder", "tets_box",
    "mixed_box")}
BOXES = ("hexes_box", "tets_box", "mixed_box")

# ---------------------------------------------------------------------------
# a. Gmsh pairs
PAIRS_2D = [("quads_disk", "tris_disk"), ("tris_disk", "mixed_disk"), ("mixed_disk", "quads_disk")]
PAIRS_3D = [("hexes_box", "tets_box"), ("tets_box", "mixed_box"), ("mixed_box", "hexes_box"),
            ("wedges_cylinder", "mixed_box")]
disk_area = None
for t, s in PAIRS_2D + PAIRS_3D:
    target, source = MESHES[t], MESHES[s]
    what = "%s <- %s" % (t, s)
    p = Projection(target, source)
    box = t in BOXES and s in BOXES
    check_linear(p, what, expected_covered=1.0 if box else None,
                 all_valid=True)
    fraction = cell_array(p.out, "CoveredFraction")
    if box:
        worst = float(np.max(np.abs(fraction - 1)))
        check(worst <= 1e-12, "%s: CoveredFraction == 1 on every cell (off by %g)" % (what, worst))
    if t == "wedges_cylinder":
        # The cylinder is inside the box: covered whole, its volume.
        volume = float(cell_sizes(target).sum())
        check(abs(p.covered - volume) <= 1e-12 * volume,
              "%s: covered volume %r == the cylinder's %r" % (what, p.covered, volume))
        worst = float(np.max(np.abs(fraction - 1)))
        check(worst <= 1e-12, "%s: cylinder covered whole (off by %g)" % (what, worst))
    if t in ("quads_disk", "tris_disk", "mixed_disk"):
        # Same polygonal disk drawn at different sizes: the overlap is the
        # smaller of the two areas at most, and near pi - pi 0.3^2.
        areas = (float(cell_sizes(target).sum()), float(cell_sizes(source).sum()))
        check(p.covered <= min(areas) * (1 + 1e-12) and abs(p.covered - math.pi * 0.91) < 0.01,
              "%s: covered area %r (areas %r)" % (what, p.covered, areas))
    if box:
        # EXTENSIVE: totals are kept.
        e = Projection(target, source,
                       CellDataQuantity=vtkMeshProjectionFilter.EXTENSIVE)
        total_t = float(np.sum(cell_array(e.out, "CellIndex")))
        total_s = float(np.sum(cell_array(source, "CellIndex")))
        check(abs(total_t - total_s) <= 1e-12 * abs(total_s),
              "%s: extensive CellIndex total %r == Source's %r" % (what, total_t, total_s))

# A nonlinear P1 field: the cell means (point array to cells) times the cell
# volumes add up to the exact integral of the Source's P1 field.
p = Projection(MESHES["hexes_box"], MESHES["tets_box"],
               PointDataTarget=vtkMeshProjectionFilter.TO_POINTS_AND_CELLS)
means = cell_array(p.out, "U")
check(means is not None and point_array(p.out, "U") is not None,
      "points and cells: U on the points and on the cells")
if means is not None:
    exact, volume = integral(MESHES["tets_box"], "U")
    got = float(np.sum(means * cell_sizes(MESHES["hexes_box"])))
    check(abs(got - exact) <= 1e-12 * abs(exact),
          "hexes_box <- tets_box: sum of U's cell means x volume %r == integral %r" % (got, exact))
    check(abs(volume - 1) < 1e-12, "tets_box volume %r" % volume)

# ---------------------------------------------------------------------------
# b. Advancing front == brute force
for t, s in (("mixed_box", "hexes_box"), ("mixed_disk", "quads_disk")):
    options = dict(PointDataTarget=vtkMeshProjectionFilter.TO_POINTS_AND_CELLS,
                   CellDataTarget=vtkMeshProjectionFilter.TO_POINTS_AND_CELLS)
    front = Projection(MESHES[t], MESHES[s], **options)
    brute = Projection(MESHES[t], MESHES[s], SearchMethod=vtkMeshProjectionFilter.BRUTE_FORCE,
                       **options)
    check(front.filter.GetSearchMethod() == vtkMeshProjectionFilter.ADVANCING_FRONT and
          brute.filter.GetSearchMethod() == vtkMeshProjectionFilter.BRUTE_FORCE, "search methods set")
    same_results(brute.out, front.out, "%s <- %s: brute force == front" % (t, s))
    check(abs(front.covered - brute.covered) <= 1e-12 * front.covered,
          "%s <- %s: covered measure front %r brute %r" % (t, s, front.covered, brute.covered))

# ---------------------------------------------------------------------------
# c. Every dataset type on both ports


def image(origin, spacing, dims):
    im = vtkImageData()
    im.SetOrigin(*origin)
    im.SetSpacing(*spacing)
    im.SetDimensions(*dims)
    return with_fields(im)


def both_ports(ds, mesh, what, covered, ds_covered_whole=True, mesh_covered_whole=False):
    """ds <- mesh and mesh <- ds: Linear exact, types kept, covered measure."""
    p = Projection(ds, mesh)
    check_linear(p, "%s <- %s" % (what, "mesh"), expected_covered=covered,
                 all_valid=ds_covered_whole)
    if ds_covered_whole:
        worst = float(np.max(np.abs(cell_array(p.out, "CoveredFraction") - 1)))
        check(worst <= 1e-12, "%s: covered whole (CoveredFraction off by %g)" % (what, worst))
    q = Projection(mesh, ds)
    check_linear(q, "mesh <- %s" % what, expected_covered=covered, all_valid=mesh_covered_whole)
    return p, q


SQUARE = ((-0.65, -0.15), (-0.6, 0.0))  # inside the disk, away from the hole: area 0.3
AREA = 0.5 * 0.6
BOX = ((0.1, 0.9), (0.2, 0.7), (0.0, 1.0))  # inside [0,1]^3: volume 0.4
VOLUME = 0.8 * 0.5 * 1.0

# vtkImageData: voxels (3D), pixels (2D, z = 0), pixels in the plane x = 0.3.
im3 = image((0.1, 0.2, 0.0), (0.8 / 8, 0.5 / 5, 1.0 / 7), (9, 6, 8))
both_ports(im3, MESHES["tets_box"], "image 3D", VOLUME)
whole = image((0, 0, 0), (1 / 6, 1 / 5, 1 / 4), (7, 6, 5))
both_ports(whole, MESHES["tets_box"], "image 3D [0,1]^3", 1.0, mesh_covered_whole=True)
im2 = image((-0.65, -0.6, 0.0), (0.5 / 10, 0.6 / 12, 1.0), (11, 13, 1))
both_ports(im2, MESHES["tris_disk"], "image 2D", AREA)
both_ports(im2, MESHES["quads_disk"], "image 2D vs quads", AREA)
im2x = image((0.3, -0.65, -0.6), (1.0, 0.5 / 10, 0.6 / 12), (1, 11, 13))
tris_x = moved(MESHES["tris_disk"], lambda x: np.c_[np.full(len(x), 0.3), x[:, 0], x[:, 1]])
both_ports(im2x, tris_x, "image 2D in x = 0.3", AREA)
# The plane x = 0.3 gives the z = 0 result (its coordinates are picked, not
# mapped) for a field that moves with the mesh.
same_x = vtkUnstructuredGrid()
same_x.DeepCopy(tris_x)
set_point_array(same_x, "V", smooth(xyz(MESHES["tris_disk"])))
same_z = vtkUnstructuredGrid()
same_z.DeepCopy(MESHES["tris_disk"])
set_point_array(same_z, "V", smooth(xyz(MESHES["tris_disk"])))
in_x = Projection(im2x, same_x)
in_z = Projection(im2, same_z)
d = relative_difference(point_array(in_x.out, "V"), point_array(in_z.out, "V"))
check(d <= 1e-12, "image in x = 0.3 == image in z = 0 for a field moving with the mesh (%g)" % d)

# Image data on both ports, of other extents: the Source is asked for its
# whole extent, not for the Input's (the pipeline's default, beyond the
# coarser Source's extent here; a reader would give only that part).
fine = image((0.0, 0.0, 0.0), (1.0 / 20, 1.0 / 16, 1.0), (21, 17, 1))
coarse = image((-0.1, -0.1, 0.0), (1.2 / 9, 1.2 / 7, 1.0), (10, 8, 1))
p = Projection(fine, coarse)
check_linear(p, "image <- coarser image of a larger extent", expected_covered=1.0, all_valid=True)
asked = p.filter.GetExecutive().GetInputInformation(1, 0).Get(vtkStreamingDemandDrivenPipeline.UPDATE_EXTENT())
check(tuple(asked) == tuple(coarse.GetExtent()),
      "the Source asked for %s, its whole extent is %s" % (tuple(asked), coarse.GetExtent()))
# Pixels and voxels with ghost cells (split cells: the split leaves them
# out): no crash, the ghost cell uncovered, Linear exact elsewhere.
# (Each ghost cell's corners are shared with other cells: all stay valid.)
for ghosted, what, cell in ((image((0.1, 0.1, 0.0), (0.08, 0.08, 1.0), (11, 11, 1)), "pixels", 5),
                            (image((0.1, 0.1, 0.1), (0.1, 0.1, 0.1), (7, 7, 7)), "voxels", 86)):
    ghost = np.zeros(ghosted.GetNumberOfCells(), dtype=np.uint8)
    ghost[cell] = vtkDataSetAttributes.DUPLICATECELL
    g = numpy_to_vtk(ghost, deep=1)
    g.SetName(vtkDataSetAttributes.GhostArrayName())
    ghosted.GetCellData().AddArray(g)
    p = Projection(ghosted, MESHES["tets_box"] if what == "voxels" else coarse)
    check(not p.errors, "%s with a ghost cell: errors %r" % (what, p.errors))
    fraction = cell_array(p.out, "CoveredFraction")
    check(fraction[cell] == 0 and np.all(np.delete(fraction, cell) > 0),
          "%s with a ghost cell: covered fractions %s" % (what, fraction[:8]))
    err, valid = linear_error(p.out)
    check(err <= 1e-12 and valid == p.out.GetNumberOfPoints(),
          "%s with a ghost cell: Linear error %g, %d of %d points valid"
          % (what, err, valid, p.out.GetNumberOfPoints()))

# vtkRectilinearGrid: graded coordinates of [0,1]^3.
rg = vtkRectilinearGrid()
coords = [np.linspace(0, 1, 8) ** 1.4, 0.5 - 0.5 * np.cos(np.linspace(0, math.pi, 7)),
          np.linspace(0, 1, 6) ** 0.8]
rg.SetDimensions(*[len(c) for c in coords])
rg.SetXCoordinates(numpy_to_vtk(coords[0], deep=True))
rg.SetYCoordinates(numpy_to_vtk(coords[1], deep=True))
rg.SetZCoordinates(numpy_to_vtk(coords[2], deep=True))
with_fields(rg)
both_ports(rg, MESHES["tets_box"], "rectilinear", 1.0, mesh_covered_whole=True)
both_ports(rg, MESHES["mixed_box"], "rectilinear vs mixed", 1.0, mesh_covered_whole=True)
# 2D rectilinear in z = 0.
rg2 = vtkRectilinearGrid()
c2 = [-0.65 + 0.5 * np.linspace(0, 1, 9) ** 1.3, -0.6 + 0.6 * np.linspace(0, 1, 7) ** 0.7,
      np.zeros(1)]
rg2.SetDimensions(9, 7, 1)
for setter, c in zip((rg2.SetXCoordinates, rg2.SetYCoordinates, rg2.SetZCoordinates), c2):
    setter(numpy_to_vtk(np.ascontiguousarray(c), deep=True))
with_fields(rg2)
both_ports(rg2, MESHES["mixed_disk"], "rectilinear 2D", AREA)

# vtkStructuredGrid: [0,1]^3 curved inside (x += 0.03 sin(3y) sin(pi x)): the
# boundary stays the box's.
n = (9, 8, 7)
g = np.stack(np.meshgrid(*[np.linspace(0, 1, k) for k in n], indexing="ij"), axis=-1)
g = g.transpose(2, 1, 0, 3).reshape(-1, 3)  # x fastest
g[:, 0] += 0.03 * np.sin(3 * g[:, 1]) * np.sin(math.pi * g[:, 0])
g[:, 2] += 0.02 * np.cos(2 * g[:, 0]) * np.sin(math.pi * g[:, 2])
sg = vtkStructuredGrid()
sg.SetDimensions(*n)
sgp = vtkPoints()
sgp.SetData(numpy_to_vtk(g, deep=True))
sg.SetPoints(sgp)
with_fields(sg)
check(abs(float(cell_sizes(sg).sum()) - 1) < 1e-3, "structured grid fills about [0,1]^3")
both_ports(sg, MESHES["tets_box"], "structured", 1.0, mesh_covered_whole=True)
both_ports(sg, MESHES["hexes_box"], "structured vs hexes", 1.0, mesh_covered_whole=True)

# vtkPolyData of quadrilaterals: the same cells as quads_disk, the same result.
quads_pd = as_polydata(MESHES["quads_disk"])
p = Projection(quads_pd, MESHES["tris_disk"])
check_linear(p, "polydata quads <- tris_disk", all_valid=True)
same_results(p.out, Projection(MESHES["quads_disk"], MESHES["tris_disk"]).out,
             "polydata quads == quads_disk as Input", points=["U", "Linear", "vtkValidPointMask"],
             cells=["CellIndex", "CoveredFraction"])
q = Projection(MESHES["tris_disk"], quads_pd)
check_linear(q, "tris_disk <- polydata quads", all_valid=False)
same_results(q.out, Projection(MESHES["tris_disk"], MESHES["quads_disk"]).out,
             "polydata quads == quads_disk as Source")

# Triangle strips (vtkStripper on tris_disk): the same triangles, the same
# P1 field.
stripper = vtkStripper()
stripper.SetInputData(as_polydata(MESHES["tris_disk"]))
stripper.Update()
strips = stripper.GetOutput()
check(strips.GetNumberOfStrips() > 0 and strips.GetNumberOfStrips() < MESHES["tris_disk"].GetNumberOfCells(),
      "vtkStripper made %d strips" % strips.GetNumberOfStrips())
check(np.array_equal(xyz(strips), xyz(MESHES["tris_disk"])), "strips keep tris_disk's points")
p = Projection(strips, MESHES["quads_disk"])
check_linear(p, "strips <- quads_disk", all_valid=True)
same_results(p.out, Projection(MESHES["tris_disk"], MESHES["quads_disk"]).out,
             "strips == tris_disk as Input", points=["U", "Linear", "vtkValidPointMask"], cells=[])
q = Projection(MESHES["quads_disk"], strips)
check_linear(q, "quads_disk <- strips")
same_results(q.out, Projection(MESHES["quads_disk"], MESHES["tris_disk"]).out,
             "strips == tris_disk as Source", points=["U", "Linear", "vtkValidPointMask"],
             cells=["CoveredFraction"])
check(abs(p.covered - Projection(MESHES["tris_disk"], MESHES["quads_disk"]).covered) <= 1e-12 * p.covered,
      "strips cover what their triangles cover")


def honeycomb(r, x0, y0, columns, rows):
    """Pointy-top hexagons of circumradius r in rows; the first and last rows
    are cut through the centres (pentagons). Returns (points, polygons) with
    shared points (conforming)."""
    w = math.sqrt(3) * r
    keys, points, polygons = {}, [], []

    def pid(p):
        k = (round(p[0], 9), round(p[1], 9))
        if k not in keys:
            keys[k] = len(points)
            points.append(p)
        return keys[k]
    for j in range(rows):
        for i in range(columns - (j % 2)):
            cx, cy = x0 + w * (i + 0.5 * (j % 2)), y0 + 1.5 * r * j
            hexagon = [(cx + r * math.cos(math.radians(a)), cy + r * math.sin(math.radians(a)))
                       for a in (-90, -30, 30, 90, 150, 210)]
            if j == 0:  # the half above the centre line: a pentagon
                corners = [(cx + w / 2, cy), hexagon[2], hexagon[3], hexagon[4], (cx - w / 2, cy)]
            elif j == rows - 1:
                corners = [(cx - w / 2, cy), hexagon[5], hexagon[0], hexagon[1], (cx + w / 2, cy)]
            else:
                corners = hexagon
            polygons.append([pid(c) for c in corners])
    return np.array(points), polygons


def polygon_area(x, c):
    px, py = x[c, 0], x[c, 1]
    return 0.5 * float(np.sum(px * np.roll(py, -1) - np.roll(px, -1) * py))


# General polygons: hexagons and pentagons, in the disk away from the hole.
hp, hpolys = honeycomb(0.06, -0.62, -0.7, 5, 6)
hp3 = np.c_[hp, np.zeros(len(hp))]
hex_pd = with_fields(polydata(hp3, polys=hpolys))
hex_area = sum(polygon_area(hp, c) for c in hpolys)
check(min(polygon_area(hp, c) for c in hpolys) > 0, "polygons counterclockwise")
check(sorted(set(len(c) for c in hpolys)) == [5, 6], "pentagons and hexagons")
both_ports(hex_pd, MESHES["tris_disk"], "polygons", hex_area)
both_ports(hex_pd, MESHES["mixed_disk"], "polygons vs mixed", hex_area)

# Pentagonal and hexagonal prisms: the polygons extruded in 3 layers, inside
# [0,1]^3. VTK's prisms: base counterclockwise seen from the top face.
pp, ppolys = honeycomb(0.07, 0.15, 0.12, 5, 7)
layers = np.array([0.2, 0.4, 0.55, 0.8])
prism_points = np.concatenate([np.c_[pp, np.full(len(pp), z)] for z in layers])
types, cells = [], []
for k in range(len(layers) - 1):
    for c in ppolys:
        bottom = [k * len(pp) + i for i in c]
        top = [(k + 1) * len(pp) + i for i in c]
        types.append(VTK_PENTAGONAL_PRISM if len(c) == 5 else VTK_HEXAGONAL_PRISM)
        cells.append(bottom + top)
prisms = with_fields(unstructured(prism_points, types, cells))
prism_volume = sum(polygon_area(pp, c) for c in ppolys) * (layers[-1] - layers[0])
sizes = cell_sizes(prisms)
check(sizes.min() > 0 and abs(float(sizes.sum()) - prism_volume) <= 1e-12,
      "prism mesh: vtkCellSizeFilter volume %r == %r" % (float(sizes.sum()), prism_volume))
check(set(types) == {VTK_PENTAGONAL_PRISM, VTK_HEXAGONAL_PRISM}, "both prism types present")
both_ports(prisms, MESHES["tets_box"], "prisms", prism_volume)
both_ports(prisms, MESHES["mixed_box"], "prisms vs mixed", prism_volume)

# ---------------------------------------------------------------------------
# d. Polyhedra: hexes_box as face streams (every third face reversed).
HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
hexes = MESHES["hexes_box"]
hex_conn = vtk_to_numpy(hexes.GetCells().GetConnectivityArray()).reshape(-1, 8)
poly = vtkUnstructuredGrid()
poly.SetPoints(hexes.GetPoints())
reversed_faces = 0
for c, corners in enumerate(hex_conn):
    stream = [6]
    for k, face in enumerate(HEX_FACES):
        ids = [int(corners[i]) for i in face]
        if (c + k) % 3 == 0:
            ids.reverse()
            reversed_faces += 1
        stream += [4] + ids
    idl = vtkIdList()
    for i in stream:
        idl.InsertNextId(i)
    poly.InsertNextCell(VTK_POLYHEDRON, idl)
poly.GetPointData().ShallowCopy(hexes.GetPointData())
poly.GetCellData().ShallowCopy(hexes.GetCellData())
check(poly.GetNumberOfCells() == hexes.GetNumberOfCells() and reversed_faces > 0,
      "polyhedra built (%d reversed faces)" % reversed_faces)
check(poly.GetCellType(0) == VTK_POLYHEDRON, "polyhedron cells")
for s in ("tets_box", "mixed_box"):
    p = Projection(poly, MESHES[s])
    check_linear(p, "polyhedra <- %s" % s, expected_covered=1.0, all_valid=True)
    same_results(p.out, Projection(hexes, MESHES[s]).out, "polyhedra == hexahedra as Input (%s)" % s)
for t in ("tets_box", "mixed_box"):
    p = Projection(MESHES[t], poly)
    check_linear(p, "%s <- polyhedra" % t, expected_covered=1.0, all_valid=True)
    same_results(p.out, Projection(MESHES[t], hexes).out, "polyhedra == hexahedra as Source (%s)" % t)

# ---------------------------------------------------------------------------
# e. Errors and warnings


def check_passed_through(p, what):
    out = p.out
    check(out.GetNumberOfPoints() == p.target.GetNumberOfPoints() and
          out.GetNumberOfCells() == p.target.GetNumberOfCells(), "%s: Input passed through" % what)
    check(out.GetPointData().GetArray("vtkValidPointMask") is None and
          out.GetCellData().GetArray("CoveredFraction") is None and
          out.GetPointData().GetArray("U") is None,
          "%s: no projected arrays, no vtkValidPointMask" % what)


# A biquadratic triangle in Source (7 nodes: not one of the accepted
# second-order cells).
qt = with_fields(unstructured([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0.5, 0, 0), (0.5, 0.5, 0),
                               (0, 0.5, 0), (1 / 3, 1 / 3, 0)], [VTK_BIQUADRATIC_TRIANGLE], [range(7)]))
target = without_u(MESHES["tris_disk"])
p = Projection(target, qt)
check(p.error("Tessellate"), "biquadratic triangle Source: error naming Tessellate (%r)" % p.errors)
check_passed_through(p, "biquadratic triangle")
# A quadratic-linear wedge in Source (12 nodes), next to linear ones.
qwedge_points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (0.5, 0, 0),
                 (0.5, 0.5, 0), (0, 0.5, 0), (0.5, 0, 1), (0.5, 0.5, 1), (0, 0.5, 1)]
qwedge = with_fields(unstructured(qwedge_points, [VTK_QUADRATIC_LINEAR_WEDGE], [range(12)]))
target = without_u(MESHES["tets_box"])
p = Projection(target, qwedge)
check(p.error("Tessellate"), "quadratic-linear wedge Source: error naming Tessellate (%r)" % p.errors)
check_passed_through(p, "quadratic-linear wedge")

# A twisted hexahedron (two top corners swapped), as Input and as Source.
twisted = vtkUnstructuredGrid()
twisted.DeepCopy(hexes)
conn = vtk_to_numpy(twisted.GetCells().GetConnectivityArray())
conn[6], conn[7] = int(conn[7]), int(conn[6])
twisted.GetCells().Modified()
twisted.Modified()
twisted.GetPointData().RemoveArray("U")
p = Projection(twisted, MESHES["tets_box"])
check(p.error("cannot be split"), "twisted hexahedron Input: error 'cannot be split' (%r)" % p.errors)
check_passed_through(p, "twisted hexahedron Input")
twisted_source = with_fields(twisted)
target = without_u(MESHES["tets_box"])
p = Projection(target, twisted_source)
check(p.error("cannot be split"), "twisted hexahedron Source: error 'cannot be split' (%r)" % p.errors)
check_passed_through(p, "twisted hexahedron Source")

# A 3D Input, a 2D Source.
target = without_u(MESHES["tets_box"])
p = Projection(target, MESHES["quads_disk"])
check(p.error("not to a mesh of a higher dimension"), "3D Input, 2D Source: error 'higher dimension' (%r)" % p.errors)
check_passed_through(p, "3D Input, 2D Source")

# Lower-dimensional cells (triangles among tetrahedra) are left out with a
# warning; the tetrahedra get what they get alone.
with_faces = vtkUnstructuredGrid()
with_faces.DeepCopy(MESHES["tets_box"])
tet_conn = vtk_to_numpy(with_faces.GetCells().GetConnectivityArray()).reshape(-1, 4)
for c in tet_conn[:5]:
    ids = vtkIdList()
    for i in c[:3]:
        ids.InsertNextId(int(i))
    with_faces.InsertNextCell(VTK_TRIANGLE, ids)
n_tets = MESHES["tets_box"].GetNumberOfCells()
p = Projection(with_faces, MESHES["hexes_box"])
check(p.warning("lower dimension"), "triangles among tetrahedra: a warning (%r)" % p.warnings)
check(not p.errors, "triangles among tetrahedra: no error (%r)" % p.errors)
alone = Projection(MESHES["tets_box"], MESHES["hexes_box"]).out
same_results(p.out, alone, "tets with triangles: point arrays", points=["U", "Linear"], cells=[])
ci = cell_array(p.out, "CellIndex")
vm = cell_array(p.out, "vtkValidCellMask")
check(ci is not None and relative_difference(ci[:n_tets], cell_array(alone, "CellIndex")) <= 1e-12
      and np.all(vm[n_tets:] == 0) and np.all(vm[:n_tets] == 1),
      "tets with triangles: tetrahedra's cell values as alone, triangles invalid")

# ---------------------------------------------------------------------------
# f. Composites
tets = MESHES["tets_box"]
left = cut(hexes, lambda c: c[:, 0] < 0.5)
right = cut(hexes, lambda c: c[:, 0] >= 0.5)
check(left.GetNumberOfCells() > 0 and right.GetNumberOfCells() > 0 and
      left.GetNumberOfCells() + right.GetNumberOfCells() == hexes.GetNumberOfCells(),
      "hexes_box cut into %d + %d cells" % (left.GetNumberOfCells(), right.GetNumberOfCells()))
for block in (left, right):
    block.GetPointData().RemoveArray("U")  # the output's U must come from Source
tets_target = without_u(tets)
empty = vtkUnstructuredGrid()

mb = vtkMultiBlockDataSet()
mb.SetBlock(0, left)
mb.SetBlock(1, right)
mb.SetBlock(2, empty)
nested = vtkMultiBlockDataSet()
nested.SetBlock(0, tets_target)
mb.SetBlock(3, nested)


def check_leaf(out_leaf, leaf, what, source=tets):
    check(out_leaf is not None and out_leaf.GetClassName() == leaf.GetClassName(),
          "%s: output leaf of the Input's type" % what)
    if out_leaf is None:
        return
    check(out_leaf.GetNumberOfCells() == leaf.GetNumberOfCells(), "%s: counts kept" % what)
    alone = Projection(leaf, source).out
    same_results(out_leaf, alone, "%s == projected alone" % what)
    err, valid = linear_error(out_leaf)
    check(err <= 1e-12 and valid == leaf.GetNumberOfPoints(), "%s: Linear exact (%g)" % (what, err))


p = Projection(mb, tets)
out = p.out
check(not p.errors and not p.warnings, "multiblock: no error or warning (%r %r)" % (p.errors, p.warnings))
check(isinstance(out, vtkMultiBlockDataSet) and out.GetNumberOfBlocks() == 4,
      "multiblock: 4 blocks (%s)" % out.GetClassName())
if isinstance(out, vtkMultiBlockDataSet) and out.GetNumberOfBlocks() == 4:
    check_leaf(out.GetBlock(0), left, "multiblock block 0")
    check_leaf(out.GetBlock(1), right, "multiblock block 1")
    b2 = out.GetBlock(2)
    check(b2 is not None and b2.GetNumberOfCells() == 0 and b2.GetNumberOfPoints() == 0 and
          b2.GetPointData().GetArray("vtkValidPointMask") is None,
          "multiblock: the empty block stays empty")
    b3 = out.GetBlock(3)
    check(isinstance(b3, vtkMultiBlockDataSet) and b3.GetNumberOfBlocks() == 1,
          "multiblock: nesting kept")
    if isinstance(b3, vtkMultiBlockDataSet):
        check_leaf(b3.GetBlock(0), tets_target, "multiblock nested tets")
check(abs(p.covered - 2.0) <= 1e-12 * 2, "multiblock: covered measure summed over leaves %r" % p.covered)

# A vtkTable leaf is skipped with a warning; a leaf that cannot be split (a
# twisted hexahedron) fails and is passed through with a warning; the others
# are projected.
quads_target = without_u(twisted)
mixed = vtkMultiBlockDataSet()
mixed.SetBlock(0, left)
mixed.SetBlock(1, vtkTable())
mixed.SetBlock(2, quads_target)
mixed.SetBlock(3, right)
p = Projection(mixed, tets)
out = p.out
check(not p.errors, "multiblock with a table and a twisted leaf: no error (%r)" % p.errors)
check(p.warning("not datasets"), "a table leaf: warning (%r)" % p.warnings)
check(p.warning("passed through"), "a twisted leaf in a 3D Input: warning (%r)" % p.warnings)
check(out.GetNumberOfBlocks() == 4, "table and twisted leaf: 4 blocks")
if out.GetNumberOfBlocks() == 4:
    check_leaf(out.GetBlock(0), left, "with table: block 0")
    check_leaf(out.GetBlock(3), right, "with table: block 3")
    b2 = out.GetBlock(2)
    check(b2 is not None and b2.GetNumberOfPoints() == quads_target.GetNumberOfPoints() and
          b2.GetPointData().GetArray("vtkValidPointMask") is None and
          b2.GetPointData().GetArray("U") is None, "the twisted leaf passed through")

# vtkPartitionedDataSet and vtkPartitionedDataSetCollection as Input.
pds = vtkPartitionedDataSet()
pds.SetPartition(0, left)
pds.SetPartition(1, right)
p = Projection(pds, tets)
out = p.out
check(isinstance(out, vtkPartitionedDataSet) and out.GetNumberOfPartitions() == 2,
      "partitioned dataset output (%s)" % out.GetClassName())
if isinstance(out, vtkPartitionedDataSet) and out.GetNumberOfPartitions() == 2:
    check_leaf(out.GetPartition(0), left, "partition 0")
    check_leaf(out.GetPartition(1), right, "partition 1")
check(abs(p.covered - 1.0) <= 1e-12, "partitioned dataset: covered %r" % p.covered)
pdc = vtkPartitionedDataSetCollection()
first = vtkPartitionedDataSet()
first.SetPartition(0, left)
first.SetPartition(1, right)
second = vtkPartitionedDataSet()
second.SetPartition(0, tets_target)
pdc.SetPartitionedDataSet(0, first)
pdc.SetPartitionedDataSet(1, second)
p = Projection(pdc, tets)
out = p.out
check(isinstance(out, vtkPartitionedDataSetCollection) and out.GetNumberOfPartitionedDataSets() == 2,
      "partitioned dataset collection output (%s)" % out.GetClassName())
if isinstance(out, vtkPartitionedDataSetCollection) and out.GetNumberOfPartitionedDataSets() == 2:
    check(out.GetNumberOfPartitions(0) == 2 and out.GetNumberOfPartitions(1) == 1,
          "collection: partitions per dataset kept")
    check_leaf(out.GetPartition(0, 0), left, "collection 0/0")
    check_leaf(out.GetPartition(0, 1), right, "collection 0/1")
    check_leaf(out.GetPartition(1, 0), tets_target, "collection 1/0")

# OutputIntersections on a two-block Input: the pieces of both blocks with
# their flat indices; their volumes add up to the overlap.
two = vtkMultiBlockDataSet()
two.SetBlock(0, left)
two.SetBlock(1, right)
p = Projection(two, tets, OutputIntersections=True)
pieces = p.filter.GetOutputDataObject(2)
blocks = cell_array(pieces, "TargetBlock")
volumes = cell_array(pieces, "Volume")
check(blocks is not None and set(np.unique(blocks).astype(int).tolist()) == {1, 2},
      "TargetBlock holds both blocks' flat indices (%r)" %
      (None if blocks is None else np.unique(blocks).tolist()))
if volumes is not None and blocks is not None:
    check(abs(float(volumes.sum()) - 1) <= 1e-12 and abs(p.covered - 1) <= 1e-12,
          "pieces' volume %r == overlap %r == 1" % (float(volumes.sum()), p.covered))
    for flat, block in ((1, left), (2, right)):
        v = float(volumes[blocks == flat].sum())
        expected = float(cell_sizes(block).sum())
        check(abs(v - expected) <= 1e-12, "block %d's pieces: volume %r == %r" % (flat, v, expected))
check(p.filter.GetOutputDataObject(1).GetNumberOfCells() == 0, "no polygons for a 3D Input")

# A composite Source: the blocks of a cut mesh (each with its own copy of the
# interface points) give the uncut mesh's result.


def composite_source_checks(target, mesh, cuts, what):
    blocks = [cut(mesh, k) for k in cuts]
    check(sum(b.GetNumberOfCells() for b in blocks) == mesh.GetNumberOfCells() and
          all(b.GetNumberOfCells() > 0 for b in blocks), "%s: the blocks hold every cell" % what)
    options = dict(PointDataTarget=vtkMeshProjectionFilter.TO_POINTS_AND_CELLS)
    uncut = Projection(target, mesh, **options)
    sm = vtkMultiBlockDataSet()
    for i, b in enumerate(blocks):
        sm.SetBlock(i, b)
    coll = vtkPartitionedDataSetCollection()
    part_a = vtkPartitionedDataSet()
    for i, b in enumerate(blocks[:-1]):
        part_a.SetPartition(i, b)
    part_b = vtkPartitionedDataSet()
    part_b.SetPartition(0, blocks[-1])
    coll.SetPartitionedDataSet(0, part_a)
    coll.SetPartitionedDataSet(1, part_b)
    for name, src in (("multiblock", sm), ("partitioned collection", coll)):
        p = Projection(target, src, **options)
        check(not p.errors, "%s, %s Source: no error (%r)" % (what, name, p.errors))
        check(p.out.GetClassName() == target.GetClassName(), "%s, %s Source: output type" % (what, name))
        same_results(p.out, uncut.out, "%s, %s Source == uncut" % (what, name),
                     points=["U", "Linear", "vtkValidPointMask"],
                     cells=["U", "CellIndex", "CoveredFraction", "vtkValidCellMask"])
        check(abs(p.covered - uncut.covered) <= 1e-12 * uncut.covered,
              "%s, %s Source: covered %r == %r" % (what, name, p.covered, uncut.covered))


composite_source_checks(hexes, tets, [lambda c: c[:, 0] < 0.35,
                                      lambda c: (c[:, 0] >= 0.35) & (c[:, 1] < 0.6),
                                      lambda c: (c[:, 0] >= 0.35) & (c[:, 1] >= 0.6)], "3D")
composite_source_checks(MESHES["tris_disk"], MESHES["quads_disk"],
                        [lambda c: c[:, 0] < 0, lambda c: (c[:, 0] >= 0) & (c[:, 1] < 0.2),
                         lambda c: (c[:, 0] >= 0) & (c[:, 1] >= 0.2)], "2D")

# A composite Source of vtkImageData blocks (two stacked halves of one
# image, the same voxels, split alike) gives the whole image's result.
# (Their points are computed in double: vtkAppendFilter's default precision
# would round them to float, 3e-8 off.)
whole = image((0, 0, 0), (1 / 6, 1 / 5, 1 / 6), (7, 6, 7))
halves = vtkMultiBlockDataSet()
halves.SetBlock(0, image((0, 0, 0), (1 / 6, 1 / 5, 1 / 6), (7, 6, 4)))
halves.SetBlock(1, image((0, 0, 0.5), (1 / 6, 1 / 5, 1 / 6), (7, 6, 4)))
p = Projection(tets_target, halves)
check_linear(p, "tets_box <- multiblock of two vtkImageData halves", expected_covered=1.0,
             all_valid=True)
same_results(p.out, Projection(tets_target, whole).out,
             "multiblock of two vtkImageData halves == the whole image as Source",
             points=["U", "Linear", "vtkValidPointMask"], cells=["CoveredFraction"])

print("%.1f s" % (time.time() - START))
finish()
