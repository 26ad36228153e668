"""GUI test: the animation steps through a time series of the Source and Mesh
Projection follows. Run by the paraview client with the plugin loaded:

    paraview --plugin-search-paths=DIR --plugins=MeshProjection --script=TimeSteps.py

with MP_SOURCE_DIR (the project's root: --script runs without __file__),
MP_TEMP_DIR (scratch) and MP_RESULT (a file that receives "passed" or the
failures) in the environment. The script steps the animation scene as the VCR
buttons do, compares each step's projected Wave with a fresh projection of
that step, then ends ParaView with its status.
"""
import os
import sys
import traceback

result = os.environ.get("MP_RESULT", "TimeSteps.result")
failures = []
try:
    from mpsupport.testing import end_client_script
    import numpy as np
    import meshprojection  # noqa: F401 (the filter's wrapping, before any client-side object)
    from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, OpenDataFile,
                                 PVDReader, Render, SaveScreenshot, Show, Hide)
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from mpsupport.testing import DATA, fresh_projection, read, read_step, write_series

    temp = os.environ.get("MP_TEMP_DIR", ".")
    steps = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5]
    pvd = write_series(os.path.join(temp, "gui-series"), "src", read("lshape_source.vtu"), steps)
    source = PVDReader(FileName=pvd)
    target = OpenDataFile(os.path.join(DATA, "lshape_target.vtu"))
    view = GetActiveViewOrCreate("RenderView")
    Show(source, view)
    Show(target, view)
    import paraview.simple as simple  # MeshProjection, defined by the plugin loaded at start-up
    projection = simple.MeshProjection(Input=target, Source=source)
    display = Show(projection, view)
    Hide(source, view)
    Hide(target, view)
    ColorBy(display, ("POINTS", "Wave"))
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.GoToFirst()
    algorithm = projection.GetClientSideObject()
    seen = []
    for k, t in enumerate(steps):
        if k > 0:
            scene.GoToNext()  # the "Next Frame" button
        Render(view)
        if abs(scene.AnimationTime - t) > 1e-12:
            failures.append("animation time %r, expected %r" % (scene.AnimationTime, t))
        out = algorithm.GetOutputDataObject(0)
        wave = vtk_to_numpy(out.GetPointData().GetArray("Wave")).copy()
        fresh = fresh_projection(read("lshape_target.vtu"), read_step(pvd, k))
        expected = vtk_to_numpy(fresh.GetPointData().GetArray("Wave"))
        error = float(np.max(np.abs(wave - expected)))
        if not error < 1e-12:
            failures.append("t = %g: the shown Wave differs from that step's projection by %g"
                            % (t, error))
        if k > 0 and not algorithm.GetOperatorReused():
            failures.append("t = %g: the operator was rebuilt on fixed meshes" % t)
        seen.append(float(wave.mean()))
    if len(set(round(v, 9) for v in seen)) != len(steps):
        failures.append("the steps did not all give different fields: %r" % seen)
    display.RescaleTransferFunctionToDataRange(False, True)
    view.ResetCamera()
    SaveScreenshot(os.path.join(temp, "TimeSteps.png"), view, ImageResolution=[400, 400])
except Exception:  # a failure of the script itself
    failures.append(traceback.format_exc())
end_client_script(result, failures)  # (a NameError if mpsupport did not import: the test times out)
