"""The main job: project sample fields from one mesh onto another with the
MeshProjection ParaView plugin, write the results and pictures, print a summary.

Run with pvpython (under xvfb-run on a machine without a display):

    pvpython Scripts/project_sample.py --plugin PATH/MeshProjection.so [--out-dir build/main]
    pvpython Scripts/project_sample.py --plugin ... --source S.vtu --target T.vtu [--name NAME]

Without --source/--target it runs the four samples of Data/: the 2D pair
(lshape_*.vtu, triangles), the 3D pair (lshape3d_*.vtu, tetrahedra), the
surface pair (sphere_*.vtu: two Gmsh facetizations of a sphere, triangles
onto curved quadrilaterals) and a trace (the 3D source onto
lshape3d_sheet.vtu, a curved sheet inside its solid). For each case NAME it writes
OUT_DIR/NAME-projected.vtu (the target mesh with every projected source
array, vtkValidPointMask and CoveredFraction), OUT_DIR/NAME-intersections.vtp
or .vtu (the intersection polygons or polyhedra) and OUT_DIR/NAME.png: the
source field (left) beside the projected field (right) in the same colours;
in 3D, a slice through both; for a surface, seen from above at an angle;
for a trace, a slice of the source beside the sheet.
"""
import argparse
import math
import os
import sys
import time

from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, GetScalarBar,
                             IntegrateVariables, LoadPlugin, OpenDataFile, OutputPort, Render,
                             SaveData, SaveScreenshot, Show, Slice, Text, Threshold, Transform)
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SIZE = [1400, 620]
BAR_LEFT = 0.9  # the share of the picture's width left of the colour bar


def integral(proxy, array, association="POINTS"):
    """Exact integral of a P1 point array (or a P0 cell array; its first
    component), and the area or volume, via IntegrateVariables."""
    integrated = servermanager.Fetch(IntegrateVariables(Input=proxy))
    data = integrated.GetPointData() if association == "POINTS" else integrated.GetCellData()
    value = data.GetArray(array).GetValue(0)
    cd = integrated.GetCellData()
    measure = cd.GetArray("Volume") if cd.GetArray("Volume") and cd.GetArray("Volume").GetValue(0) else cd.GetArray("Area")
    return value, measure.GetValue(0)


def describe(proxy):
    """'N triangles' or 'N triangles and M quadrilaterals' ... from the cell types."""
    from vtkmodules.vtkCommonDataModel import vtkCellTypes
    data = servermanager.Fetch(proxy)
    counts = {}
    for c in range(data.GetNumberOfCells()):
        name = vtkCellTypes.GetClassNameFromTypeId(data.GetCellType(c))
        counts[name] = counts.get(name, 0) + 1
    words = {"vtkTriangle": "triangles", "vtkQuad": "quadrilaterals", "vtkTetra": "tetrahedra",
             "vtkPolygon": "polygons", "vtkHexahedron": "hexahedra", "vtkWedge": "wedges"}
    return " and ".join("%d %s" % (n, words.get(k, k)) for k, n in sorted(counts.items()))


def union_bounds(a, b):
    """The box (xmin, xmax, ymin, ymax, zmin, zmax) around two boxes."""
    return [min(a[k], b[k]) if k % 2 == 0 else max(a[k], b[k]) for k in range(6)]


def picture(source, projection, array, title_source, title_target, path, slice_z=None, tilt=None,
            slice_projection=True, association="POINTS", invalid=False):
    """Source (left) and projection (right), same colour map; 3D: slices z = slice_z
    (of the source only unless `slice_projection`); a surface: seen from above,
    tilted by `tilt` degrees towards -y. `invalid`: some target values are
    invalid (no Source there), drawn in yellow from the valid mask, which a line names."""
    view = CreateView("RenderView")
    view.ViewSize = SIZE
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    left, right = source, projection
    if slice_z is not None:
        left = Slice(Input=source)
        right = Slice(Input=projection) if slice_projection else projection
        for cut in (left, right) if slice_projection else (left,):
            cut.SliceType.Origin = [0, 0, slice_z]
            cut.SliceType.Normal = [0, 0, 1]
    # Both panels frame the union of the two meshes' boxes: an own pair's
    # target may reach beyond its Source.
    bounds = union_bounds(source.GetDataInformation().GetBounds(), projection.GetDataInformation().GetBounds())
    width = bounds[1] - bounds[0]
    height = bounds[3] - bounds[2]
    shift = 1.25 * width
    moved = Transform(Input=right)
    moved.Transform.Translate = [shift, 0, 0]
    aspect = float(SIZE[0]) / SIZE[1]
    # The meshes fill the left BAR_LEFT of the picture; the colour bar stands to their right.
    scale = max(0.62 * height, 0.55 * (shift + width) / (aspect * BAR_LEFT))

    def screen_x(x):  # normalized viewport x of world x
        return 0.5 * BAR_LEFT + (x - bounds[0] - 0.5 * (shift + width)) / (2 * scale * aspect)

    for proxy, label, x in ((left, title_source, screen_x(bounds[0])),
                            (moved, title_target, screen_x(bounds[0] + shift))):
        display = Show(proxy, view)
        display.SetRepresentationType("Surface With Edges")
        display.EdgeColor = [0.25, 0.25, 0.25]
        ColorBy(display, (association, array))
        title = Show(Text(Text=label), view)
        title.WindowLocation = "Any Location"
        title.Position = [max(0.01, x), 0.92]
        title.FontSize = 20
        title.Color = [0, 0, 0]
    if invalid:
        # Drawn over the projection from the mask, not from the values: a
        # label array's invalid cells hold FillLabel, not NaN.
        mask = "vtkValidPointMask" if association == "POINTS" else "vtkValidCellMask"
        holes = Threshold(Input=moved, Scalars=[association, mask], LowerThreshold=0, UpperThreshold=0.5,
                          AllScalars=0)
        hole_display = Show(holes, view)
        hole_display.SetRepresentationType("Surface With Edges")
        ColorBy(hole_display, None)
        hole_display.AmbientColor = hole_display.DiffuseColor = [1, 1, 0]
        hole_display.EdgeColor = [0.25, 0.25, 0.25]
        note = Show(Text(Text="yellow: no Source there (invalid, %s 0)" % mask), view)
        note.WindowLocation = "Any Location"
        note.Position = [max(0.01, screen_x(bounds[0] + shift)), 0.03]
        note.FontSize = 16
        note.Color = [0, 0, 0]
    lut = GetColorTransferFunction(array)
    data = source.PointData if association == "POINTS" else source.CellData
    lut.RescaleTransferFunction(*data[array].GetRange())
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = array
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    bar.WindowLocation = "Any Location"
    bar.Position = [BAR_LEFT + 0.01, 0.12]
    bar.ScalarBarLength = 0.7
    Render(view)  # the first render resets the camera: place it afterwards
    # The camera's centre is the meshes' centre moved right so that they sit in the left BAR_LEFT.
    centre = [bounds[0] + 0.5 * (shift + width) + (1 - BAR_LEFT) * scale * aspect, bounds[2] + 0.55 * height]
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = centre + [bounds[5] if slice_z is None else slice_z]
    view.CameraPosition = centre + [bounds[5] + 10]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelScale = scale
    if tilt is not None:
        # Rotated about the x axis: x stays horizontal on the screen.
        a = math.radians(tilt)
        focal = [centre[0], 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])]
        view.CameraFocalPoint = focal
        view.CameraPosition = [focal[0], focal[1] - 10 * math.sin(a), focal[2] + 10 * math.cos(a)]
        view.CameraViewUp = [0, math.cos(a), math.sin(a)]
    Render(view)
    SaveScreenshot(path, view, ImageResolution=SIZE)
    Delete(view)  # release the GL context before the interpreter exits


def first_array(data, wanted):
    """(name, "POINTS" or "CELLS") of the Source array to show: `wanted`, else
    the first point array, else the first cell array (the filter's own masks
    left out); (None, reason) when there is none."""
    own = ("vtkValidPointMask", "vtkValidCellMask", "vtkGhostType", "vtkOriginalPointIds", "vtkOriginalCellIds")
    found = []
    for association, attributes in (("POINTS", data.GetPointData()), ("CELLS", data.GetCellData())):
        for i in range(attributes.GetNumberOfArrays()):
            a = attributes.GetArray(i)
            if a is not None and a.GetName() and a.GetName() not in own:
                found.append((a.GetName(), association))
    if wanted:
        chosen = [f for f in found if f[0] == wanted]
        if not chosen:
            return None, "the Source has no array %r (it has: %s)" % (
                wanted, ", ".join(n for n, _ in found) or "none")
        return chosen[0]
    if not found:
        return None, "the Source has no point or cell array to project"
    return found[0]


def cell_dimension(data):
    """The dimension of a dataset's cells (that of its first cell; -1 without cells)."""
    return data.GetCell(0).GetCellDimension() if data.GetNumberOfCells() else -1


def valid_count(output):
    """How many target points and cells the projection reached (its masks)."""
    count = 0
    for attributes, mask in ((output.GetPointData(), "vtkValidPointMask"),
                             (output.GetCellData(), "vtkValidCellMask")):
        if attributes.GetArray(mask) is not None:
            count += int(vtk_to_numpy(attributes.GetArray(mask)).astype(bool).sum())
    return count


def own_integral(field, name):
    """The filter's integral array `name` of the output's field data (None without it)."""
    a = field.GetArray(name)
    return None if a is None else a.GetValue(0)


def bounds_text(info):
    b = info.GetBounds()
    return "[%s]" % ", ".join("%.3g..%.3g" % (b[2 * k], b[2 * k + 1]) for k in range(3))


def run_case(name, source_file, target_file, array, out_dir, sample):
    """Projects Source onto Target and writes NAME-projected.vtu, the
    pieces and NAME.png; prints a summary. `array` is the Source array shown
    (None: the first); a sample also checks its conservation. False, with one
    line said, when there is nothing to project (no array, no overlap)."""
    source = OpenDataFile(source_file)
    target = OpenDataFile(target_file)
    source.UpdatePipeline()
    target.UpdatePipeline()
    source_data = servermanager.Fetch(source)
    array, association = first_array(source_data, array)
    if array is None:
        print("%s: nothing projected: %s (%s)." % (name, association, source_file))
        return False

    projection = MeshProjection(Input=target, Source=source)  # noqa: F821 (from the plugin)
    projection.OutputIntersections = 1
    start = time.perf_counter()
    projection.UpdatePipeline()
    seconds = time.perf_counter() - start

    s_info = source.GetDataInformation()
    t_info = target.GetDataInformation()
    output = servermanager.Fetch(projection)
    if valid_count(output) == 0:
        print("%s: nothing projected: Source %s %s and Target %s %s do not overlap." %
              (name, os.path.basename(source_file), bounds_text(s_info),
               os.path.basename(target_file), bounds_text(t_info)))
        return False
    t_dim = cell_dimension(servermanager.Fetch(target))
    three_d = t_dim == 3
    pieces_port = 2 if three_d else 1
    # A trace: a 3D source, a target of lower dimension inside it.
    trace = not three_d and cell_dimension(source_data) == 3
    # A surface in 3D: 2D cells whose points span three dimensions.
    extent = [b - a for a, b in zip(t_info.GetBounds()[::2], t_info.GetBounds()[1::2])]
    surface = not three_d and not trace and min(extent) > 1e-6 * max(extent)
    s_cells, t_cells = describe(source), describe(target)
    projected_file = os.path.join(out_dir, name + "-projected.vtu")
    pieces_file = os.path.join(out_dir, name + ("-intersections.vtu" if three_d else "-intersections.vtp"))
    # Inline binary, not appended: VTK 9.2 cannot read appended data back with
    # Debian 12's patched expat.
    SaveData(projected_file, proxy=OutputPort(projection, 0), DataMode="Binary")
    SaveData(pieces_file, proxy=OutputPort(projection, pieces_port), DataMode="Binary")

    s_int, s_measure = integral(source, array, association)
    t_int, t_measure = integral(projection, array, association)
    conservation = abs(t_int - s_int) / max(abs(s_int), 1e-300)
    # The filter's own integrals (field data): over the target's covered
    # part, the projection's (that of the projected source field), and over
    # the part of the source it covers, the source field's (Conservation.h:
    # point data weighed by the covered measure of the cells around each
    # point). For a surface they differ as the two facetizations' areas do
    # (ConserveSourceIntegral would equalize them).
    field = output.GetFieldData()
    suffix = " (cell data)" if association == "CELLS" else ""
    # None for an array projected as labels (integer arrays): labels are not integrated.
    s_own = None if trace else own_integral(field, "SourceIntegral_" + array + suffix)
    t_own = own_integral(field, "TargetIntegral_" + array + suffix)
    if trace and sample:
        # The linear field, which a trace reproduces exactly.
        x = vtk_to_numpy(output.GetPoints().GetData())
        linear_error = float(abs(vtk_to_numpy(output.GetPointData().GetArray("Linear")) -
                                 (1 + 2 * x[:, 0] - 3 * x[:, 1] + 0.5 * x[:, 2])).max())
    mask = projection.PointData["vtkValidPointMask"].GetRange()
    pieces = projection.GetDataInformation(pieces_port).GetNumberOfCells()

    print("%s: mortar L2 projection, advancing front (Gander & Japhet)" % name)
    print("  source        %s: %s, %d points" %
          (os.path.basename(source_file), s_cells, s_info.GetNumberOfPoints()))
    print("  target        %s: %s, %d points" %
          (os.path.basename(target_file), t_cells, t_info.GetNumberOfPoints()))
    if three_d:
        # Port 2 holds the polyhedra as tetrahedra: one polyhedron per (source, target) pair.
        tets = servermanager.Fetch(projection, idx=2).GetCellData()
        pairs = set(zip(vtk_to_numpy(tets.GetArray("SourceCellId")).tolist(),
                        vtk_to_numpy(tets.GetArray("TargetCellId")).tolist()))
        print("  intersections %d polyhedra (as %d tetrahedra)" % (len(pairs), pieces))
    else:
        print("  intersections %d polygons" % pieces)
    print("  time          %.3f s (pipeline update: neighbours, locator, search, assembly, solve)" % seconds)
    if trace:
        print("  volume, area  source %.15g, target %.15g" % (s_measure, t_measure))
    else:
        print("  %s        source %.15g, target %.15g" % ("volume" if three_d else "area  ", s_measure, t_measure))
    if not sample:
        arrays = [a for a in ([output.GetPointData().GetArrayName(i)
                               for i in range(output.GetPointData().GetNumberOfArrays())] +
                              [output.GetCellData().GetArrayName(i)
                               for i in range(output.GetCellData().GetNumberOfArrays())])
                  if not a.startswith("vtk") and a != "CoveredFraction"]
        print("  projected     %s" % ", ".join(arrays))
    if t_own is None:
        print("  integral of %s: none (projected as labels: each value one of the Source's, not integrated)" %
              array)
    elif trace:
        print("  integral of %s over the sheet %.15g (the projected volume field's)" % (array, t_own))
        if sample:
            print("  Linear        exact on the sheet to %.1e (a trace of a linear field is exact)" % linear_error)
    elif surface or not sample:
        print("  integral of %s (SourceIntegral_, TargetIntegral_): source %.15g, target %.15g, relative "
              "difference %.2e" % (array, s_own, t_own, abs(t_own - s_own) / max(abs(s_own), 1e-300)))
    else:
        print("  integral of %s: source %.15g, projected %.15g, relative error %.2e" %
              (array, s_int, t_int, conservation))
    print("  valid points  mask range %s" % (list(mask),))
    png = os.path.join(out_dir, name + ".png")
    z = None
    if three_d or trace:
        bounds = s_info.GetBounds()
        z = bounds[4] + (0.5 if trace else 0.55) * (bounds[5] - bounds[4])
    picture(source, projection, array,
            "Source: %s%s" % (s_cells, "" if z is None else ", slice z = %.2f" % z),
            ("Projected onto a sheet inside it: %s" if trace else "Projected onto target: %s") % t_cells, png, z,
            tilt=35 if surface or trace else None,
            slice_projection=not trace, association=association,
            invalid=(projection.CellData["vtkValidCellMask"].GetRange()[0] if association == "CELLS" else mask[0]) == 0)
    print("  wrote         %s, %s, %s" % (projected_file, pieces_file, png))
    if not sample:
        return True
    if trace:
        return linear_error < 1e-10 and mask[0] == 1
    if surface:
        return abs(t_own - s_own) < 1e-2 * abs(s_own) and mask[0] == 1
    return conservation < 1e-12 and mask[0] == 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", required=True, help="path of MeshProjection.so")
    parser.add_argument("--source", help="source mesh (.vtu); default: the samples in Data/")
    parser.add_argument("--target", help="target mesh (.vtu)")
    parser.add_argument("--name", default="custom", help="output name for --source/--target")
    parser.add_argument("--array", help="Source array shown in the picture (default: Smooth for the samples, "
                        "the first point array, else cell array, for --source/--target)")
    parser.add_argument("--out-dir", default=os.path.join(ROOT, "build", "main"))
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    LoadPlugin(args.plugin, ns=globals())

    data = os.path.join(ROOT, "Data")
    if args.source or args.target:
        if not (args.source and args.target):
            parser.error("--source and --target go together")
        cases = [(args.name, args.source, args.target, False)]
    else:
        cases = [("lshape2d", os.path.join(data, "lshape_source.vtu"), os.path.join(data, "lshape_target.vtu")),
                 ("lshape3d", os.path.join(data, "lshape3d_source.vtu"),
                  os.path.join(data, "lshape3d_target.vtu")),
                 ("sphere", os.path.join(data, "sphere_source.vtu"), os.path.join(data, "sphere_target.vtu")),
                 ("trace", os.path.join(data, "lshape3d_source.vtu"), os.path.join(data, "lshape3d_sheet.vtu"))]
        cases = [case + (True,) for case in cases]
    ok = all([run_case(name, s, t, args.array or ("Smooth" if sample else None), args.out_dir, sample)
              for name, s, t, sample in cases])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
