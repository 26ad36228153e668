"""The trace sample of Data/: a wavy sheet inside the 3D sample's solid.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Data/make_sample_data_trace.py

(needs python3-gmsh, and the build's `mpsupport` package on PYTHONPATH)

  lshape3d_sheet.vtu  ~3,400 triangles (Gmsh Frontal-Delaunay, size 0.07) of
                      the L-shaped section with its square hole (the solid of
                      lshape3d_*.vtu: [0,3]x[0,3] minus [1.5,3]x[1.5,3], hole
                      [0.5,1]x[0.5,1]), lifted to z = 0.5 + 0.2 sin(2x) cos(1.5y):
                      a curved surface inside the solid (z in [0.3, 0.7]) whose
                      rim lies on the solid's side walls

The main job projects the 3D source's fields onto it (a trace: the volume
field on a surface inside). Gmsh's node and element order is kept; the file
is written inline binary (VTK 9.2 with Debian 12's expat cannot read
appended data back).
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from mpsupport import gmshmeshes  # noqa: E402
from make_sample_data import write  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray  # noqa: E402
from vtkmodules.vtkCommonCore import vtkPoints  # noqa: E402
from vtkmodules.vtkCommonDataModel import VTK_TRIANGLE, vtkCellArray, vtkUnstructuredGrid  # noqa: E402


def section():
    import gmsh
    occ = gmsh.model.occ
    square = occ.addRectangle(0, 0, 0, 3, 3)
    corner = occ.addRectangle(1.5, 1.5, 0, 1.5, 1.5)
    hole = occ.addRectangle(0.5, 0.5, 0, 0.5, 0.5)
    occ.cut([(2, square)], [(2, corner), (2, hole)])
    occ.synchronize()
    return [], []


def main():
    x, cells = gmshmeshes._generate("sheet", 2, section, 0.07, [("Mesh.Algorithm", 6)])
    used = np.unique(np.asarray(cells).ravel())
    assert len(used) == len(x), "every Gmsh node is a corner"
    x = np.array(x)
    x[:, 2] = 0.5 + 0.2 * np.sin(2 * x[:, 0]) * np.cos(1.5 * x[:, 1])
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x), deep=True))
    connectivity = np.asarray(cells, dtype=np.int64).ravel()
    array = vtkCellArray()
    array.SetData(numpy_to_vtkIdTypeArray(np.arange(0, len(connectivity) + 1, 3, dtype=np.int64), deep=True),
                  numpy_to_vtkIdTypeArray(connectivity, deep=True))
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    grid.SetCells(VTK_TRIANGLE, array)
    path = os.path.join(HERE, "lshape3d_sheet.vtu")
    write(grid, path)
    print("wrote %s: %d triangles, %d points" % (path, grid.GetNumberOfCells(), grid.GetNumberOfPoints()))


if __name__ == "__main__":
    main()
