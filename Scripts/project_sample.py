"""The main job: project a sample field from one mesh onto another with the
MeshProjection ParaView plugin, write the result and a picture, print a summary.

Run with pvpython (under xvfb-run on a machine without a display):

    pvpython Scripts/project_sample.py --plugin PATH/MeshProjection.so \
        [--source Data/lshape_source.vtu] [--target Data/lshape_target.vtu] \
        [--array Smooth] [--out-dir build/main]

Writes OUT_DIR/projected.vtu (the target mesh with every projected source
array, vtkValidPointMask and CoveredFraction), OUT_DIR/intersections.vtp (the
intersection polygons) and OUT_DIR/projection.png (the source field, left,
beside the projected field, right, in the same colours).
"""
import argparse
import os
import sys
import time

from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, GetScalarBar,
                             IntegrateVariables, LoadPlugin, OpenDataFile, OutputPort,
                             Render, SaveData, SaveScreenshot, Show, Text,
                             Transform)

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def integral(proxy, array):
    """Exact integral of a P1 point array (and the area) via IntegrateVariables."""
    integrated = servermanager.Fetch(IntegrateVariables(Input=proxy))
    value = integrated.GetPointData().GetArray(array).GetValue(0)
    area = integrated.GetCellData().GetArray("Area").GetValue(0)
    return value, area


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", required=True, help="path of MeshProjection.so")
    parser.add_argument("--source", default=os.path.join(ROOT, "Data", "lshape_source.vtu"))
    parser.add_argument("--target", default=os.path.join(ROOT, "Data", "lshape_target.vtu"))
    parser.add_argument("--array", default="Smooth", help="point array shown in the picture")
    parser.add_argument("--out-dir", default=os.path.join(ROOT, "build", "main"))
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)

    LoadPlugin(args.plugin, ns=globals())
    source = OpenDataFile(args.source)
    target = OpenDataFile(args.target)
    source.UpdatePipeline()
    target.UpdatePipeline()

    projection = MeshProjection(Input=target, Source=source)  # noqa: F821 (from the plugin)
    projection.OutputIntersections = 1
    start = time.perf_counter()
    projection.UpdatePipeline()
    seconds = time.perf_counter() - start

    projected_file = os.path.join(args.out_dir, "projected.vtu")
    polygons_file = os.path.join(args.out_dir, "intersections.vtp")
    SaveData(projected_file, proxy=OutputPort(projection, 0))
    SaveData(polygons_file, proxy=OutputPort(projection, 1))

    s_info = source.GetDataInformation()
    t_info = target.GetDataInformation()
    p_info = projection.GetDataInformation(1)
    s_int, s_area = integral(source, args.array)
    t_int, t_area = integral(projection, args.array)
    conservation = abs(t_int - s_int) / max(abs(s_int), 1e-300)
    mask = projection.PointData["vtkValidPointMask"].GetRange()

    print("MeshProjection: mortar L2 projection, advancing front (Gander & Japhet)")
    print("  source        %s: %d triangles, %d points" %
          (os.path.basename(args.source), s_info.GetNumberOfCells(), s_info.GetNumberOfPoints()))
    print("  target        %s: %d triangles, %d points" %
          (os.path.basename(args.target), t_info.GetNumberOfCells(), t_info.GetNumberOfPoints()))
    print("  intersections %d polygons" % p_info.GetNumberOfCells())
    print("  time          %.3f s (pipeline update, incl. neighbours, locator, solve)" % seconds)
    print("  area          source %.15g, target %.15g" % (s_area, t_area))
    print("  integral of %s: source %.15g, projected %.15g, relative error %.2e" %
          (args.array, s_int, t_int, conservation))
    print("  valid points  mask range %s" % (list(mask),))
    print("  wrote         %s, %s" % (projected_file, polygons_file))

    # The picture: source (left) and projection (right), same colour map.
    view = CreateView("RenderView")
    view.ViewSize = [1400, 620]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    bounds = s_info.GetBounds()
    width = bounds[1] - bounds[0]
    height = bounds[3] - bounds[2]
    shift = 1.25 * width
    moved = Transform(Input=projection)
    moved.Transform.Translate = [shift, 0, 0]
    lut = GetColorTransferFunction(args.array)
    # Fit both meshes: x over [xmin, xmin + shift + width], titles above.
    aspect = 1400.0 / 620.0
    scale = max(0.62 * height, 0.55 * (shift + width) / aspect)
    def screen_x(x):  # normalized viewport x of world x
        return 0.5 + (x - bounds[0] - 0.5 * (shift + width)) / (2 * scale * aspect)

    for proxy, label, x in ((source, "Source: %d triangles" % s_info.GetNumberOfCells(),
                             screen_x(bounds[0])),
                            (moved, "Projected onto target: %d triangles" % t_info.GetNumberOfCells(),
                             screen_x(bounds[0] + shift))):
        display = Show(proxy, view)
        display.SetRepresentationType("Surface With Edges")
        display.EdgeColor = [0.25, 0.25, 0.25]
        ColorBy(display, ("POINTS", args.array))
        title = Text(Text=label)
        title_display = Show(title, view)
        title_display.WindowLocation = "Any Location"
        title_display.Position = [max(0.01, x), 0.92]
        title_display.FontSize = 20
        title_display.Color = [0, 0, 0]
    lut.RescaleTransferFunction(*source.PointData[args.array].GetRange())
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = args.array
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    Render(view)  # the first render resets the camera: place it afterwards
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [bounds[0] + 0.5 * (shift + width), bounds[2] + 0.55 * height, 0]
    view.CameraPosition = [bounds[0] + 0.5 * (shift + width), bounds[2] + 0.55 * height, 10]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelScale = scale
    Render(view)
    picture = os.path.join(args.out_dir, "projection.png")
    SaveScreenshot(picture, view, ImageResolution=[1400, 620])
    print("  picture       %s" % picture)
    Delete(view)  # release the GL context before the interpreter exits
    del view
    return 0 if conservation < 1e-12 and mask[0] == 1 else 1


if __name__ == "__main__":
    sys.exit(main())
