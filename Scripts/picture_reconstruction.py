"""The user guide's picture of CellDataReconstruction: cell data on a coarse
mesh (left) projected onto a fine one under each mode (Constant, Linear
limited, Linear), in the same colours; the field is smooth with a front.

    xvfb-run -a pvpython Scripts/picture_reconstruction.py --plugin PATH/MeshProjection.so \\
        [--out docs/images/reconstruction.png]
"""
import argparse
import os
import tempfile

import numpy as np
from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, LoadPlugin,
                             PVTrivialProducer, Render, SaveScreenshot, Show, Text)
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_TRIANGLE, vtkImageData
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

from mpsupport import meshes

PANEL = [480, 520]


def field(x):
    front = np.tanh((x[:, 0] + 0.6 * x[:, 1] - 0.85) / 0.06)
    return 0.6 * front + 0.4 * np.sin(5 * x[:, 1]) * np.cos(3 * x[:, 0])


def source_mesh():
    g = meshes.grid(*meshes.triangles(10, (0, 0, 0), (1, 1, 0), 3), VTK_TRIANGLE)
    x = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 3)
    a = numpy_to_vtk(field(x[conn].mean(axis=1)), deep=True)
    a.SetName("u")
    g.GetCellData().AddArray(a)
    return g


def panel(producer, title, path, array_range):
    view = CreateView("RenderView")
    view.ViewSize = PANEL
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    display = Show(producer, view)
    ColorBy(display, ("CELLS", "u"))
    lut = GetColorTransferFunction("u")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(*array_range)
    label = Text(Text=title)
    label_display = Show(label, view)
    label_display.Color = [0, 0, 0]
    label_display.FontSize = 22
    label_display.WindowLocation = "Upper Center"
    Render(view)  # (the first render resets the camera: the camera after it)
    view.CameraPosition = [0.5, 0.5, 3]
    view.CameraFocalPoint = [0.5, 0.5, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.62
    Render(view)
    SaveScreenshot(path, view, ImageResolution=PANEL)
    Delete(view)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--out", default=os.path.join("docs", "images", "reconstruction.png"))
    args = parser.parse_args()
    LoadPlugin(args.plugin, ns=globals())
    source = source_mesh()
    target = meshes.grid(*meshes.triangles(90, (0, 0, 0), (1, 1, 0), 4), VTK_TRIANGLE)
    u = vtk_to_numpy(source.GetCellData().GetArray("u"))
    array_range = (float(u.min()), float(u.max()))
    source_producer = PVTrivialProducer()
    source_producer.GetClientSideObject().SetOutput(source)
    target_producer = PVTrivialProducer()
    target_producer.GetClientSideObject().SetOutput(target)
    with tempfile.TemporaryDirectory() as tmp:
        paths = [os.path.join(tmp, "0.png")]
        panel(source_producer, "Source: %d cells" % source.GetNumberOfCells(), paths[0], array_range)
        for mode, text in ((0, "Constant"), (1, "Linear, limited"), (2, "Linear")):
            projection = MeshProjection(Input=target_producer, Source=source_producer)  # noqa: F821
            projection.CellDataReconstruction = mode
            paths.append(os.path.join(tmp, "%d.png" % (mode + 1)))
            panel(projection, text, paths[-1], array_range)
        # The panels side by side.
        rows = []
        for path in paths:
            reader = vtkPNGReader()
            reader.SetFileName(path)
            reader.Update()
            image = reader.GetOutput()
            w, h, _ = image.GetDimensions()
            pixels = vtk_to_numpy(image.GetPointData().GetScalars())
            rows.append(pixels.reshape(h, w, -1))
        joined = np.ascontiguousarray(np.concatenate(rows, axis=1))
        out = vtkImageData()
        out.SetDimensions(joined.shape[1], joined.shape[0], 1)
        scalars = numpy_to_vtk(joined.reshape(-1, joined.shape[2]), deep=True)
        out.GetPointData().SetScalars(scalars)
        os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
        writer = vtkPNGWriter()
        writer.SetFileName(args.out)
        writer.SetInputData(out)
        writer.Write()
    print("wrote %s" % args.out)


if __name__ == "__main__":
    main()
