"""The picture of docs/user-guide.md's "The fringe and beyond the Source":
a pair made by Gmsh that overlaps in part (a square of triangles, Input,
half beyond a disk, the Source, whose boundary is drawn), the field
sin(2x) cos(3y) projected to the points. Left: the error |u - f| without
the fringe's aggregation (FringeThreshold 0); middle: with it (the
default), on the same scale; right: the projected field with Extrapolation
Smooth beyond the Source.

    xvfb-run -a /usr/bin/python3 Scripts/fringe_picture.py docs/images/fringe.png
(with PYTHONPATH=<build>/lib/python3/dist-packages)
"""
import sys

import numpy as np

import meshprojection
from mpsupport import gmshmeshes
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkFiltersCore import vtkFeatureEdges
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkDataSetMapper, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401


def field(x):
    return np.sin(2 * x[:, 0]) * np.cos(3 * x[:, 1])


target = gmshmeshes.moved(gmshmeshes.planar(0.06), translate=(0.25, -0.45, 0))
source = gmshmeshes.with_point_field(gmshmeshes.surface("disk", 0.075), "f", lambda x, y, z: field(np.c_[x, y, z]))


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


before, after = project(FringeThreshold=0), project()
worst = np.nanmax(vtk_to_numpy(before.GetPointData().GetArray("error")))
panels = [(before, "error", (0, worst), "error, FringeThreshold 0 (plain L2)"),
          (after, "error", (0, worst), "error, FringeThreshold 0.25 (default)"),
          (project(Extrapolation=1), "f", (-1, 1), "field, Extrapolation Smooth")]
for data, name, _, title in panels[:2]:
    e = vtk_to_numpy(data.GetPointData().GetArray("error"))
    print("%s: worst error %.3g" % (title, np.nanmax(e)))

boundary = vtkFeatureEdges()
boundary.SetInputData(source)
boundary.BoundaryEdgesOn()
boundary.FeatureEdgesOff()
boundary.ManifoldEdgesOff()
boundary.NonManifoldEdgesOff()

width, height = 1500, 600
window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(width, height)
window.SetNumberOfLayers(2)
for k, (data, name, scalar_range, title) in enumerate(panels):
    # The title and the colour bar on a white panel; the meshes above it,
    # in the band between (the Source's boundary clipped to it).
    panel = vtkRenderer()
    panel.SetViewport(k / 3.0, 0, (k + 1) / 3.0, 1)
    panel.SetBackground(1, 1, 1)
    window.AddRenderer(panel)
    renderer = vtkRenderer()
    renderer.SetLayer(1)
    renderer.SetViewport(k / 3.0 + 0.005, 0.16, (k + 1) / 3.0 - 0.005, 0.93)
    table = vtkLookupTable()
    table.SetNanColor(0.8, 0.8, 0.8, 1)
    table.SetTableRange(*scalar_range)
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
    actor.GetProperty().SetEdgeColor(0.35, 0.35, 0.35)
    renderer.AddActor(actor)
    edges = vtkPolyDataMapper()
    edges.SetInputConnection(boundary.GetOutputPort())
    edges.ScalarVisibilityOff()
    outline = vtkActor()
    outline.SetMapper(edges)
    outline.GetProperty().SetColor(0, 0, 0)
    outline.GetProperty().SetLineWidth(3)
    outline.SetPosition(0, 0, 0.01)
    renderer.AddActor(outline)
    bar = vtkScalarBarActor()
    bar.SetLookupTable(table)
    bar.SetOrientationToHorizontal()
    bar.SetNumberOfLabels(3)
    bar.SetLabelFormat("%.2g")
    bar.SetPosition(0.1, 0.02)
    bar.SetWidth(0.8)
    bar.SetHeight(0.12)
    bar.UnconstrainedFontSizeOn()
    bar.GetLabelTextProperty().SetFontSize(15)
    bar.GetLabelTextProperty().SetColor(0, 0, 0)
    bar.GetLabelTextProperty().ShadowOff()
    bar.GetLabelTextProperty().ItalicOff()
    panel.AddActor2D(bar)
    text = vtkTextActor()
    text.SetInput(title)
    text.GetTextProperty().SetColor(0, 0, 0)
    text.GetTextProperty().SetFontSize(19)
    text.SetPosition(12, height - 32)
    panel.AddActor2D(text)
    renderer.ResetCamera(0.25, 1.25, -0.45, 0.55, 0, 0)
    renderer.GetActiveCamera().Zoom(1.45)
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
