"""The README's own-pair command on pairs unlike the samples (run with
Debian's python3; it writes the pairs and runs Scripts/project_sample.py
--source --target under pvpython, as Scripts/main.sh does):

 - a Source without `Smooth`, with point arrays Temperature (linear) and
   Velocity (3 components) and a cell array Pressure: every array is
   projected, the summary reports Temperature (the first), the linear field
   is exact, the picture is written, exit code 0;
 - a Source with one cell array only: projected and reported (its
   integral conserved), exit code 0;
 - a Target that reaches beyond the Source: exit code 0, projected (exact)
   where covered;
 - a Source with only an integer label array and a Target beyond it:
   labels projected, the summary says they are not integrated, and the
   picture shows the invalid cells (which hold FillLabel, not NaN) in yellow;
 - a pair that does not overlap: exit code 1, one line saying so, no
   traceback.

    python3 TestMeshProjectionOwnPair.py PVPYTHON PLUGIN PROJECT_SAMPLE OUT_DIR
"""
import os
import re
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_QUAD, VTK_TRIANGLE
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader, vtkXMLUnstructuredGridWriter

from mpsupport import meshes
from mpsupport.testing import check, finish

pvpython, plugin, script, out_dir = sys.argv[1:5]
os.makedirs(out_dir, exist_ok=True)


def linear(x):
    return 1 + 2 * x[:, 0] - 3 * x[:, 1]


def write(name, grid):
    path = os.path.join(out_dir, name + ".vtu")
    w = vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(grid)
    w.SetDataModeToBinary()  # inline: Debian's expat cannot read appended data
    w.Write()
    return path


def target(shift=0.0):
    x, cells = meshes.triangles(10, (shift, 0, 0), (1 + shift, 1, 0), seed=1)
    return write("target%g" % shift, meshes.grid(x, cells, VTK_TRIANGLE))


def source(point_arrays):
    g = meshes.grid(*meshes.quads(12, (-0.1, -0.1, 0), (1.1, 1.1, 0), seed=2), VTK_QUAD)
    x = vtk_to_numpy(g.GetPoints().GetData())
    if point_arrays:
        meshes.add_array(g.GetPointData(), "Temperature", linear(x))
        meshes.add_array(g.GetPointData(), "Velocity", np.stack([x[:, 1], -x[:, 0], 0 * x[:, 0]], 1))
    meshes.add_array(g.GetCellData(), "Pressure" if point_arrays else "Density", np.arange(g.GetNumberOfCells()) % 5 + 1.0)
    return write("source_points" if point_arrays else "source_cells", g)


def labelled_source():
    """A Source whose only array is an integer cell label (0 and 2)."""
    g = meshes.grid(*meshes.quads(12, (-0.1, -0.1, 0), (1.1, 1.1, 0), seed=2), VTK_QUAD)
    labels = numpy_to_vtk(2 * (np.arange(g.GetNumberOfCells(), dtype=np.int32) % 2), deep=True)
    labels.SetName("Material")
    g.GetCellData().AddArray(labels)
    return write("source_labels", g)


def yellow_pixels(name):
    """Pixels of NAME.png in the invalid parts' colour (yellow)."""
    r = vtkPNGReader()
    r.SetFileName(os.path.join(out_dir, name + ".png"))
    r.Update()
    rgb = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
    return int(((rgb[:, 0] > 150) & (abs(rgb[:, 0] - rgb[:, 1]) < 20) & (rgb[:, 2] < 80)).sum())


def run(name, source_file, target_file):
    done = subprocess.run([pvpython, script, "--plugin", plugin, "--source", source_file, "--target", target_file,
                           "--name", name, "--out-dir", out_dir], capture_output=True, text=True, timeout=300)
    print("---- %s: exit code %d\n%s%s" % (name, done.returncode, done.stdout, done.stderr))
    check("Traceback" not in done.stderr, "%s: no traceback" % name)
    return done


def projected(name):
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(out_dir, name + "-projected.vtu"))
    r.Update()
    return r.GetOutput()


# A Source without Smooth: every array projected, the first one shown.
done = run("fields", source(True), target())
check(done.returncode == 0, "fields: exit code %d" % done.returncode)
check("integral of Temperature (SourceIntegral_, TargetIntegral_)" in done.stdout,
      "fields: the summary reports Temperature")
check(re.search(r"projected +Temperature, Velocity, Pressure", done.stdout) is not None,
      "fields: every Source array listed as projected")
out = projected("fields")
for kind, data, name in (("point", out.GetPointData(), "Temperature"), ("point", out.GetPointData(), "Velocity"),
                         ("cell", out.GetCellData(), "Pressure")):
    check(data.GetArray(name) is not None, "fields: %s array %s in the output" % (kind, name))
if out.GetPointData().GetArray("Temperature") is not None:
    x = vtk_to_numpy(out.GetPoints().GetData())
    err = np.abs(vtk_to_numpy(out.GetPointData().GetArray("Temperature")) - linear(x)).max()
    check(err < 1e-10, "fields: linear Temperature exact (%.3g)" % err)
    check(out.GetPointData().GetArray("Velocity").GetNumberOfComponents() == 3, "fields: Velocity keeps 3 components")
png = os.path.join(out_dir, "fields.png")
check(os.path.exists(png) and os.path.getsize(png) > 10000, "fields: the picture is written")

# Only a cell array.
done = run("cells", source(False), target())
check(done.returncode == 0, "cells: exit code %d" % done.returncode)
found = re.search(r"integral of Density .* relative difference ([0-9.e+-]+)", done.stdout)
check(found is not None and float(found.group(1)) < 1e-12,
      "cells: the summary reports Density, conserved (%s)" % (found.group(1) if found else "not said"))
check(projected("cells").GetCellData().GetArray("Density") is not None, "cells: Density in the output")

# A Target reaching beyond the Source: projected where covered, exit code 0.
done = run("partial", source(True), target(0.5))
check(done.returncode == 0, "partial: exit code %d" % done.returncode)
out = projected("partial")
valid = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
x = vtk_to_numpy(out.GetPoints().GetData())
err = np.abs(vtk_to_numpy(out.GetPointData().GetArray("Temperature"))[valid] - linear(x[valid])).max()
check(0 < valid.sum() < len(valid) and err < 1e-10,
      "partial: %d of %d points valid, linear exact there (%.3g)" % (valid.sum(), len(valid), err))

check(yellow_pixels("partial") > 1000, "partial: the picture shows the invalid part (%d yellow pixels)" %
      yellow_pixels("partial"))
check(yellow_pixels("fields") == 0, "fields: no yellow where everything is valid (%d)" % yellow_pixels("fields"))

# Only an integer label array, the Target reaching beyond: labels are not
# integrated (said), the invalid cells hold FillLabel yet show as invalid.
done = run("labels", labelled_source(), target(0.5))
check(done.returncode == 0, "labels: exit code %d" % done.returncode)
check("integral of Material: none (projected as labels" in done.stdout, "labels: the summary says it is not integrated")
material = vtk_to_numpy(projected("labels").GetCellData().GetArray("Material"))
check(set(np.unique(material).tolist()) == {-1, 0, 2}, "labels: Source labels and FillLabel only: %s" %
      np.unique(material))
check(yellow_pixels("labels") > 1000, "labels: the picture shows the invalid cells (%d yellow pixels)" %
      yellow_pixels("labels"))

# Apart: one line, exit code 1.
done = run("apart", source(True), target(5.0))
check(done.returncode == 1, "apart: exit code %d" % done.returncode)
said = [line for line in done.stdout.splitlines() if "do not overlap" in line]
check(len(said) == 1 and said[0].startswith("apart: nothing projected:"), "apart: one line says so: %r" % said)
check(not os.path.exists(os.path.join(out_dir, "apart.png")), "apart: no picture")
finish()
