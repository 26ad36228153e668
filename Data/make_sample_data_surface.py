"""The surface sample of Data/: two Gmsh facetizations of the unit sphere.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Data/make_sample_data_surface.py

(needs python3-gmsh, and the build's `mpsupport` package on PYTHONPATH)

  sphere_source.vtu  ~6,200 triangles (Frontal-Delaunay, size 0.07),
                     point data Smooth, Linear; cell data Pressure
  sphere_target.vtu  ~1,200 quadrilaterals (Frontal-Delaunay recombined by
                     Blossom, size 0.12): curved quads, each split by the
                     filter into two triangles on its own points

  Smooth   = 2 + sin(3x) cos(2y) + 0.5 z  (positive: its integral means something)
  Linear   = 1 + 2x - 3y + 0.5z  (linear in space; on a curved surface a
                                  projection is exact only to O(h^2))
  Pressure = 1 + z^2 at each triangle's centroid (cell data)

Gmsh's node and element order is kept; the files are written inline binary
(VTK 9.2 with Debian 12's expat cannot read appended data back).
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

from mpsupport import gmshmeshes  # noqa: E402
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import VTK_QUAD, VTK_TRIANGLE, vtkUnstructuredGrid  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter  # noqa: E402


def to_grid(poly):
    grid = vtkUnstructuredGrid()
    grid.SetPoints(poly.GetPoints())
    offsets = vtk_to_numpy(poly.GetPolys().GetOffsetsArray())
    corners = set(np.diff(offsets).tolist())
    assert len(corners) == 1, corners
    grid.SetCells(VTK_TRIANGLE if corners == {3} else VTK_QUAD, poly.GetPolys())
    return grid


def add(data, name, values):
    array = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float64), deep=True)
    array.SetName(name)
    data.AddArray(array)


def write(grid, name):
    writer = vtkXMLUnstructuredGridWriter()
    writer.SetFileName(os.path.join(HERE, name))
    writer.SetDataModeToBinary()
    writer.SetInputData(grid)
    writer.Write()
    print("wrote %s: %d cells, %d points" % (name, grid.GetNumberOfCells(), grid.GetNumberOfPoints()))


def main():
    source = to_grid(gmshmeshes.surface("sphere", 0.07, 6))
    x = vtk_to_numpy(source.GetPoints().GetData())
    add(source.GetPointData(), "Smooth", 2 + np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + 0.5 * x[:, 2])
    add(source.GetPointData(), "Linear", 1 + 2 * x[:, 0] - 3 * x[:, 1] + 0.5 * x[:, 2])
    cells = vtk_to_numpy(source.GetCells().GetConnectivityArray()).reshape(-1, 3)
    z = x[cells, 2].mean(axis=1)
    add(source.GetCellData(), "Pressure", 1 + z * z)
    source.GetPointData().SetActiveScalars("Smooth")
    write(source, "sphere_source.vtu")
    target = to_grid(gmshmeshes.surface("sphere", 0.12, 6, quads=True))
    write(target, "sphere_target.vtu")


if __name__ == "__main__":
    main()
