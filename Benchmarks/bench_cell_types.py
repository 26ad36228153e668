"""What cells that are not simplices cost: hexahedra, quads, mixed cells,
image data, against the same meshes already split into simplices.

    PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 Benchmarks/bench_cell_types.py [--sizes 2D,3D]

(PYTHONPATH: the build's `meshprojection` and `mpsupport` packages; see README.md here.)

Target meshes of the unit square (2D) and unit cube (3D), each given four ways:
  * quads / hexahedra as a vtkUnstructuredGrid, points numbered along the grid;
  * the same, cells and points shuffled (a reader's numbering without locality);
  * the same grid as vtkImageData (pixels / voxels: the points are computed);
  * the same cells split into simplices beforehand with Triangulate /
    Tetrahedralize (vtkDataSetTriangleFilter): the filter's fast path;
and, in 3D, a mixed mesh (the cube's halves as hexahedra and wedges).
The Source is a jittered triangle / tetrahedron mesh (mpbench) of
about as many cells. One point field is projected; each case is the best of
three runs, one thread; columns: the filter's total, the input stage (cell
types, the split, checks, fields) and the search (with the intersections),
in seconds, and the total's ratio to the pre-split target. Prints Markdown.
"""
import argparse
import sys

import numpy as np
from mpbench import UNIT, best_run, cube_mesh, square_mesh, to_grid
from mpsupport import meshes


def structured(n, dim, rng=None):
    """An n^dim grid of the unit square or cube as quads or hexahedra (VTK's
    corner order, points along the grid: mpsupport.meshes without jitter);
    with `rng`, points and cells shuffled."""
    points, cells = (meshes.quads if dim == 2 else meshes.hexahedra)(n, *UNIT, 0, jitter=0.0)
    if rng is not None:
        perm = rng.permutation(len(points))
        inverse = np.empty_like(perm)
        inverse[perm] = np.arange(len(perm))
        points = points[perm]
        cells = inverse[cells][rng.permutation(len(cells))]
    return points, cells


def mixed(n):
    """The cube: hexahedra for x < 1/2, each other hexahedron as two wedges."""
    points, hexes = structured(n, 3)
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid, VTK_HEXAHEDRON, VTK_WEDGE
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
    centre = points[hexes].mean(axis=1)
    left = hexes[centre[:, 0] < 0.5]
    right = hexes[centre[:, 0] >= 0.5]
    # hexahedron 0..7 -> wedges (0 1 2 | 4 5 6) and (0 2 3 | 4 6 7)
    wedges = np.concatenate([right[:, [0, 1, 2, 4, 5, 6]], right[:, [0, 2, 3, 4, 6, 7]]])
    conn = np.concatenate([left.ravel(), wedges.ravel()])
    offsets = np.concatenate([[0], np.cumsum([8] * len(left) + [6] * len(wedges))])
    types = np.array([VTK_HEXAHEDRON] * len(left) + [VTK_WEDGE] * len(wedges), dtype=np.uint8)
    grid = vtkUnstructuredGrid()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(points, deep=1))
    grid.SetPoints(pts)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(offsets.astype(np.int64), deep=1),
                  numpy_to_vtkIdTypeArray(conn.astype(np.int64), deep=1))
    t = vtkUnsignedCharArray()
    t.DeepCopy(numpy_to_vtk(types, deep=1))
    grid.SetCells(t, cells)
    return grid


def image(n, dim):
    from vtkmodules.vtkCommonDataModel import vtkImageData
    img = vtkImageData()
    img.SetDimensions(n + 1, n + 1, n + 1 if dim == 3 else 1)
    img.SetSpacing(1.0 / n, 1.0 / n, 1.0 / n)
    return img


def presplit(grid):
    from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
    f = vtkDataSetTriangleFilter()
    f.SetInputData(grid)
    f.Update()
    return f.GetOutput()


def best_of_three(target, source):
    """Best of 3 runs on one thread (the table is for one thread): total, input stage, search, pieces."""
    total, input_stage, _, search, _, pieces = best_run(target, source, 1, 3)
    return total, input_stage, search, pieces


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", default="316,46", help="cells per side: 2D,3D (default 316,46: 1e5 quads, 1e5 hexahedra)")
    args = parser.parse_args()
    from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, VTK_QUAD
    n2, n3 = (int(s) for s in args.sizes.split(","))
    rng = np.random.default_rng(5)
    print("| target | cells | simplices (pre-split) | total (s) | input stage (s) | search (s) | total / pre-split |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for dim, n in ((2, n2), (3, n3)):
        k = max(2, int(0.9 * n))
        points, cells, simplex = square_mesh(k, k, 3) if dim == 2 else cube_mesh(k, k, k, 3)
        source = to_grid(points, cells, simplex, np.sin(4 * points[:, 0]) * np.cos(3 * points[:, 1]))
        cell_type = VTK_QUAD if dim == 2 else VTK_HEXAHEDRON
        kind = "quads" if dim == 2 else "hexahedra"
        ordered = to_grid(*structured(n, dim), cell_type)
        cases = [("%s (grid order)" % kind, ordered),
                 ("%s (shuffled)" % kind, to_grid(*structured(n, dim, rng), cell_type)),
                 ("image data", image(n, dim))]
        if dim == 3:
            cases.append(("hexahedra + wedges", mixed(n)))
        split = presplit(ordered)
        cases.append(("pre-split (%s)" % ("Triangulate" if dim == 2 else "Tetrahedralize"), split))
        reference = best_of_three(split, source)[0]
        for name, target in cases:
            total, inputs, search, pairs = best_of_three(target, source)
            simplices = presplit(target).GetNumberOfCells() if name.startswith("hexahedra +") else None
            print("| %dD %s | %d | %s | %.3f | %.3f | %.3f | %.2f |" % (
                dim, name, target.GetNumberOfCells(),
                "" if simplices is None else simplices, total, inputs, search, total / reference))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
