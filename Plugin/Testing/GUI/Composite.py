"""GUI test: a multiblock Input, projected block by block. Run by the paraview
client with the plugin loaded:

    paraview --dr --plugin-search-paths=DIR --plugins=MeshProjection --script=Composite.py

with MP_SOURCE_DIR (the project's root: --script runs without __file__),
MP_TEMP_DIR (scratch) and MP_RESULT (a file that receives PASS, or FAIL and
the failures) in the environment. The script writes a .vtm of three blocks
inside [0,1]^3 (hexes_box cut at x = 0.5 into two blocks, and mixed_box), without
their own Linear array, opens it and tets_box.vtu as the File > Open dialog
does, applies Mesh Projection (Input = the .vtm, Source = tets_box), shows the
output coloured by the projected Linear, and checks the fetched output: a
multiblock of the same blocks, each with vtkValidPointMask, and Linear =
1 + 2x - 3y + 0.5z at its valid points (linear fields are exact). It then ends
ParaView with its status.
"""
import os
import sys
import traceback

result = os.environ.get("MP_RESULT", "Composite.result")
failures = []
try:
    from mpsupport.testing import end_client_script
    import numpy as np
    import meshprojection  # noqa: F401 (the filter's wrapping, before any client-side object)
    from paraview import servermanager
    from paraview.simple import (ColorBy, GetActiveViewOrCreate, Hide, OpenDataFile, Render,
                                 SaveScreenshot, Show)
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkMultiBlockDataSet
    from mpsupport.testing import GMSH as gmsh, cut, read, write_multiblock

    temp = os.environ.get("MP_TEMP_DIR", ".")
    os.makedirs(temp, exist_ok=True)

    def without_linear(grid):
        """The grid without its own Linear: the output's Linear must come from Source."""
        grid.GetPointData().RemoveArray("Linear")
        return grid

    hexes = read(os.path.join(gmsh, "hexes_box.vtu"))
    blocks = [("hexes x < 0.5", without_linear(cut(hexes, lambda c: c[:, 0] < 0.5))),
              ("hexes x >= 0.5", without_linear(cut(hexes, lambda c: c[:, 0] >= 0.5))),
              ("mixed box", without_linear(read(os.path.join(gmsh, "mixed_box.vtu"))))]
    for name, grid in blocks:
        if grid.GetNumberOfCells() == 0:
            failures.append("block %r of the written Input is empty" % name)
    vtm = os.path.join(temp, "composite-input.vtm")
    if not write_multiblock(vtm, blocks):
        failures.append("could not write %s" % vtm)

    target = OpenDataFile(vtm)
    source = OpenDataFile(os.path.join(gmsh, "tets_box.vtu"))
    view = GetActiveViewOrCreate("RenderView")
    Show(target, view)
    Show(source, view)
    import paraview.simple as simple  # MeshProjection, defined by the plugin loaded at start-up
    projection = simple.MeshProjection(Input=target, Source=source)
    display = Show(projection, view)
    Hide(target, view)
    Hide(source, view)
    ColorBy(display, ("POINTS", "Linear"))
    display.RescaleTransferFunctionToDataRange(False, True)
    view.ResetCamera()
    Render(view)

    out = servermanager.Fetch(projection)
    if not isinstance(out, vtkMultiBlockDataSet):
        failures.append("the output is a %s, not a vtkMultiBlockDataSet" % out.GetClassName())
    elif out.GetNumberOfBlocks() != len(blocks):
        failures.append("the output has %d blocks, the Input %d"
                        % (out.GetNumberOfBlocks(), len(blocks)))
    else:
        for i, (name, grid) in enumerate(blocks):
            leaf = out.GetBlock(i)
            if leaf is None or leaf.GetNumberOfCells() != grid.GetNumberOfCells():
                failures.append("block %d (%s): %s instead of the Input's %d cells"
                                % (i, name, "missing" if leaf is None
                                   else "%d cells" % leaf.GetNumberOfCells(),
                                   grid.GetNumberOfCells()))
                continue
            meta = out.GetMetaData(i) if out.HasMetaData(i) else None
            shown = meta.Get(vtkCompositeDataSet.NAME()) if meta is not None else None
            if shown != name:
                failures.append("block %d is named %r, the Input's %r" % (i, shown, name))
            pd = leaf.GetPointData()
            if pd.GetArray("vtkValidPointMask") is None or pd.GetArray("Linear") is None:
                failures.append("block %d (%s): point arrays %r, no vtkValidPointMask or Linear"
                                % (i, name, [pd.GetArrayName(k)
                                             for k in range(pd.GetNumberOfArrays())]))
                continue
            if leaf.GetCellData().GetArray("CellIndex") is None:
                failures.append("block %d (%s): the Source's cell array CellIndex is missing"
                                % (i, name))
            valid = vtk_to_numpy(pd.GetArray("vtkValidPointMask")) != 0
            if valid.sum() < 0.9 * len(valid):  # Source and blocks all fill [0,1]^3
                failures.append("block %d (%s): only %d of %d points valid"
                                % (i, name, valid.sum(), len(valid)))
            x = vtk_to_numpy(leaf.GetPoints().GetData())
            exact = 1 + 2 * x[:, 0] - 3 * x[:, 1] + 0.5 * x[:, 2]
            linear = vtk_to_numpy(pd.GetArray("Linear"))
            error = float(np.max(np.abs(linear[valid] - exact[valid]), initial=0.0))
            if not error < 1e-11:
                failures.append("block %d (%s): Linear differs from 1+2x-3y+0.5z by %g"
                                % (i, name, error))
    SaveScreenshot(os.path.join(temp, "Composite.png"), view, ImageResolution=[400, 400])
except Exception:  # a failure of the script itself
    failures.append(traceback.format_exc())
end_client_script(result, failures)  # (a NameError if mpsupport did not import: the test times out)
