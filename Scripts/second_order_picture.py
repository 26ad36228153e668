"""The picture of docs/method.md's "Second-order cells: point data in the
cells' own space": a curved pair made by Gmsh (unit disks, boundary mid
nodes on the circle). Left: the Source, coarse 6-node triangles, with
sin(2x) cos(3y) + xy at its nodes; middle: its projection u onto the
Input, 9-node quadrilaterals; right: |u - f| at the Input's nodes (log
scale). Cells are subdivided for display only, so their edges show curved.

    xvfb-run -a /usr/bin/python3 Scripts/second_order_picture.py docs/images/second_order.png
(with PYTHONPATH=<build>/lib/python3/dist-packages)
"""
import sys

import numpy as np

import meshprojection
from mpsupport import gmshmeshes
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkLookupTable, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkFiltersGeneral import vtkVertexGlyphFilter
from vtkmodules.vtkFiltersGeometry import vtkDataSetSurfaceFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                         vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401


def field(x):
    return np.sin(2 * x[:, 0]) * np.cos(3 * x[:, 1]) + x[:, 0] * x[:, 1]


def project(source, target):
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.Update()
    out = f.GetOutput()
    x = vtk_to_numpy(out.GetPoints().GetData())
    error = np.abs(vtk_to_numpy(out.GetPointData().GetArray("f")) - field(x))
    print("Input: %d nodes, worst nodal error %.3g, mean %.3g" % (len(x), error.max(), error.mean()))
    return out, error


def curved_edges(mesh, samples=8):
    """Polylines along the cells' quadratic edges (corner, mid node, corner),
    each edge once: VTK numbers the mid node of edge i (corners i, i + 1) n + i."""
    x = vtk_to_numpy(mesh.GetPoints().GetData())
    edges = set()
    for c in range(mesh.GetNumberOfCells()):
        ids = [mesh.GetCell(c).GetPointId(k) for k in range(mesh.GetCell(c).GetNumberOfPoints())]
        n = 3 if len(ids) == 6 else 4
        for i in range(n):
            a, b, m = ids[i], ids[(i + 1) % n], ids[n + i]
            edges.add((min(a, b), m, max(a, b)))
    s = np.linspace(0, 1, samples + 1)[:, None]
    points, lines = vtkPoints(), vtkCellArray()
    for a, m, b in edges:
        curve = x[a] * (1 - s) * (1 - 2 * s) + x[m] * 4 * s * (1 - s) + x[b] * s * (2 * s - 1)
        first = points.GetNumberOfPoints()
        for p in curve:
            points.InsertNextPoint(p[0], p[1], p[2] + 0.01)
        lines.InsertNextCell(len(curve), range(first, first + len(curve)))
    polylines = vtkPolyData()
    polylines.SetPoints(points)
    polylines.SetLines(lines)
    return polylines


def nodes(mesh, values):
    """The mesh's nodes as vertices carrying `values`."""
    glyphs = vtkVertexGlyphFilter()
    glyphs.SetInputData(mesh)
    glyphs.Update()
    glyphs.GetOutput().GetPointData().SetScalars(numpy_to_vtk(values, deep=True))
    return glyphs.GetOutput()


def actor(data, table=None, color=(0.2, 0.2, 0.2)):
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(data)
    mapper.SetScalarVisibility(table is not None)
    if table is not None:
        mapper.SetLookupTable(table)
        mapper.UseLookupTableScalarRangeOn()
    result = vtkActor()
    result.SetMapper(mapper)
    result.GetProperty().SetColor(*color)
    result.GetProperty().SetLineWidth(1.5)
    return result


def surface(mesh, name):
    """The quadratic cells subdivided twice, the field interpolated in them."""
    mesh.GetPointData().SetActiveScalars(name)
    tessellate = vtkDataSetSurfaceFilter()
    tessellate.SetInputData(mesh)
    tessellate.SetNonlinearSubdivisionLevel(2)
    tessellate.Update()
    return tessellate.GetOutput()


def colors(scalar_range, label_format, log=False):
    """A blue-to-red table over `scalar_range` and its horizontal bar."""
    table = vtkLookupTable()
    if log:
        table.SetScaleToLog10()
    table.SetTableRange(*scalar_range)
    table.SetHueRange(0.66, 0.0)
    table.Build()
    bar = vtkScalarBarActor()
    bar.SetLookupTable(table)
    bar.SetOrientationToHorizontal()
    bar.SetNumberOfLabels(4)
    bar.SetLabelFormat(label_format)
    bar.SetPosition(0.1, 0.02)
    bar.SetWidth(0.8)
    bar.SetHeight(0.12)
    bar.UnconstrainedFontSizeOn()
    text = bar.GetLabelTextProperty()
    text.SetFontSize(15)
    text.SetColor(0, 0, 0)
    text.ShadowOff()
    text.ItalicOff()
    return table, bar


def add_panel(window, k, height, title, actors, bar):
    # The title and the colour bar on a white panel, the meshes above it.
    panel = vtkRenderer()
    panel.SetViewport(k / 3.0, 0, (k + 1) / 3.0, 1)
    panel.SetBackground(1, 1, 1)
    panel.AddActor2D(bar)
    text = vtkTextActor()
    text.SetInput(title)
    text.GetTextProperty().SetColor(0, 0, 0)
    text.GetTextProperty().SetFontSize(19)
    text.SetPosition(12, height - 32)
    panel.AddActor2D(text)
    window.AddRenderer(panel)
    renderer = vtkRenderer()
    renderer.SetLayer(1)
    renderer.SetViewport(k / 3.0 + 0.005, 0.16, (k + 1) / 3.0 - 0.005, 0.91)
    for a in actors:
        renderer.AddActor(a)
    renderer.ResetCamera(-1, 1, -1, 1, 0, 0)
    renderer.GetActiveCamera().Zoom(1.35)
    window.AddRenderer(renderer)


def main(path):
    source = gmshmeshes.with_point_field(gmshmeshes.second_order("disk", 0.6), "f",
                                         lambda x, y, z: field(np.c_[x, y, z]))
    target = gmshmeshes.second_order("disk", 0.28, quads=True)
    projected, error = project(source, target)
    top = np.abs(vtk_to_numpy(source.GetPointData().GetArray("f"))).max()
    values, values_bar = colors((-top, top), "%.1f")
    errors, errors_bar = colors((error.max() * 1e-3, error.max()), "%.0e", log=True)
    dots = actor(nodes(projected, error), errors)
    dots.GetProperty().SetPointSize(9)
    dots.GetProperty().RenderPointsAsSpheresOn()
    dots.SetPosition(0, 0, 0.02)
    edges = actor(curved_edges(projected))
    panels = [("Source: 6-node triangles, f", [actor(surface(source, "f"), values), actor(curved_edges(source))],
               values_bar),
              ("Input: 9-node quads, projected u", [actor(surface(projected, "f"), values), edges], values_bar),
              ("|u - f| at the Input's nodes",
               [actor(surface(target, None), color=(0.88, 0.88, 0.88)), edges, dots], errors_bar)]
    width, height = 1500, 520
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.SetNumberOfLayers(2)
    for k, (title, actors, bar) in enumerate(panels):
        add_panel(window, k, height, title, actors, bar)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1])
