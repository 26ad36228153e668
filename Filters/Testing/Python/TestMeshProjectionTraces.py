"""Traces through the VTK filter: a surface or a curve inside a volume mesh
(Gmsh's tetrahedra of a ball and a box, an image), and a curve inside a 2D
mesh. Checks: front == brute force, the pieces tile every target cell,
linear fields exact on surfaces and curves inside the volume and on its
boundary (its own faces, and another mesh of the box's faces), cell data,
second-order rates for a smooth field, the errors for pairs that are not
traces."""
import math

import numpy as np

from mpsupport import gmshmeshes
from mpsupport.testing import check, covered_by_pieces, finish, mortar, observed_filter
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkMultiBlockDataSet, vtkPolyData
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkAppendFilter, vtkReverseSense
from vtkmodules.vtkFiltersGeneral import vtkTransformFilter
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource


def linear(x, y, z):
    return 1.0 + 2.0 * x - 3.0 * y + 0.5 * z


def smooth(x, y, z):
    return np.sin(2.0 * x) * np.cos(y) + z * z


def points(mesh):
    return vtk_to_numpy(mesh.GetPoints().GetData())


def values(output, name="f", cells=False):
    data = output.GetCellData() if cells else output.GetPointData()
    return vtk_to_numpy(data.GetArray(name))


def scaled(mesh, factor, shift=(0.0, 0.0, 0.0)):
    transform = vtkTransform()
    transform.Translate(*shift)
    transform.Scale(factor, factor, factor)
    f = vtkTransformFilter()
    f.SetTransform(transform)
    f.SetInputData(mesh)
    f.Update()
    return f.GetOutput()


def boundary(volume, reverse=False):
    """The volume mesh's own boundary faces (its points, its triangles)."""
    g = vtkGeometryFilter()
    g.SetInputData(volume)
    g.Update()
    if not reverse:
        return g.GetOutput()
    r = vtkReverseSense()
    r.SetInputData(g.GetOutput())
    r.Update()
    return r.GetOutput()


def cell_measures(mesh):
    """Area of each polygon (fanned) or length of each line."""
    x = points(mesh)
    cells = mesh.GetPolys() if mesh.GetNumberOfPolys() else mesh.GetLines()
    offsets = vtk_to_numpy(cells.GetOffsetsArray())
    connectivity = vtk_to_numpy(cells.GetConnectivityArray())
    result = []
    for i in range(len(offsets) - 1):
        ids = connectivity[offsets[i]:offsets[i + 1]]
        p = x[ids]
        if len(ids) == 2:
            result.append(np.linalg.norm(p[1] - p[0]))
            continue
        s = np.zeros(3)
        for k in range(1, len(ids) - 1):
            s += np.cross(p[k] - p[0], p[k + 1] - p[0])
        result.append(0.5 * np.linalg.norm(s))
    return np.array(result)


def check_trace(what, target, source, whole=True, field=linear):
    """Front == brute force, the pieces tile the target cells, the linear
    field exact at every point, the integral on the target reported."""
    if isinstance(source, vtkImageData):
        x = np.array([source.GetPoint(i) for i in range(source.GetNumberOfPoints())])
        copy = vtkImageData()
        copy.ShallowCopy(source)
        array = numpy_to_vtk(np.ascontiguousarray(field(x[:, 0], x[:, 1], x[:, 2])), deep=True)
        array.SetName("f")
        copy.GetPointData().AddArray(array)
        source = copy
    else:
        source = gmshmeshes.with_point_field(source, "f", field)
    front = mortar(target, source)
    brute = mortar(target, source, brute=True)
    uf, ub = values(front.GetOutput()), values(brute.GetOutput())
    # 1e-12 at every point that a cell covered by more than 0.1% holds; the
    # points valid through slivers only (the filter warns about them: their
    # rows are ill conditioned, about 1 / the cover, so the pieces' rounding,
    # summed in another order by the brute force, grows) to 1e-9.
    fraction = values(front.GetOutput(), "CoveredFraction", cells=True)
    cells = target.GetPolys() if target.GetNumberOfPolys() else target.GetLines()
    offsets = vtk_to_numpy(cells.GetOffsetsArray())
    connectivity = vtk_to_numpy(cells.GetConnectivityArray())
    best = np.zeros(len(uf))  # per point, the largest cover of its cells
    np.maximum.at(best, connectivity, np.repeat(fraction, np.diff(offsets)))
    tolerance = np.where(best >= 1e-3, 1e-12, 1e-9)
    difference = np.abs(uf - ub)
    same = (difference <= tolerance) | (np.isnan(uf) & np.isnan(ub))
    check(same.all(), "%s: front == brute force (%g where covered, %g through slivers only)" % (
        what, np.nanmax(np.where(best >= 1e-3, difference, 0.0)),
        np.nanmax(np.where(best < 1e-3, difference, 0.0))))
    measures = cell_measures(target)
    covered = covered_by_pieces(front, target)
    over = np.max((covered - measures) / measures)
    check(over < 1e-12, "%s: pieces overlap (%g)" % (what, over))
    if whole:
        under = np.max((measures - covered) / measures)
        check(under < 1e-12, "%s: pieces tile every cell (%g)" % (what, under))
        check(np.all(np.abs(fraction - 1) < 1e-12), "%s: every cell covered (%g)" % (what, np.max(np.abs(fraction - 1))))
    mask = values(front.GetOutput(), "vtkValidPointMask").astype(bool)
    if whole:
        check(mask.all(), "%s: every point valid (%d of %d)" % (what, mask.sum(), len(mask)))
    x = points(front.GetOutput())
    if field is linear:
        # Where the target leaves the volume, a function whose support is
        # barely covered has an ill-conditioned row (docs/limitations.md):
        # there the solver's tolerance shows. Checked: the points whose
        # cells are all covered whole.
        inner = mask.copy()
        if not whole:
            for c in np.where(fraction < 1 - 1e-12)[0]:
                inner[connectivity[offsets[c]:offsets[c + 1]]] = False
        error = np.abs(uf - linear(x[:, 0], x[:, 1], x[:, 2]))
        check(error[inner].max() < 1e-11, "%s: a linear field is exact (%g at %d points)" % (
            what, error[inner].max(), inner.sum()))
        # Every valid point, barely covered ones too: no garbage (rounding
        # slivers where the target touches the volume's boundary carry no
        # measure, so such points are invalid, not extrapolated from nothing).
        check(error[mask].max() < 1e-8, "%s: a linear field near exact at every valid point (%g)" % (
            what, error[mask].max()))
    fd = front.GetOutput().GetFieldData()
    check(fd.GetArray("TargetIntegral_f") is not None and fd.GetArray("SourceIntegral_f") is None,
          "%s: the target integral only (the source is a volume)" % what)
    print("%-34s %6d cells, %7d pieces, covered %.6f" % (
        what, target.GetNumberOfCells(), front.GetOutput(1).GetNumberOfCells(), front.GetCoveredMeasure()))
    return front


ball = gmshmeshes.volume("sphere", 0.2)
box = gmshmeshes.volume("box", 0.15)

# --- Surfaces inside the volume, and on its boundary -------------------------
check_trace("sphere r = 0.6 in the ball", scaled(gmshmeshes.surface("sphere", 0.1), 0.6), ball)
check_trace("torus in the ball", scaled(gmshmeshes.surface("torus", 0.1), 0.6), ball)
check_trace("the ball's own boundary", boundary(ball), ball)
check_trace("the ball's boundary, reversed", boundary(ball, reverse=True), ball)
check_trace("plane z = 0.37 in the box", gmshmeshes.surface("patch0.37", 0.08), box)
check_trace("plane z = 0 (the box's bottom)", gmshmeshes.surface("patch0", 0.08), box)
check_trace("the box's own faces", boundary(box), box)
check_trace("another mesh of the box's faces", gmshmeshes.surface("box", 0.1), box)
check_trace("its quads", gmshmeshes.surface("box", 0.1, quads=True), box)
# Half of the sphere leaves the box: the part inside is covered.
outside = check_trace("a sphere half out of the box", scaled(gmshmeshes.surface("sphere", 0.1), 0.4, (0.5, 0.5, 1.0)), box, whole=False)
for shift in ((0.5, 0.5, 0.0), (1.0, 0.5, 0.5), (0.0, 0.3, 0.6)):
    # Spheres across other faces: vertices on a face, and facets outside
    # touching it (once 361 off at a valid point, extrapolated from slivers).
    check_trace("a sphere across the box's face at %s" % (shift,),
                scaled(gmshmeshes.surface("sphere", 0.1), 0.4, shift), box, whole=False)
fraction = values(outside.GetOutput(), "CoveredFraction", cells=True)
check(0.3 < np.mean(fraction) < 0.7 and fraction.max() == 1.0 and fraction.min() == 0.0,
      "a sphere half out of the box: cells in, out and across (mean fraction %g)" % np.mean(fraction))

# --- An image as the volume (split into tetrahedra) ---------------------------
image = vtkImageData()
image.SetDimensions(9, 8, 10)
image.SetOrigin(-0.05, -0.05, -0.05)
image.SetSpacing(1.1 / 8, 1.1 / 7, 1.1 / 9)
check_trace("sphere in an image", scaled(gmshmeshes.surface("sphere", 0.1), 0.4, (0.5, 0.5, 0.5)), image)

# A plane through many of the image's vertices (x + y + z = 1.5 through a 5^3
# image of spacing 0.25): tetrahedra with corners on the plane.
centre = np.array([0.5, 0.5, 0.5])
u = 0.35 * np.array([1.0, -1.0, 0.0]) / math.sqrt(2.0)
v = 0.35 * np.array([1.0, 1.0, -2.0]) / math.sqrt(6.0)
plane = vtkPlaneSource()
plane.SetOutputPointsPrecision(1)  # double: points on the plane to rounding
plane.SetOrigin(*(centre - u - v))
plane.SetPoint1(*(centre + u - v))
plane.SetPoint2(*(centre - u + v))
plane.SetResolution(11, 13)
plane.Update()
grid = vtkImageData()
grid.SetDimensions(5, 5, 5)
grid.SetSpacing(0.25, 0.25, 0.25)
check_trace("plane through an image's vertices", plane.GetOutput(), grid)

# --- Curves in a volume, and in a 2D mesh (in its plane) -----------------------
# Every edge of the box's tetrahedra, on the box's own points (in double
# precision: vtkExtractEdges writes float points, 1e-8 off the edges, where
# the cuts of nearly parallel faces are ill-conditioned; see docs/limitations.md).
tets = vtk_to_numpy(box.GetCells().GetConnectivityArray()).reshape(-1, 4)
pairs = np.sort(tets[:, [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]].reshape(-1, 2), axis=1)
pairs = np.unique(pairs, axis=0)
lines = vtkCellArray()
lines.SetData(numpy_to_vtkIdTypeArray(np.arange(0, 2 * len(pairs) + 1, 2, dtype=np.int64), deep=True),
              numpy_to_vtkIdTypeArray(np.ascontiguousarray(pairs.ravel()), deep=True))
edges = vtkPolyData()
edges.SetPoints(box.GetPoints())
edges.SetLines(lines)
check_trace("every edge of the box's tetrahedra", edges, box)
check_trace("B-spline in the ball", scaled(gmshmeshes.curve("spline", 0.05), 0.25, (0.0, 0.0, -0.3)), ball)
square = gmshmeshes.surface("patch0", 0.07)
check_trace("wave in a square", gmshmeshes.moved(gmshmeshes.curve("wave", 0.03), 0.0, (0.0, 0.5, 0.0)), square)
check_trace("the square's boundary in it", gmshmeshes.curve("square", 0.04), square)
check_trace("the same, 2D mesh lifted to z = 3", gmshmeshes.moved(gmshmeshes.curve("square", 0.04), 0.0, (0.0, 0.0, 3.0)),
            gmshmeshes.moved(square, 0.0, (0.0, 0.0, 3.0)))
check_trace("a circle in a tilted plane", gmshmeshes.moved(scaled(gmshmeshes.curve("circle", 0.05), 0.3, (0.5, 0.5, 0)), 30.0),
            gmshmeshes.moved(square, 30.0))

# --- Cell data: a constant per tetrahedron ----------------------------------
source = gmshmeshes.with_point_field(box, "f", linear)
constant = numpy_to_vtk(np.full(box.GetNumberOfCells(), 2.5), deep=True)
constant.SetName("c")
source.GetCellData().AddArray(constant)
out = mortar(gmshmeshes.surface("patch0.37", 0.08), source, CellDataTarget=1).GetOutput()  # to points
c = values(out, "c")
check(np.max(np.abs(c - 2.5)) < 1e-12, "cell data to points: a constant stays exact (%g)" % np.max(np.abs(c - 2.5)))
f = mortar(gmshmeshes.surface("patch0.37", 0.08), source, CellDataTarget=2)  # to cells
c = values(f.GetOutput(), "c", cells=True)
check(np.max(np.abs(c - 2.5)) < 1e-12, "cell data to cells: a constant stays exact (%g)" % np.max(np.abs(c - 2.5)))
total = f.GetOutput().GetFieldData().GetArray("TargetIntegral_c (cell data)").GetValue(0)
check(abs(total - 2.5) < 1e-11, "cell data: its integral over the unit square is 2.5 (%g)" % total)

# --- Second order for a smooth field ----------------------------------------
errors = []
for h in (0.3, 0.15):
    target = scaled(gmshmeshes.surface("sphere", h / 2), 0.6)
    out = mortar(target, gmshmeshes.with_point_field(gmshmeshes.volume("sphere", h), "f", smooth), pieces=False).GetOutput()
    x = points(out)
    e = values(out) - smooth(x[:, 0], x[:, 1], x[:, 2])
    errors.append(math.sqrt(np.mean(e * e)))
rate = math.log(errors[0] / errors[1], 2)
print("smooth field on a sphere in the ball: rms errors %s, rate %.2f" % (errors, rate))
check(rate > 1.7, "smooth field: second order (rate %.2f)" % rate)

# --- A plane between two blocks of a composite Source -------------------------
# Each block's faces are its boundary: both blocks take the plane (reported);
# merged with their points, the blocks are one mesh and the plane takes the
# cells its normal points to (the upper block's value 2).
def half_box(z0, value):
    g = vtkImageData()
    g.SetDimensions(5, 5, 3)
    g.SetSpacing(0.25, 0.25, 0.25)
    g.SetOrigin(0.0, 0.0, z0)
    c = numpy_to_vtk(np.full(g.GetNumberOfCells(), value), deep=True)
    c.SetName("c")
    g.GetCellData().AddArray(c)
    return g


blocks = vtkMultiBlockDataSet()
blocks.SetBlock(0, half_box(0.0, 1.0))
blocks.SetBlock(1, half_box(0.5, 2.0))
between = vtkPlaneSource()
between.SetOutputPointsPrecision(1)
between.SetOrigin(0.05, 0.05, 0.5)
between.SetPoint1(0.95, 0.05, 0.5)
between.SetPoint2(0.05, 0.95, 0.5)
between.SetResolution(7, 6)
between.Update()
f, warnings = observed_filter("WarningEvent")
f.SetInputData(between.GetOutput())
f.SetSourceData(blocks)
f.SetCellDataTarget(2)
f.Update()
check(any("between two blocks" in w for w in warnings), "a plane between blocks: reported (%r)" % warnings)
merged = vtkAppendFilter()
merged.SetMergePoints(True)
merged.AddInputData(blocks.GetBlock(0))
merged.AddInputData(blocks.GetBlock(1))
merged.Update()
f = mortar(between.GetOutput(), merged.GetOutput(), CellDataTarget=2)
c = values(f.GetOutput(), "c", cells=True)
fraction = values(f.GetOutput(), "CoveredFraction", cells=True)
check(np.all(c == 2.0) and np.all(np.abs(fraction - 1) < 1e-12),
      "a plane between merged blocks: the upper cells, covered once (%s, %g)" % (np.unique(c), fraction.max()))

# --- Points valid through slivers only ---------------------------------------
# (a 2D square beside another, reaching 1e-5 into it: the points on that
# edge have their cells covered in a strip of about 1e-5 / 0.07 of their
# area.) With the fringe (the default) no such point stays valid: each
# takes a stable extension or is dropped, and nothing is reported. With the
# fringe off (FringeThreshold 0) they keep the values extrapolated from the
# strip, and the filter reports them.
def through_slivers(threshold):
    """The points valid through slivers only, and the warnings said."""
    f, warnings = observed_filter("WarningEvent")
    f.SetInputData(gmshmeshes.moved(gmshmeshes.surface("patch0", 0.07), 0.0, (-1.0 + 1e-5, 0.0, 0.0)))
    f.SetSourceData(gmshmeshes.with_point_field(gmshmeshes.surface("patch0", 0.05), "f", linear))
    if threshold is not None:
        f.SetFringeThreshold(threshold)
    f.Update()
    out = f.GetOutput()
    fraction = values(out, "CoveredFraction", cells=True)
    cells = out.GetPolys()
    offsets = vtk_to_numpy(cells.GetOffsetsArray())
    connectivity = vtk_to_numpy(cells.GetConnectivityArray())
    most = np.zeros(out.GetNumberOfPoints())
    for c in range(out.GetNumberOfCells()):
        ids = connectivity[offsets[c]:offsets[c + 1]]
        most[ids] = np.maximum(most[ids], fraction[c])
    mask = values(out, "vtkValidPointMask").astype(bool)
    return int(np.sum(mask & (most < 1e-3))), warnings


count, warnings = through_slivers(None)
check(count == 0 and not any("valid through slivers" in w for w in warnings),
      "the fringe (default): no point valid through slivers only (%d), none reported (%r)" % (count, warnings))
count, warnings = through_slivers(0.0)
check(count >= 10, "the fringe off: points valid through slivers made (%d)" % count)
check(any("%d Input points are valid through slivers only" % count in w for w in warnings),
      "the fringe off: points valid through slivers reported (%r)" % warnings)
f, warnings = observed_filter("WarningEvent")  # a fresh one: each warning is given once
f.SetInputData(gmshmeshes.moved(gmshmeshes.surface("patch0", 0.07), 0.0, (0.37, 0.0, 0.0)))
f.SetSourceData(gmshmeshes.with_point_field(gmshmeshes.surface("patch0", 0.05), "f", linear))
f.Update()
check(not any("slivers" in w for w in warnings), "no sliver warning without slivers (%r)" % warnings)

# --- Pairs that are not traces ------------------------------------------------
for target, source, expected in ((ball, gmshmeshes.surface("sphere", 0.2), "not to a mesh of a higher dimension"),
                                 (gmshmeshes.curve("spline", 0.1), square, "leaves the plane of the 2D Source"),
                                 (gmshmeshes.curve("circle", 0.1), gmshmeshes.surface("sphere", 0.2), "not from a curved surface")):
    f, messages = observed_filter("ErrorEvent")
    f.SetInputData(target)
    f.SetSourceData(gmshmeshes.with_point_field(source, "f", linear))
    f.Update()
    check(any(expected in m for m in messages), "error '%s': %r" % (expected, messages))
    check(f.GetOutput().GetPointData().GetArray("f") is None, "no values after the error '%s'" % expected)

finish()
