"""Time series from pvpython: a PVD series of the Source on a fixed mesh is
followed step by step with the operator reused; a moving Source and a moving
target (Input) rebuild it; every step equals a fresh projection of that
step's meshes, and conserves.

    pvpython TestMeshProjectionTime.py PLUGIN.so TEMP_DIR
"""
import os
import sys

import numpy as np  # noqa: E402
from paraview.simple import LoadPlugin, OpenDataFile, PVDReader  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as SDDP  # noqa: E402

import meshprojection  # noqa: E402,F401  (before any client-side object is wrapped)
from mpsupport.testing import (DATA, cell_measures, check, finish, fresh_projection, integral, read,  # noqa: E402
                               read_step, write_series)

plugin, temp_dir = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, ns=globals())
STEPS = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5]


def advertised(proxy):
    proxy.UpdatePipelineInformation()
    info = proxy.GetClientSideObject().GetOutputInformation(0)
    return [info.Get(SDDP.TIME_STEPS(), i) for i in range(info.Length(SDDP.TIME_STEPS()))]


def follow(name, target_proxy, source_proxy, target_pvd, source_pvd, expect_reuse):
    projection = MeshProjection(Input=target_proxy, Source=source_proxy)  # noqa: F821
    steps = advertised(projection)
    check(steps == STEPS, "%s: the output advertises the time steps %r" % (name, steps))
    algorithm = projection.GetClientSideObject()
    previous = None
    for k, t in enumerate(STEPS):
        projection.UpdatePipeline(t)
        out = algorithm.GetOutputDataObject(0)
        wave = vtk_to_numpy(out.GetPointData().GetArray("Wave")).copy()
        heat = vtk_to_numpy(out.GetCellData().GetArray("Heat")).copy()
        target_grid = read_step(target_pvd, k) if target_pvd else read("lshape_target.vtu")
        source_grid = read_step(source_pvd, k)
        ref = fresh_projection(target_grid, source_grid)
        expected = vtk_to_numpy(ref.GetPointData().GetArray("Wave"))
        same_mask = np.array_equal(np.isnan(wave), np.isnan(expected))
        error = np.nanmax(np.abs(wave - expected)) if same_mask else np.inf
        # Moved meshes cover each other partly: slivers make M_tt ill
        # conditioned there, and the solves stop at a relative residual.
        check(error < (1e-12 if expect_reuse else 1e-10), "%s, t = %g: Wave equals a fresh projection of that step (%.3g)"
              % (name, t, error))

        check(np.array_equal(vtk_to_numpy(out.GetPoints().GetData()),
                             vtk_to_numpy(target_grid.GetPoints().GetData())),
              "%s, t = %g: the output has that step's target points" % (name, t))
        if not expect_reuse:  # moved meshes cover different domains
            previous = wave
            check(not algorithm.GetOperatorReused(), "%s, t = %g: operator rebuilt" % (name, t))
            continue
        s_int, _ = integral(source_grid, "Wave")
        t_int, _ = integral(out, "Wave")
        check(abs(s_int - t_int) <= 1e-12 * max(1.0, abs(s_int)),
              "%s, t = %g: Wave conserved (%r vs %r)" % (name, t, s_int, t_int))
        heat_s = vtk_to_numpy(source_grid.GetCellData().GetArray("Heat"))
        h_int = float(np.sum(cell_measures(source_grid) * heat_s))
        h_out = float(np.sum(cell_measures(out) * heat))
        check(abs(h_int - h_out) <= 1e-12 * abs(h_int),
              "%s, t = %g: cell data Heat conserved (%r vs %r)" % (name, t, h_int, h_out))
        if previous is not None:
            check(np.max(np.abs(wave - previous)) > 0.1, "%s, t = %g: the values changed" % (name, t))
        reused = algorithm.GetOperatorReused()
        check(reused == (expect_reuse and k > 0),
              "%s, t = %g: operator reused = %r" % (name, t, reused))
        previous = wave
    # Back to an earlier step: that step's numbers again.
    projection.UpdatePipeline(STEPS[1])
    again = vtk_to_numpy(algorithm.GetOutputDataObject(0).GetPointData().GetArray("Wave"))
    ref = fresh_projection(read_step(target_pvd, 1) if target_pvd else read("lshape_target.vtu"),
                    read_step(source_pvd, 1))
    check(np.nanmax(np.abs(again - vtk_to_numpy(ref.GetPointData().GetArray("Wave")))) < 1e-12,
          "%s: back at t = %g, that step's values" % (name, STEPS[1]))


source_grid = read("lshape_source.vtu")
target_grid = read("lshape_target.vtu")
fixed = write_series(os.path.join(temp_dir, "fixed"), "src", source_grid, STEPS)
moving = write_series(os.path.join(temp_dir, "moving"), "src", source_grid, STEPS,
                      move=lambda t: (0.02 * t, -0.01 * t, 0.0))
# The moving target carries no fields of its own.
moving_target = write_series(os.path.join(temp_dir, "target"), "tgt", target_grid, STEPS, wave=False,
                             move=lambda t: (-0.015 * t, 0.01 * t, 0.0))
static_target = OpenDataFile(os.path.join(DATA, "lshape_target.vtu"))

follow("fixed meshes", static_target, PVDReader(FileName=fixed), None, fixed, True)
follow("moving Source", static_target, PVDReader(FileName=moving), None, moving, False)
# A moving target and a Source whose fields change on a fixed mesh.
follow("moving Input", PVDReader(FileName=moving_target), PVDReader(FileName=fixed), moving_target,
       fixed, False)
finish()
