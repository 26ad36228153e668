"""The picture of docs/user-guide.md's "The fringe and beyond the Source":
a 2D pair made by Gmsh that overlaps in part (Input moved beyond the
Source, whose outline is drawn), the field sin(2x)cos(3y) projected to the
points. Left: the error |u - f| without the fringe's aggregation
(FringeThreshold 0); middle: with it (the default); right: the projected
field with Extrapolation Smooth beyond the Source.

    xvfb-run -a /usr/bin/python3 Scripts/fringe_picture.py OUT.png
(with PYTHONPATH=<build>/lib/python3/dist-packages)
"""
import sys

import numpy as np

import meshprojection
from mpsupport import gmshmeshes
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonColor import vtkNamedColors
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkFiltersCore import vtkFeatureEdges
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkDataSetMapper, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401


def field(x):
    return np.sin(2 * x[:, 0]) * np.cos(3 * x[:, 1])


target = gmshmeshes.moved(gmshmeshes.planar(0.04), translate=(0.37, 0.23, 0))
source = gmshmeshes.planar(0.052)
source.GetPointData().AddArray(numpy_to_vtk(field(vtk_to_numpy(source.GetPoints().GetData())), deep=True))
source.GetPointData().GetArray(0).SetName("f")


def project(**properties):
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    out = f.GetOutput()
    x = vtk_to_numpy(out.GetPoints().GetData())
    error = np.abs(vtk_to_numpy(out.GetPointData().GetArray("f")) - field(x))
    a = numpy_to_vtk(error, deep=True)
    a.SetName("error")
    out.GetPointData().AddArray(a)
    return out


panels = [(project(FringeThreshold=0), "error", "error without the fringe's aggregation"),
          (project(), "error", "error with it (default)"),
          (project(Extrapolation=1), "f", "field, Extrapolation Smooth")]
worst = max(np.nanmax(vtk_to_numpy(panels[0][0].GetPointData().GetArray("error"))), 1e-3)

window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(1500, 560)
outline = vtkCubeSource()
outline.SetBounds(0, 1, 0, 1, 0, 0)
edges = vtkFeatureEdges()
edges.SetInputConnection(outline.GetOutputPort())
for k, (data, name, title) in enumerate(panels):
    renderer = vtkRenderer()
    renderer.SetViewport(k / 3.0, 0, (k + 1) / 3.0, 1)
    renderer.SetBackground(1, 1, 1)
    table = vtkLookupTable()
    table.SetNanColor(0.85, 0.85, 0.85, 1)
    if name == "error":
        table.SetScaleToLog10()
        table.SetTableRange(1e-4, worst)
        table.SetHueRange(0.66, 0.0)
    else:
        table.SetTableRange(-1, 1)
        table.SetHueRange(0.66, 0.0)
    table.Build()
    data.GetPointData().SetActiveScalars(name)
    mapper = vtkDataSetMapper()
    mapper.SetInputData(data)
    mapper.SetLookupTable(table)
    mapper.UseLookupTableScalarRangeOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().EdgeVisibilityOn()
    actor.GetProperty().SetEdgeColor(0.3, 0.3, 0.3)
    actor.GetProperty().SetLineWidth(0.5)
    renderer.AddActor(actor)
    border_mapper = vtkPolyDataMapper()
    border_mapper.SetInputConnection(edges.GetOutputPort())
    border_mapper.ScalarVisibilityOff()
    border = vtkActor()
    border.SetMapper(border_mapper)
    border.GetProperty().SetColor(vtkNamedColors().GetColor3d("Black"))
    border.GetProperty().SetLineWidth(3)
    renderer.AddActor(border)
    bar = vtkScalarBarActor()
    bar.SetLookupTable(table)
    bar.SetNumberOfLabels(3)
    bar.SetWidth(0.1)
    bar.SetHeight(0.6)
    bar.SetPosition(0.86, 0.15)
    bar.GetLabelTextProperty().SetColor(0, 0, 0)
    bar.SetTitle(name)
    bar.UnconstrainedFontSizeOn()
    bar.GetTitleTextProperty().SetFontSize(16)
    bar.GetLabelTextProperty().SetFontSize(14)
    bar.GetTitleTextProperty().SetColor(0, 0, 0)
    renderer.AddActor2D(bar)
    text = vtkTextActor()
    text.SetInput(title)
    text.GetTextProperty().SetColor(0, 0, 0)
    text.GetTextProperty().SetFontSize(18)
    text.SetPosition(10, 520)
    renderer.AddActor2D(text)
    renderer.ResetCamera(-0.05, 1.6, -0.05, 1.3, 0, 0)
    renderer.GetActiveCamera().Zoom(1.35)
    window.AddRenderer(renderer)
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.Update()
writer = vtkPNGWriter()
writer.SetFileName(sys.argv[1])
writer.SetInputConnection(grab.GetOutputPort())
writer.Write()
print("wrote", sys.argv[1])
