"""Serendipity cells that are not affine images of their reference cell
(Geometry/HiddenNodes.h), through the filter, on Gmsh order-2 meshes
(mpsupport.gmshmeshes.second_order): 8-node quadrilaterals of an
unstructured square (straight, not parallelograms), 20-node hexahedra of
extruded unstructured quadrilaterals and 15-node wedges of extruded
triangles, both extrusions tilted by z -> z (1 + 0.3 x) (their tops no
longer parallel to their bottoms; every face stays planar and every mid
node on its straight edge):

    a. a quadratic field given at every Source node is reproduced at every
       node of such Inputs to 1e-9 of its range, from Sources of the same
       and of other types;
    b. such a Source projected onto a linear Input keeps the quadratic's
       integral over the domain to 1e-11 (TargetIntegral_ and
       SourceIntegral_);
    c. on curved disks of 8-node quadrilaterals a linear field is exact at
       every node (1e-9 of its range).
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import (VTK_QUADRATIC_HEXAHEDRON, VTK_QUADRATIC_QUAD, VTK_QUADRATIC_TETRA,
                                           VTK_QUADRATIC_TRIANGLE, VTK_QUADRATIC_WEDGE, VTK_TETRA, VTK_TRIANGLE,
                                           vtkUnstructuredGrid)

import meshprojection
from mpsupport import gmshmeshes
from mpsupport.testing import check, finish


def quadratic(x):
    return 0.3 + x[:, 0] - 2.0 * x[:, 1] + 0.7 * x[:, 2] + 1.5 * x[:, 0] ** 2 - x[:, 0] * x[:, 1] \
        + 0.8 * x[:, 1] ** 2 + 0.6 * x[:, 1] * x[:, 2] - 0.9 * x[:, 2] ** 2 + 0.4 * x[:, 0] * x[:, 2]


def linear(x):
    return 1.0 + 2.0 * x[:, 0] - 3.0 * x[:, 1] + 0.5 * x[:, 2]


def tilt(x):
    """z -> z (1 + 0.3 x): bilinear, so straight second-order cells stay straight."""
    y = x.copy()
    y[:, 2] *= 1.0 + 0.3 * x[:, 0]
    return y


def points_of(g):
    return vtk_to_numpy(g.GetPoints().GetData())


def rebuilt(g, cell=lambda t, ids: (t, ids), transform=None):
    """A copy of g: each cell through cell(type, ids), the points through transform."""
    out = vtkUnstructuredGrid()
    points = vtkPoints()
    x = points_of(g).copy()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(transform(x) if transform else x), deep=True))
    out.SetPoints(points)
    out.Allocate(g.GetNumberOfCells())
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        t, kept = cell(g.GetCellType(c), [ids.GetId(k) for k in range(ids.GetNumberOfIds())])
        out.InsertNextCell(t, len(kept), kept)
    return out


def corners_only(g, transform=None):
    linear_of = {VTK_QUADRATIC_TRIANGLE: (VTK_TRIANGLE, 3), VTK_QUADRATIC_TETRA: (VTK_TETRA, 4)}
    return rebuilt(g, lambda t, ids: (linear_of[t][0], ids[:linear_of[t][1]]), transform)


def with_fields(g):
    g = rebuilt(g)
    x = points_of(g)
    for name, values in (("Quadratic", quadratic(x)), ("Linear", linear(x))):
        a = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
        a.SetName(name)
        g.GetPointData().AddArray(a)
    return g


def project(target, source):
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.Update()
    return f.GetOutput()


def nodal_error(out, name, f):
    x = points_of(out)
    valid = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
    exact = f(x)
    error = np.abs(vtk_to_numpy(out.GetPointData().GetArray(name)) - exact)
    return np.max(error[valid]) / np.ptp(exact), valid


def non_affine(g):
    """How many of g's serendipity cells are not affine images of their reference cell,
    and how many there are."""
    # (a corner, and the corners its reference point and its axes' ends give)
    frames = {VTK_QUADRATIC_QUAD: (2, [0, 1, 3], [1, 1]), VTK_QUADRATIC_HEXAHEDRON: (6, [0, 1, 3, 4], [1, 1, 1]),
              VTK_QUADRATIC_WEDGE: (4, [0, 1, 2, 3], [1, 0, 1])}
    x = points_of(g)
    count = total = 0
    for c in range(g.GetNumberOfCells()):
        t = g.GetCellType(c)
        if t not in frames:
            continue
        ids = [g.GetCell(c).GetPointId(k) for k in range(g.GetCell(c).GetNumberOfPoints())]
        corner, frame, steps = frames[t]
        guess = x[ids[frame[0]]] + sum(s * (x[ids[k]] - x[ids[frame[0]]]) for s, k in zip(steps, frame[1:]))
        total += 1
        count += np.linalg.norm(guess - x[ids[corner]]) > 1e-6
    return count, total


def box_integral(f, dimension, transform):
    """The integral of f over the image of the unit square or cube under transform
    (here the identity or tilt, Jacobian 1 + 0.3 x): Gauss rules, exact for these polynomials."""
    r, w = np.polynomial.legendre.leggauss(6)
    r, w = 0.5 * (r + 1.0), 0.5 * w
    grids = np.meshgrid(*([r] * dimension), indexing="ij")
    weights = np.prod(np.meshgrid(*([w] * dimension), indexing="ij"), axis=0).ravel()
    x = np.zeros((weights.size, 3))
    for a in range(dimension):
        x[:, a] = grids[a].ravel()
    jacobian = 1.0 + 0.3 * x[:, 0] if transform is tilt else 1.0
    y = transform(x) if transform else x
    return float(np.sum(weights * jacobian * f(y)))


square = {"quad8": gmshmeshes.second_order("square", 0.29, True, True),
          "quad8 fine": gmshmeshes.second_order("square", 0.21, True, True),
          "quad9": gmshmeshes.second_order("square", 0.31, True),
          "tri6": gmshmeshes.second_order("square", 0.23)}
hexes = {"hex20": rebuilt(gmshmeshes.second_order("prisms", 0.5, True, True), transform=tilt),
         "hex20 fine": rebuilt(gmshmeshes.second_order("prisms", 0.34, True, True), transform=tilt),
         "hex27": rebuilt(gmshmeshes.second_order("prisms", 0.4, True), transform=tilt)}
wedges = {"wedge15": rebuilt(gmshmeshes.second_order("prisms", 0.5, False, True), transform=tilt),
          "wedge15 fine": rebuilt(gmshmeshes.second_order("prisms", 0.34, False, True), transform=tilt),
          "wedge18": rebuilt(gmshmeshes.second_order("prisms", 0.4), transform=tilt)}

for family in (square, hexes, wedges):
    for name, g in family.items():
        count, total = non_affine(g)
        print("%s: %d of %d serendipity cells not affine" % (name, count, total))
        check(total == 0 or count >= total // 2, "%s: most serendipity cells are not affine (%d of %d)"
              % (name, count, total))

# a. Quadratic fields at every node of non-affine serendipity Inputs.
pairs = [("quad8", "quad8 fine"), ("quad8 fine", "quad8"), ("quad9", "quad8"), ("tri6", "quad8"),
         ("quad8", "quad9"), ("hex20", "hex20 fine"), ("hex20 fine", "hex20"), ("hex27", "hex20"),
         ("wedge15", "wedge15 fine"), ("wedge15 fine", "wedge15"), ("wedge18", "wedge15"), ("hex20", "wedge15")]
meshes = dict(square, **hexes, **wedges)
worst = 0.0
for s, t in pairs:
    error, valid = nodal_error(project(meshes[t], with_fields(meshes[s])), "Quadratic", quadratic)
    worst = max(worst, error)
    print("%s -> %s: quadratic field off by %.2g of its range" % (s, t, error))
    check(valid.all() and error <= 1e-9,
          "%s -> %s: a quadratic field reproduced at every node (%.2g of its range, %d of %d valid)"
          % (s, t, error, valid.sum(), len(valid)))
print("worst quadratic error on non-affine serendipity Inputs: %.2g of the range" % worst)

# b. Such Sources onto linear Inputs keep the quadratic's integral.
for name, source_mesh, target_mesh, dimension, transform in (
        ("quad8 -> triangles", square["quad8"], corners_only(gmshmeshes.second_order("square", 0.19)), 2, None),
        ("hex20 -> tetrahedra", hexes["hex20 fine"],
         corners_only(gmshmeshes.second_order("cube", 0.3), tilt), 3, tilt),
        ("wedge15 -> tetrahedra", wedges["wedge15 fine"],
         corners_only(gmshmeshes.second_order("cube", 0.3), tilt), 3, tilt)):
    exact = box_integral(quadratic, dimension, transform)
    out = project(target_mesh, with_fields(source_mesh))
    target_integral = out.GetFieldData().GetArray("TargetIntegral_Quadratic").GetValue(0)
    source_integral = out.GetFieldData().GetArray("SourceIntegral_Quadratic").GetValue(0)
    print("%s: integral %.15g, TargetIntegral_ %.15g, SourceIntegral_ %.15g"
          % (name, exact, target_integral, source_integral))
    check(abs(target_integral - exact) <= 1e-11 * abs(exact),
          "%s: the quadratic's integral kept (%.3g relative)" % (name, abs(target_integral / exact - 1)))
    check(abs(source_integral - exact) <= 1e-11 * abs(exact),
          "%s: SourceIntegral_ is the quadratic's integral (%.3g relative)" % (name, abs(source_integral / exact - 1)))

# c. Curved disks of 8-node quadrilaterals: linear fields exact at every node.
disk = {"quad8": gmshmeshes.second_order("disk", 0.23, True, True),
        "tri6": gmshmeshes.second_order("disk", 0.29)}
for s, t in (("quad8", "tri6"), ("tri6", "quad8"), ("quad8", "quad8")):
    target = disk[t] if s != t else gmshmeshes.second_order("disk", 0.31, True, True)
    error, valid = nodal_error(project(target, with_fields(disk[s])), "Linear", linear)
    print("disk %s -> %s: linear field off by %.2g of its range" % (s, t, error))
    check(valid.any() and error <= 1e-9, "disk %s -> %s: a linear field exact at every node (%.2g)" % (s, t, error))

finish()
