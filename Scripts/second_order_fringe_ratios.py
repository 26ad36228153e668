"""The fringe's error ratios on second-order Inputs, on more pairs than
Python.SecondOrderFringe holds: Gmsh order-2 meshes
(mpsupport.gmshmeshes.second_order) moved so that the Input reaches beyond
the Source, the fields of mpsupport.fringe. Per pair, as the test measures
them: the worst error at a valid node over the worst at interior nodes
(nodes whose cells are all covered) for the point data, at the free nodes
only, and for the cell data sent to points; the linear field's worst error
at a valid node (over its range); the aggregated nodes; the nodes covered
a tenth or more of their cells' measure left invalid. With -v, per pair
the five worst valid nodes: their ratio, covered fraction, stencil size,
sum |w|, and the extension's error split into its truncation (the weights
applied to the exact field) and the free values' errors it carries.

    PYTHONPATH=<build>/lib/python3/dist-packages:Testing/Support/Python \\
        /usr/bin/python3 Scripts/second_order_fringe_ratios.py [-v] [pair ...]
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter

from meshprojection import fringe_extension
from mpsupport import gmshmeshes
from mpsupport.fringe import fully_covered, linear, point_cells, smooth, with_fields
from mpsupport.testing import mortar

# Each second-order type's linear cell on its corners: the measure of a cell.
CORNERS = {22: (5, 3), 23: (9, 4), 28: (9, 4), 24: (10, 4), 25: (12, 8), 29: (12, 8)}

so = gmshmeshes.second_order
moved = gmshmeshes.moved
# name: (Input, Source); the first six are Python.SecondOrderFringe's.
PAIRS = {
    "tri6<-quad9": lambda: (moved(so("square", 0.06), translate=(0.31, 0.17, 0)), so("square", 0.078, True)),
    "tri6<-disk": lambda: (moved(so("square", 0.06), translate=(0.25, -0.45, 0)), so("disk", 0.078, True)),
    "quad9<-tri6": lambda: (moved(so("square", 0.078, True), translate=(0.4, 0.1, 0)), so("square", 0.06)),
    "tet10<-hex20": lambda: (moved(so("cube", 0.14), translate=(0.27, 0.13, 0.21)), so("hexes", 0.14, False, True)),
    "hex20<-tet10": lambda: (moved(so("hexes", 0.17, False, True), translate=(0.27, 0.13, 0.21)), so("cube", 0.17)),
    "hex27<-tet10": lambda: (moved(so("hexes", 0.2), translate=(-0.33, 0.41, 0.07)), so("cube", 0.17)),
    "quad9<-tri6/b": lambda: (moved(so("square", 0.078, True), translate=(-0.23, 0.37, 0)), so("square", 0.06)),
    "quad9<-tri6/c": lambda: (moved(so("square", 0.09, True), translate=(0.13, -0.29, 0)), so("square", 0.07)),
    "quad8<-tri6": lambda: (moved(so("square", 0.078, True, True), translate=(0.4, 0.1, 0)), so("square", 0.06)),
    "tri6<-tri6": lambda: (moved(so("square", 0.07), translate=(0.21, -0.33, 0)), so("square", 0.06)),
    "tet10<-tet10": lambda: (moved(so("cube", 0.15), translate=(-0.2, 0.33, 0.11)), so("cube", 0.17)),
    "hex20<-tet10/b": lambda: (moved(so("hexes", 0.17, False, True), translate=(-0.19, 0.31, -0.23)),
                               so("cube", 0.17)),
    "hex27<-hex20": lambda: (moved(so("hexes", 0.2), translate=(0.27, -0.19, 0.13)), so("hexes", 0.17, False, True)),
    "tet10<-hex27": lambda: (moved(so("cube", 0.14), translate=(-0.31, 0.23, 0.17)), so("hexes", 0.2)),
}


def measures(g):
    """Per cell of g the measure of the linear cell on its corners."""
    corners = vtkUnstructuredGrid()
    corners.SetPoints(g.GetPoints())
    for c in range(g.GetNumberOfCells()):
        t, n = CORNERS[g.GetCellType(c)]
        corners.InsertNextCell(t, n, [g.GetCell(c).GetPointId(k) for k in range(n)])
    f = vtkCellSizeFilter()
    f.SetInputData(corners)
    f.Update()
    name = "Area" if g.GetCell(0).GetCellDimension() == 2 else "Volume"
    return vtk_to_numpy(f.GetOutput().GetCellData().GetArray(name))


def array(out, name, cells=False):
    data = out.GetCellData() if cells else out.GetPointData()
    return vtk_to_numpy(data.GetArray(name))


def measure(name, verbose):
    target, source_mesh = PAIRS[name]()
    around = point_cells(target)
    f = mortar(target, with_fields(source_mesh), pieces=False, CellDataTarget=1, CacheOperator=True)
    out = f.GetOutput()
    x = vtk_to_numpy(out.GetPoints().GetData())
    valid = array(out, "vtkValidPointMask").astype(bool)
    cover = array(out, "CoveredFraction", cells=True)
    interior = valid & fully_covered(cover, around)
    exact = linear(x)
    lin = np.max(np.abs(array(out, "l") - exact)[valid]) / np.ptp(exact)
    P = fringe_extension(f).tocsr()
    free = valid & (P.getnnz(axis=0) > 0 if P.shape[0] else True)
    error = array(out, "s") - smooth(x)
    scale = np.max(np.abs(error[interior]))
    cell_error = np.abs(array(out, "c") - smooth(x))
    size = measures(target)
    fraction = np.array([np.dot(cover[c], size[c]) / size[c].sum() for c in around])
    print("%-15s point %6.2f  free %5.2f  cell %5.2f  linear %.0e  aggregated %d of %d valid  "
          "invalid covered >= 10%%: %d" % (
              name, np.max(np.abs(error[valid])) / scale, np.max(np.abs(error[free])) / scale,
              np.max(cell_error[valid]) / np.max(cell_error[interior]), lin, valid.sum() - free.sum(),
              valid.sum(), (~valid & (fraction >= 0.1)).sum()), flush=True)
    for i in np.argsort(-np.where(valid, np.abs(error), 0))[:5 if verbose else 0]:
        cols, w = P.indices[P.indptr[i]:P.indptr[i + 1]], P.data[P.indptr[i]:P.indptr[i + 1]]
        aggregated = not (len(cols) == 1 and cols[0] == i)
        truncation = np.dot(w, smooth(x[cols])) - smooth(x[i:i + 1])[0] if aggregated else 0.0
        carried = np.dot(w, error[cols]) if aggregated else 0.0
        print("    node %5d  %6.2f  covered %.3f  %s  points %3d  sum|w| %5.1f  truncation %6.2f  carried %6.2f"
              % (i, abs(error[i]) / scale, fraction[i], "aggregated" if aggregated else "free      ",
                 len(cols), np.abs(w).sum(), truncation / scale, carried / scale))


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "-v"]
    for pair in args or PAIRS:
        measure(pair, "-v" in sys.argv)
