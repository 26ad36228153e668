"""Time the filter on two Gmsh facetizations of the unit sphere (a surface in 3D).

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_surfaces.py [H]

H is the target's mesh size (default 0.006: about 824,000 triangles, Gmsh
Frontal-Delaunay); the source is 1.3 H (Delaunay). Needs python3-gmsh;
at the default size Gmsh's meshing outlasts the projection. Prints the best
of two runs on 1 and on 2 threads, with the stages, as on the performance page (docs/performance.md).
"""
import sys
import time

import numpy as np

from mpbench import time_filter
from mpsupport import gmshmeshes

h = float(sys.argv[1]) if len(sys.argv) > 1 else 0.006
start = time.time()
target = gmshmeshes.surface("sphere", h, 6)
source = gmshmeshes.with_point_field(gmshmeshes.surface("sphere", 1.3 * h, 5), "f", lambda x, y, z: x * y + np.sin(2 * z))
print("meshing %.1f s: target %d triangles, source %d" % (time.time() - start, target.GetNumberOfCells(),
                                                           source.GetNumberOfCells()))
time_filter(target, source)
