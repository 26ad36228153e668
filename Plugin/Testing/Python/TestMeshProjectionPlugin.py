"""The ParaView plugin from pvpython: load it, apply Mesh Projection to the
sample meshes, check the numbers and the properties, compare a rendered image.

    pvpython TestMeshProjectionPlugin.py PLUGIN.so TEMP_DIR
"""
import os
import sys

from paraview import servermanager  # noqa: E402
from paraview.simple import (ColorBy, CreateView, Delete, Hide, LoadPlugin, OpenDataFile,  # noqa: E402
                             Render, SaveScreenshot, Show, Slice)

from mpsupport.testing import DATA, check, compare_image, finish, integral  # noqa: E402
# Before any client-side object is wrapped: VTK's Python wrapping would
# otherwise remember the filter as its nearest wrapped base class.
from meshprojection import vtkMeshProjectionFilter  # noqa: E402

plugin, temp_dir = sys.argv[1], sys.argv[2]
os.makedirs(temp_dir, exist_ok=True)
LoadPlugin(plugin, ns=globals())
check("MeshProjection" in globals(), "the plugin defines MeshProjection")

source = OpenDataFile(os.path.join(DATA, "lshape_source.vtu"))
target = OpenDataFile(os.path.join(DATA, "lshape_target.vtu"))
source.UpdatePipeline()
projection = MeshProjection(Input=target, Source=source)  # noqa: F821

# Properties mirror the C++ setters, with the same defaults.
check(projection.SearchMethod == "Advancing Front", "SearchMethod default %r" % projection.SearchMethod)
check(projection.OutputIntersections == 0, "OutputIntersections default")
check(projection.FillWithNaN == 1 and projection.FillValue == 0, "fill defaults")
check(set(projection.ListProperties()) == {
    "Input", "Source", "FillValue", "FillWithNaN", "OutputIntersections", "SearchMethod",
    "PointDataArrays", "CellDataArrays", "PointDataTarget", "CellDataTarget", "CellDataQuantity",
    "CellDataReconstruction", "MassMatrix", "PreserveBounds", "MaximumIterations", "CacheOperator", "KeepMatrices", "PointDataArrayInfo", "CellDataArrayInfo",
    "NumberOfThreads", "Renumbering", "CurvedCellSubdivision", "SurfaceReach", "MaximumNormalAngle", "ConserveSourceIntegral",
    "Extrapolation", "FringeThreshold",
    "NormalOrientation", "TangentArrays", "DensityArray", "MassWeightedArrays",
    "CategoricalMode", "CategoricalArrays", "LabelFractions", "FillLabel"},
      "properties %r" % projection.ListProperties())
check(len(projection.TangentArrays) == 0, "TangentArrays default: none")
check(projection.DensityArray == "None" and len(projection.MassWeightedArrays) == 0,
      "mass weighting off by default (%r, %r)" % (projection.DensityArray, projection.MassWeightedArrays))
check(projection.CategoricalMode == "Integer Arrays" and list(projection.CategoricalArrays) == [] and
      projection.LabelFractions == 0 and projection.FillLabel == -1,
      "label defaults %r %r" % (projection.CategoricalMode, list(projection.CategoricalArrays)))
check(projection.SurfaceReach == 0.5 and projection.MaximumNormalAngle == 45 and
      projection.ConserveSourceIntegral == 0 and projection.NormalOrientation == "Same", "surface defaults")
check(projection.PointDataTarget == "Points" and projection.CellDataTarget == "Cells",
      "transfer defaults %r %r" % (projection.PointDataTarget, projection.CellDataTarget))
check(projection.CellDataQuantity == "Intensive" and projection.MassMatrix == "Consistent",
      "quantity and mass defaults")
check(projection.CellDataReconstruction == "Constant",
      "reconstruction default %r" % projection.CellDataReconstruction)
check(projection.PreserveBounds == 0 and projection.CacheOperator == 1 and projection.KeepMatrices == 0,
      "bounds, cache and matrices defaults")
check(projection.Extrapolation == "None" and projection.FringeThreshold == 0.25,
      "fringe defaults %r %r" % (projection.Extrapolation, projection.FringeThreshold))
check(projection.MaximumIterations == 500, "iterations default %r" % projection.MaximumIterations)
check(projection.NumberOfThreads == 0 and projection.Renumbering == "Automatic",
      "threads and renumbering defaults %r %r" % (projection.NumberOfThreads, projection.Renumbering))
check(projection.CurvedCellSubdivision == 1, "CurvedCellSubdivision default %r" % projection.CurvedCellSubdivision)
# The Source was read before the filter was made (as in the GUI): its arrays
# are listed, all selected.
check(list(projection.PointDataArrays) == ["Smooth", "Linear", "Velocity"],
      "point arrays selected by default: %r" % list(projection.PointDataArrays))
check(list(projection.CellDataArrays) == ["Region"],
      "cell arrays selected by default: %r" % list(projection.CellDataArrays))
check(projection.GetProperty("FillWithNaN").SMProperty.GetXMLLabel() == "Fill With NaN",
      "the GUI label of FillWithNaN")

projection.OutputIntersections = 1
projection.UpdatePipeline()
out = servermanager.Fetch(projection)
check(out.GetNumberOfPoints() == 1270 and out.GetNumberOfCells() == 2346, "target geometry kept")
for name in ("Smooth", "Linear", "Velocity", "TargetId", "vtkValidPointMask"):
    check(out.GetPointData().GetArray(name) is not None, "point array %s" % name)
src = servermanager.Fetch(source)
s_int, _ = integral(src, "Smooth")
t_int, _ = integral(out, "Smooth")
check(abs(s_int - t_int) <= 1e-13 * abs(s_int), "conservation %r vs %r" % (s_int, t_int))
lin = out.GetPointData().GetArray("Linear")
worst = max(abs(lin.GetValue(i) - (1 + 2 * out.GetPoint(i)[0] - 3 * out.GetPoint(i)[1]))
            for i in range(out.GetNumberOfPoints()))
check(worst < 1e-12, "linear field exact (%g)" % worst)
info = projection.GetDataInformation(1)
check(info.GetNumberOfCells() > 10000, "intersection polygons on output 1: %d" % info.GetNumberOfCells())

# Brute force through the GUI property: same result.
projection.SearchMethod = "Brute Force"
projection.UpdatePipeline()
brute = servermanager.Fetch(projection)
bs = brute.GetPointData().GetArray("Smooth")
fs = out.GetPointData().GetArray("Smooth")
diff = max(abs(bs.GetValue(i) - fs.GetValue(i)) for i in range(out.GetNumberOfPoints()))
check(diff < 1e-13, "brute force == advancing front (%g)" % diff)
projection.SearchMethod = "Advancing Front"

# Cell data goes to cells by default; the array lists select what goes.
projection.UpdatePipeline()
chosen = servermanager.Fetch(projection)
region = chosen.GetCellData().GetArray("Region")
covered = chosen.GetCellData().GetArray("vtkValidCellMask")
values = {(int(region.GetValue(i)), covered.GetValue(i)) for i in range(region.GetNumberOfTuples())} \
    if region else set()
check(region is not None and region.GetClassName() in ("vtkIntArray", "vtkTypeInt32Array") and
      {v for v, c in values if c} <= {0, 1, 2} and {v for v, c in values if not c} <= {-1},
      "the Region labels (0, 1, 2) projected to cells as labels, integers: %r %r"
      % (region.GetClassName() if region else None, sorted(values)))
projection.CategoricalMode = "Selected Arrays"
projection.UpdatePipeline()
region = servermanager.Fetch(projection).GetCellData().GetArray("Region")
check(region is not None and region.GetClassName() == "vtkDoubleArray" and
      -1e-13 <= region.GetRange()[0] and region.GetRange()[1] <= 2 + 1e-13,
      "Selected Arrays, Region not checked: projected as numbers, means in [0, 2]: %r"
      % (region.GetRange() if region else None,))
projection.CategoricalArrays = ["Region"]
projection.LabelFractions = 1
projection.UpdatePipeline()
fetched = servermanager.Fetch(projection)
region = fetched.GetCellData().GetArray("Region")
fractions = fetched.GetCellData().GetArray("Region_Fractions")
check(region is not None and region.GetClassName() in ("vtkIntArray", "vtkTypeInt32Array") and
      fractions is not None and fractions.GetNumberOfComponents() == 3 and
      [fractions.GetComponentName(k) for k in range(3)] == ["0", "1", "2"],
      "Selected Arrays, Region checked: labels with their fractions")
projection.CategoricalMode = "Integer Arrays"
projection.CategoricalArrays = []
projection.LabelFractions = 0
projection.PointDataArrays = ["Smooth"]
projection.CellDataArrays = []
projection.UpdatePipeline()
chosen = servermanager.Fetch(projection)
check(chosen.GetPointData().GetArray("Smooth") is not None and
      chosen.GetPointData().GetArray("Linear") is None and
      chosen.GetCellData().GetArray("Region") is None,
      "only the selected arrays are projected")
projection.PointDataArrays = ["Smooth", "Linear", "Velocity"]
projection.CellDataArrays = ["Region"]
projection.UpdatePipeline()
# A script that names arrays before Source has run (keyword arguments, or
# a replayed trace: the lists do not know Source's arrays yet): only those
# named are projected, the others were not wanted. Naming none leaves all.
for form in ("keywords", "trace"):
    fresh_source = OpenDataFile(os.path.join(DATA, "lshape_source.vtu"))  # not run yet
    fresh_target = OpenDataFile(os.path.join(DATA, "lshape_target.vtu"))
    if form == "keywords":
        named = MeshProjection(Input=fresh_target, Source=fresh_source,  # noqa: F821
                               PointDataArrays=["Linear"])
    else:
        named = MeshProjection(Input=fresh_target, Source=fresh_source)  # noqa: F821
        named.PointDataArrays = ["Linear"]
    named.UpdatePipeline()
    got = servermanager.Fetch(named)
    check(got.GetPointData().GetArray("Linear") is not None and
          got.GetPointData().GetArray("Smooth") is None and
          got.GetPointData().GetArray("Velocity") is None and
          got.GetCellData().GetArray("Region") is not None,
          "%s: only the named point arrays, every cell array: %r %r" % (
              form, [got.GetPointData().GetArrayName(i) for i in range(got.GetPointData().GetNumberOfArrays())],
              [got.GetCellData().GetArrayName(i) for i in range(got.GetCellData().GetNumberOfArrays())]))
    # The panel's list then shows the unnamed arrays off.
    named.UpdatePipelineInformation()
    check(list(named.PointDataArrays) == ["Linear"] and
          sorted(named.PointDataArrays.Available) == ["Linear", "Smooth", "Velocity"],
          "%s: the list %r of %r" % (form, list(named.PointDataArrays), named.PointDataArrays.Available))
    Delete(named)
    Delete(fresh_source)
    Delete(fresh_target)
# The panel's whole list (here the default, all of Source's arrays): an
# array that appears upstream later (renamed) is projected too.
from paraview.simple import Calculator  # noqa: E402
calc = Calculator(Input=source, ResultArrayName="Extra", Function="coordsX")
calc.UpdatePipeline()
later = MeshProjection(Input=target, Source=calc)  # noqa: F821
later.UpdatePipeline()
check(servermanager.Fetch(later).GetPointData().GetArray("Extra") is not None, "Extra projected")
calc.ResultArrayName = "Later"
later.UpdatePipeline()
got = servermanager.Fetch(later).GetPointData()
check(got.GetArray("Later") is not None and got.GetArray("Smooth") is not None,
      "an array appearing later is projected: %r" % [got.GetArrayName(i) for i in range(got.GetNumberOfArrays())])
Delete(later)
Delete(calc)
# Another Source (another producer): the panel's lists name its arrays only,
# not those of the Source before it; back to the first, they come back.
from paraview.simple import PassArrays  # noqa: E402
passed = PassArrays(Input=source, PointDataArrays=["Linear"], CellDataArrays=[])
passed.UpdatePipeline()
kept = servermanager.Fetch(passed)
kept_names = [sorted(d.GetArrayName(i) for i in range(d.GetNumberOfArrays()))
              for d in (kept.GetPointData(), kept.GetCellData())]
switched = MeshProjection(Input=target, Source=source)  # noqa: F821
switched.UpdatePipeline()
switched.Source = passed
switched.UpdatePipeline()
switched.UpdatePipelineInformation()
lists = [sorted(switched.PointDataArrays.Available), sorted(switched.CellDataArrays.Available)]
check(lists == kept_names and kept_names[0] == ["Linear"],
      "after the Source changed the lists are %r, the new Source has %r" % (lists, kept_names))
switched.Source = source
switched.UpdatePipeline()
switched.UpdatePipelineInformation()
check(sorted(switched.PointDataArrays.Available) == ["Linear", "Smooth", "Velocity"],
      "back to the first Source: %r" % list(switched.PointDataArrays.Available))
Delete(switched)
Delete(passed)
# The operators are kept: another transfer (lumped) only applies them.
projection.MassMatrix = "Lumped"
projection.UpdatePipeline()
check(projection.GetClientSideObject().GetOperatorReused(),
      "a lumped transfer after a consistent one reuses the operators")
lumped = servermanager.Fetch(projection).GetPointData().GetArray("Smooth")
check(min(lumped.GetRange()) >= min(src.GetPointData().GetArray("Smooth").GetRange()) - 1e-14 and
      max(lumped.GetRange()) <= max(src.GetPointData().GetArray("Smooth").GetRange()) + 1e-14,
      "the lumped transfer stays within the source's range")
projection.MassMatrix = "Consistent"

# The wrapped VTK module works in pvpython too: the same numbers as the plugin.
direct = vtkMeshProjectionFilter()
direct.SetInputData(servermanager.Fetch(target))
direct.SetSourceData(src)
direct.Update()
ds = direct.GetOutput().GetPointData().GetArray("Smooth")
diff = max(abs(ds.GetValue(i) - fs.GetValue(i)) for i in range(out.GetNumberOfPoints()))
check(diff < 1e-13, "the wrapped filter in pvpython == the plugin (%g)" % diff)

# The image: the projected field on the target, fixed camera and size.
view = CreateView("RenderView")
view.ViewSize = [400, 400]
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
display = Show(projection, view)
# Shown coloured by the first projected scalar array (neither mesh has
# active scalars: the filter makes it the output's), not in a solid colour.
check(list(display.ColorArrayName) == ["POINTS", "Smooth"], "shown coloured by %r" % (display.ColorArrayName,))
display.SetRepresentationType("Surface With Edges")
display.EdgeColor = [0.3, 0.3, 0.3]
ColorBy(display, ("POINTS", "Smooth"))
display.LookupTable.RescaleTransferFunction(-0.75, 1.3)
Render(view)
view.CameraParallelProjection = 1
view.CameraPosition = [1, 1, 10]
view.CameraFocalPoint = [1, 1, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraParallelScale = 1.05
Render(view)
png = os.path.join(temp_dir, "TestMeshProjectionPlugin.png")
SaveScreenshot(png, view, ImageResolution=[400, 400])
check(compare_image(png, "TestMeshProjectionPlugin.png", temp_dir), "image matches the baseline")
Hide(projection, view)

# 3D: tetrahedral meshes of an L-shaped prism with a hole, same filter.
source3 = OpenDataFile(os.path.join(DATA, "lshape3d_source.vtu"))
target3 = OpenDataFile(os.path.join(DATA, "lshape3d_target.vtu"))
projection3 = MeshProjection(Input=target3, Source=source3)  # noqa: F821
projection3.OutputIntersections = 1
projection3.UpdatePipeline()
out3 = servermanager.Fetch(projection3)
src3 = servermanager.Fetch(source3)
s_int, s_vol = integral(src3, "Smooth")
t_int, t_vol = integral(out3, "Smooth")
check(abs(s_int - t_int) <= 1e-13 * abs(s_int), "3D conservation %r vs %r" % (s_int, t_int))
check(abs(s_vol - 6.5) < 1e-12 and abs(t_vol - 6.5) < 1e-12, "3D volumes")
lin = out3.GetPointData().GetArray("Linear")
worst = max(abs(lin.GetValue(i) - (1 + 2 * out3.GetPoint(i)[0] - 3 * out3.GetPoint(i)[1] + 0.5 * out3.GetPoint(i)[2]))
            for i in range(out3.GetNumberOfPoints()))
check(worst < 1e-12, "3D linear field exact (%g)" % worst)
check(projection3.GetDataInformation(1).GetNumberOfCells() == 0, "no 2D polygons for 3D inputs")
check(projection3.GetDataInformation(2).GetNumberOfCells() > 60000,
      "intersection polyhedra on output 2: %d tetrahedra" % projection3.GetDataInformation(2).GetNumberOfCells())

# The image: a slice z = 0.55 through the projected 3D field.
cut = Slice(Input=projection3)
cut.SliceType.Origin = [0, 0, 0.55]
cut.SliceType.Normal = [0, 0, 1]
display = Show(cut, view)
display.SetRepresentationType("Surface With Edges")
display.EdgeColor = [0.3, 0.3, 0.3]
ColorBy(display, ("POINTS", "Smooth"))
display.LookupTable.RescaleTransferFunction(-1.6, 1.6)
view.CameraPosition = [1.5, 1.5, 10]
view.CameraFocalPoint = [1.5, 1.5, 0]
view.CameraParallelScale = 1.55
Render(view)
png = os.path.join(temp_dir, "TestMeshProjectionPlugin3D.png")
SaveScreenshot(png, view, ImageResolution=[400, 400])
check(compare_image(png, "TestMeshProjectionPlugin3D.png", temp_dir), "3D image matches the baseline")

# A surface in 3D: two Gmsh facetizations of the sphere, triangles onto
# curved quadrilaterals (Data/make_sample_data_surface.py).
Hide(cut, view)
sphere_source = OpenDataFile(os.path.join(DATA, "sphere_source.vtu"))
sphere_target = OpenDataFile(os.path.join(DATA, "sphere_target.vtu"))
sphere = MeshProjection(Input=sphere_target, Source=sphere_source)  # noqa: F821
sphere.OutputIntersections = 1
sphere.UpdatePipeline()
out_s = servermanager.Fetch(sphere)
mask = out_s.GetPointData().GetArray("vtkValidPointMask")
check(mask.GetRange() == (1.0, 1.0), "sphere: every point valid")
check(sphere.GetDataInformation(1).GetNumberOfCells() > 20000,
      "sphere: intersection polygons on output 1 (%d)" % sphere.GetDataInformation(1).GetNumberOfCells())
field = out_s.GetFieldData()
t_own = field.GetArray("TargetIntegral_Smooth").GetValue(0)
s_own = field.GetArray("SourceIntegral_Smooth").GetValue(0)
check(0 < abs(t_own - s_own) < 2e-3 * s_own, "sphere: integrals over the facetizations %r, %r" % (s_own, t_own))
lin = out_s.GetPointData().GetArray("Linear")
worst = max(abs(lin.GetValue(i) - (1 + 2 * out_s.GetPoint(i)[0] - 3 * out_s.GetPoint(i)[1] + 0.5 * out_s.GetPoint(i)[2]))
            for i in range(out_s.GetNumberOfPoints()))
check(worst < 0.02, "sphere: a linear field within O(h^2) (%g)" % worst)
display = Show(sphere, view)
display.SetRepresentationType("Surface With Edges")
display.EdgeColor = [0.3, 0.3, 0.3]
ColorBy(display, ("POINTS", "Smooth"))
display.LookupTable.RescaleTransferFunction(0.5, 3.5)
view.CameraParallelProjection = 1
view.CameraFocalPoint = [0, 0, 0]
view.CameraPosition = [0, -5.7, 8.2]
view.CameraViewUp = [0, 0.82, 0.57]
view.CameraParallelScale = 1.05
Render(view)
png = os.path.join(temp_dir, "TestMeshProjectionPluginSurface.png")
SaveScreenshot(png, view, ImageResolution=[400, 400])
check(compare_image(png, "TestMeshProjectionPluginSurface.png", temp_dir), "sphere image matches the baseline")

Delete(view)
del view
finish()
