"""GUI smoke test: corrupt files and NaN values in the paraview client. Run as

    paraview --dr --plugin-search-paths=DIR --plugins=MeshProjection --script=BadInput.py

with MP_SOURCE_DIR (the project's root), MP_TEMP_DIR (scratch) and MP_RESULT
(a file that receives PASS, or FAIL and the failures) in the environment.

The script writes three .vtu files made from the L-shape samples, as a
buggy writer would: a Source and an Input whose connectivity names point
10^12, and a Source with NaN in its Smooth array. It opens them as File >
Open does and applies Mesh Projection to each pair, listening to ParaView's
own output window (the Output Messages panel): each corrupt file must give
an error there that names the cell and the point, the application must stay
alive, and the output must be Input as it came (no projected arrays). The
NaN Source must give a warning there and a projection whose Smooth is finite
wherever it is valid. Finally a good pair is projected, to show the session
still works. (The corrupt Input itself is never shown: VTK's own geometry
filter would read outside its arrays to draw it.) It then ends ParaView with
its status.
"""
import os
import sys
import traceback

result = os.environ.get("MP_RESULT", "BadInput.result")
failures = []
try:
    from mpsupport.testing import end_client_script
    import numpy as np
    import meshprojection  # noqa: F401 (the filter's wrapping, before any client-side object)
    from paraview import servermanager
    from paraview.simple import (ColorBy, Delete, GetActiveViewOrCreate, Hide, OpenDataFile,
                                 Render, SaveScreenshot, Show)
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonCore import VTK_STRING, vtkOutputWindow
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    from mpsupport.testing import read

    temp = os.environ.get("MP_TEMP_DIR", ".")
    os.makedirs(temp, exist_ok=True)

    # What reaches ParaView's output window (the Output Messages panel).
    messages = {"error": [], "warning": []}
    window = vtkOutputWindow.GetInstance()

    def listener(kind):
        @calldata_type(VTK_STRING)
        def heard(caller, event, text):
            messages[kind].append(text)
        return heard

    window.AddObserver("ErrorEvent", listener("error"))
    window.AddObserver("WarningEvent", listener("warning"))

    def write(grid, name):
        path = os.path.join(temp, name)
        writer = vtkXMLUnstructuredGridWriter()
        writer.SetInputData(grid)
        writer.SetFileName(path)
        writer.SetDataModeToBinary()  # inline: Debian's expat cannot read appended data
        writer.Write()
        return path

    def corrupt(grid, cell):
        """The grid with its cell's second point id replaced by 10^12."""
        connectivity = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
        offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray())
        connectivity[offsets[cell] + 1] = 10 ** 12
        grid.GetCells().GetConnectivityArray().Modified()
        return grid

    target_file = os.path.join(os.environ.get("MP_SOURCE_DIR", "."), "Data", "lshape_target.vtu")
    source_file = os.path.join(os.environ.get("MP_SOURCE_DIR", "."), "Data", "lshape_source.vtu")
    bad_source = write(corrupt(read(source_file), 17), "bad-source.vtu")
    bad_target = write(corrupt(read(target_file), 5), "bad-target.vtu")
    nan_grid = read(source_file)
    smooth = vtk_to_numpy(nan_grid.GetPointData().GetArray("Smooth")).copy()
    x = vtk_to_numpy(nan_grid.GetPoints().GetData())
    smooth[np.hypot(x[:, 0] - 0.5, x[:, 1] - 0.5) < 0.2] = np.nan
    spoiled = numpy_to_vtk(smooth, deep=1)
    spoiled.SetName("Smooth")
    nan_grid.GetPointData().RemoveArray("Smooth")
    nan_grid.GetPointData().AddArray(spoiled)
    nan_source = write(nan_grid, "nan-source.vtu")

    view = GetActiveViewOrCreate("RenderView")
    import paraview.simple as simple  # MeshProjection, defined by the plugin loaded at start-up

    def project(target_path, source_path, show):
        for kind in messages:
            del messages[kind][:]
        target = OpenDataFile(target_path)
        source = OpenDataFile(source_path)
        projection = simple.MeshProjection(Input=target, Source=source)
        projection.UpdatePipeline()
        out = servermanager.Fetch(projection)
        if show:
            display = Show(projection, view)
            ColorBy(display, ("POINTS", "Smooth"))
            display.RescaleTransferFunctionToDataRange(False, True)
            view.ResetCamera()
            Render(view)
        return projection, out

    # 1. Corrupt Source, then corrupt Input: an error in the window, Input passed through.
    good_points = read(target_file).GetNumberOfPoints()
    for what, target_path, source_path, cell, show in (
            ("Source", target_file, bad_source, 17, True),
            ("Input", bad_target, source_file, 5, False)):
        projection, out = project(target_path, source_path, show)
        text = " ".join(messages["error"])
        expected = "%s: cell %d refers to point 1000000000000" % (what, cell)
        if expected not in text:
            failures.append("corrupt %s: the output window did not say %r; it said %r"
                            % (what, expected, text))
        if "corrupt" not in text:
            failures.append("corrupt %s: the error does not say the dataset is corrupt" % what)
        if out is None or out.GetNumberOfPoints() != good_points:
            failures.append("corrupt %s: the output is not Input's %d points" % (what, good_points))
        elif out.GetPointData().GetArray("vtkValidPointMask") is not None:
            failures.append("corrupt %s: the output has projected arrays" % what)
        if show:
            SaveScreenshot(os.path.join(temp, "BadInput-source.png"), view, ImageResolution=[400, 400])
            Hide(projection, view)

    # 2. NaN in the Source's Smooth: a warning, a finite field where valid.
    projection, out = project(target_file, nan_source, True)
    warned = " ".join(messages["warning"])
    if "'Smooth' has" not in warned or "NaN or infinite values" not in warned:
        failures.append("NaN Source: no warning naming Smooth in the output window: %r" % warned)
    pd = out.GetPointData()
    mask = pd.GetArray("vtkValidPointMask_Smooth") or pd.GetArray("vtkValidPointMask")
    if pd.GetArray("Smooth") is None or mask is None:
        failures.append("NaN Source: no Smooth or mask in the output")
    else:
        valid = vtk_to_numpy(mask) != 0
        values = vtk_to_numpy(pd.GetArray("Smooth"))
        if not np.all(np.isfinite(values[valid])):
            failures.append("NaN Source: valid points with non-finite Smooth")
        if not (0 < np.count_nonzero(~valid) < 0.2 * len(valid)):
            failures.append("NaN Source: %d of %d points invalid (expected a few)"
                            % (np.count_nonzero(~valid), len(valid)))
    SaveScreenshot(os.path.join(temp, "BadInput-nan.png"), view, ImageResolution=[400, 400])

    # 3. The session still works: a good pair.
    projection, out = project(target_file, source_file, True)
    if messages["error"] or out.GetPointData().GetArray("vtkValidPointMask") is None:
        failures.append("good pair after the bad ones: errors %r" % messages["error"])
except Exception:  # a failure of the script itself
    failures.append(traceback.format_exc())
end_client_script(result, failures)  # (a NameError if mpsupport did not import: the test times out)
