"""Time the filter on a trace: a Gmsh sphere (radius 0.6) inside Gmsh's
tetrahedra of the unit ball.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_traces.py [H]

H is the ball's mesh size (default 0.04: about 295,000 tetrahedra); the
sphere's is H / 4 (about 300,000 triangles). Needs python3-gmsh. Prints
the best of two runs on 1 and on 2 threads, with the stages, as on the
performance page, and beside them VTK's probe on the same pair (vtkResampleWithDataSet with a
vtkStaticCellLocator, as ParaView's Resample With Dataset; not conservative).
"""
import sys
import time

import numpy as np

from mpbench import time_filter
from mpsupport import gmshmeshes
from vtkmodules.vtkCommonDataModel import vtkStaticCellLocator
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkResampleWithDataSet
from vtkmodules.vtkFiltersGeneral import vtkTransformFilter

h = float(sys.argv[1]) if len(sys.argv) > 1 else 0.04
start = time.time()
source = gmshmeshes.with_point_field(gmshmeshes.volume("sphere", h), "f", lambda x, y, z: x * y + np.sin(2 * z))
shrink = vtkTransform()
shrink.Scale(0.6, 0.6, 0.6)
moved = vtkTransformFilter()
moved.SetTransform(shrink)
moved.SetInputData(gmshmeshes.surface("sphere", h / 4, 6))
moved.Update()
target = moved.GetOutput()
print("meshing %.1f s: target %d triangles, source %d tetrahedra" % (
    time.time() - start, target.GetNumberOfCells(), source.GetNumberOfCells()))
time_filter(target, source)
best = None
for repeat in range(2):
    probe = vtkResampleWithDataSet()
    probe.SetInputData(target)
    probe.SetSourceData(source)
    probe.SetCellLocatorPrototype(vtkStaticCellLocator())
    start = time.time()
    probe.Update()
    seconds = time.time() - start
    best = seconds if best is None else min(best, seconds)
print("probe (vtkResampleWithDataSet, static cell locator): %.3f s" % best)
