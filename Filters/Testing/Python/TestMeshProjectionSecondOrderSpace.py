"""Point data of second-order cells in the cells' own space (their shape
functions, Transfer/NodalSpace.h), through the filter, on Gmsh order-2
meshes (mpsupport.gmshmeshes.second_order) of the unit square and cube and
of the unit disk (curved: its boundary mid nodes on the circle):

    a. a quadratic field given at every Source node is reproduced at every
       node of straight second-order Inputs to 1e-9 of its range: 6-node
       triangles, 9-node quadrilaterals, 10-node tetrahedra, 20- and 27-node
       hexahedra of a structured cube, 15- and 18-node wedges of an extruded
       square, Lagrange triangles and tetrahedra of order 2; from Sources of
       the same and of other types (on the linear split of the same nodes it
       is not: the error there is reported beside);
    b. a second-order Source field projected onto a linear Input keeps the
       Source field's own integral (its cells' interpolant, integrated here
       with Gauss rules through VTK's own shape functions) to 1e-11, in
       TargetIntegral_ and SourceIntegral_;
    c. on curved disks a linear field is exact at every node (1e-9 of its
       range) and constant cell data stays constant, whole and in part;
    d. MassMatrix Lumped on an Input mixing serendipity cells (hex20) with
       other second-order cells (tet10 beside them), which has no form
       (their mid-edge nodes' shares differ: Transfer/BernsteinForm.h): one
       warning, and the consistent projection (the quadratic field still
       reproduced; the other second-order Inputs are lumped:
       TestMeshProjectionSecondOrderLumped.py);
       integer point labels onto a second-order Input: each node takes the
       label of the region it lies in, fractions within [0, 1].
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import (VTK_LAGRANGE_TETRAHEDRON, VTK_LAGRANGE_TRIANGLE, VTK_QUADRATIC_TETRA,
                                           VTK_QUADRATIC_TRIANGLE, VTK_TETRA, VTK_TRIANGLE)

import meshprojection
from mpsupport import gmshmeshes, secondorder
from mpsupport.secondorder import copy_grid, linear, point_array, points_of
from mpsupport.testing import check, finish, observed_filter


def quadratic(x):
    return 0.3 + x[:, 0] - 2.0 * x[:, 1] + 0.7 * x[:, 2] + 1.5 * x[:, 0] ** 2 - x[:, 0] * x[:, 1] \
        + 0.8 * x[:, 1] ** 2 + 0.6 * x[:, 1] * x[:, 2] - 0.9 * x[:, 2] ** 2 + 0.4 * x[:, 0] * x[:, 2]


def rebuilt(g, cell=None, transform=None):
    """A copy of g without arrays: each cell through cell(type, ids), the points through transform."""
    return copy_grid(g, transform, cell=cell)


def corners_only(g):
    """The linear cells on g's corners (6-node triangles, 10-node tetrahedra)."""
    linear_of = {VTK_QUADRATIC_TRIANGLE: (VTK_TRIANGLE, 3), VTK_QUADRATIC_TETRA: (VTK_TETRA, 4)}
    return rebuilt(g, lambda t, ids: (linear_of[t][0], ids[:linear_of[t][1]]))


def as_lagrange(g):
    """The same cells as VTK's Lagrange cells of order 2 (same node order for these two)."""
    lagrange = {VTK_QUADRATIC_TRIANGLE: VTK_LAGRANGE_TRIANGLE, VTK_QUADRATIC_TETRA: VTK_LAGRANGE_TETRAHEDRON}
    return rebuilt(g, lambda t, ids: (lagrange[t], ids))


def with_fields(g):
    return secondorder.with_fields(g, (("Quadratic", quadratic), ("Linear", linear)))


def project(target, source):
    return secondorder.project(target, source)


def nodal_error(out, name, f):
    x = points_of(out)
    valid = point_array(out, "vtkValidPointMask").astype(bool)
    exact = f(x)
    return np.max(np.abs(point_array(out, name) - exact)[valid]) / np.ptp(exact), valid


def gauss_1d(n):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def reference_rule(dimension, simplex):
    """Gauss points (parametric coordinates, weights of the reference cell) exact to degree 7."""
    x, w = gauss_1d(5)
    if dimension == 2:
        u, v = np.meshgrid(x, x, indexing="ij")
        wu = np.outer(w, w).ravel()
        if simplex:  # the square folded onto the triangle (Duffy)
            return np.c_[u.ravel(), (v * (1 - u)).ravel(), 0 * u.ravel()], wu * (1 - u.ravel())
        return np.c_[u.ravel(), v.ravel(), 0 * u.ravel()], wu
    u, v, t = (a.ravel() for a in np.meshgrid(x, x, x, indexing="ij"))
    wu = np.einsum("i,j,k->ijk", w, w, w).ravel()
    if simplex == "tetra":
        return np.c_[u, v * (1 - u), t * (1 - u) * (1 - v)], wu * (1 - u) ** 2 * (1 - v)
    if simplex == "wedge":
        return np.c_[u, v * (1 - u), t], wu * (1 - u)
    return np.c_[u, v, t], wu


def own_integral(g, values):
    """The integral of the cells' own interpolant of `values` (point data),
    with VTK's shape functions and their derivatives (the Jacobian)."""
    total = 0.0
    for c in range(g.GetNumberOfCells()):
        cell = g.GetCell(c)
        d = cell.GetCellDimension()
        n = cell.GetNumberOfPoints()
        name = cell.GetClassName()
        simplex = "tetra" if "Tetra" in name else "wedge" if "Wedge" in name else ("Triangle" in name)
        xi, w = reference_rule(d, simplex)
        ids = [cell.GetPointId(k) for k in range(n)]
        x = points_of(g)[ids][:, :d]
        u = values[ids]
        for p, weight in zip(xi, w):
            functions = [0.0] * n
            derivatives = [0.0] * (n * d)
            cell.InterpolateFunctions(list(p), functions)
            cell.InterpolateDerivs(list(p), derivatives)
            jacobian = np.array(derivatives).reshape(d, n) @ x
            total += weight * abs(np.linalg.det(jacobian)) * np.dot(functions, u)
    return total


square = {"tri6": gmshmeshes.second_order("square", 0.23), "quad9": gmshmeshes.second_order("square", 0.31, True)}
square["lagrange triangles"] = as_lagrange(gmshmeshes.second_order("square", 0.27))
cube = {"tet10": gmshmeshes.second_order("cube", 0.4),
        "hex20": gmshmeshes.second_order("hexes", 0.34, incomplete=True),
        "hex27": gmshmeshes.second_order("hexes", 0.5),
        "wedge15": gmshmeshes.second_order("prisms", 0.34, incomplete=True),
        "wedge18": gmshmeshes.second_order("prisms", 0.5)}
cube["lagrange tetrahedra"] = as_lagrange(gmshmeshes.second_order("cube", 0.45))

# a. Quadratic fields at every node of straight second-order Inputs.
for family in (square, cube):
    for s in family:
        source = with_fields(family[s])
        for t in family:
            if s == t:
                continue
            error, valid = nodal_error(project(family[t], source), "Quadratic", quadratic)
            print("%s -> %s: quadratic field off by %.2g of its range" % (s, t, error))
            check(valid.all() and error <= 1e-9,
                  "%s -> %s: a quadratic field reproduced at every node (%.2g of its range, %d of %d valid)"
                  % (s, t, error, valid.sum(), len(valid)))

# b. A second-order Source onto a linear Input keeps the Source field's own integral.
for name, source_mesh, target_mesh in (
        ("tri6 -> triangles", square["tri6"], corners_only(gmshmeshes.second_order("square", 0.19))),
        ("quad9 -> triangles", square["quad9"], corners_only(gmshmeshes.second_order("square", 0.19))),
        ("tet10 -> tetrahedra", cube["tet10"], corners_only(gmshmeshes.second_order("cube", 0.3))),
        ("hex27 -> tetrahedra", cube["hex27"], corners_only(gmshmeshes.second_order("cube", 0.3)))):
    source = with_fields(source_mesh)
    exact = own_integral(source, point_array(source, "Quadratic"))
    out = project(target_mesh, source)
    target_integral = out.GetFieldData().GetArray("TargetIntegral_Quadratic").GetValue(0)
    source_integral = out.GetFieldData().GetArray("SourceIntegral_Quadratic").GetValue(0)
    print("%s: own integral %.15g, TargetIntegral_ %.15g, SourceIntegral_ %.15g"
          % (name, exact, target_integral, source_integral))
    check(abs(target_integral - exact) <= 1e-11 * abs(exact),
          "%s: the Source field's own integral kept (%.3g relative)" % (name, abs(target_integral / exact - 1)))
    check(abs(source_integral - exact) <= 1e-11 * abs(exact),
          "%s: SourceIntegral_ is the field's own integral (%.3g relative)" % (name, abs(source_integral / exact - 1)))

# c. Curved disks: linear fields exact at every node, constants constant.
disk = {"tri6": gmshmeshes.second_order("disk", 0.29), "quad9": gmshmeshes.second_order("disk", 0.23, True)}
for s in disk:
    source = with_fields(disk[s])
    for t in disk:
        for how, target in (("whole", disk[t]), ("in part", rebuilt(disk[t], transform=lambda x: x + [0.6, -0.3, 0]))):
            out = project(target, source)
            error, valid = nodal_error(out, "Linear", linear)
            print("disk %s -> %s (%s): linear field off by %.2g of its range" % (s, t, how, error))
            check(valid.any() and error <= 1e-9,
                  "disk %s -> %s (%s): a linear field exact at every node (%.2g)" % (s, t, how, error))
            covered = vtk_to_numpy(out.GetCellData().GetArray("CoveredFraction")) > 1e-9
            constant = vtk_to_numpy(out.GetCellData().GetArray("Constant"))[covered]
            check(covered.any() and np.max(np.abs(constant - 7.0)) <= 1e-12,
                  "disk %s -> %s (%s): constant cell data stays 7" % (s, t, how))

# d. Lumped mass on serendipity cells mixed with others falls back to the
# consistent one, with a warning; point labels (a region's id) onto
# second-order nodes.
def beside(a, b):
    """a and b moved by 1 along x, in one grid."""
    from vtkmodules.vtkFiltersCore import vtkAppendFilter
    append = vtkAppendFilter()
    append.AddInputData(a)
    append.AddInputData(gmshmeshes.moved(b, translate=(1.0, 0.0, 0.0)))
    append.Update()
    return append.GetOutput()


f, warnings = observed_filter("WarningEvent")
f.SetInputData(beside(cube["hex20"], cube["tet10"]))
f.SetSourceData(with_fields(beside(cube["tet10"], cube["tet10"])))
f.SetMassMatrix(1)
f.Update()
error, valid = nodal_error(f.GetOutput(), "Quadratic", quadratic)
check(valid.all() and error <= 1e-9, "lumped on hex20 + tet10: the consistent projection (%.2g)" % error)
check(sum("serendipity" in w for w in warnings) == 1, "lumped on hex20 + tet10: one warning (%r)" % warnings)
source = with_fields(square["tri6"])

x = points_of(source)
region = numpy_to_vtk((x[:, 0] > 0.5).astype(np.int32) * 2, deep=True)  # 0 left, 2 right
region.SetName("Region")
source.GetPointData().AddArray(region)
f = meshprojection.vtkMeshProjectionFilter()
f.SetInputData(square["quad9"])
f.SetSourceData(source)
f.AddCategoricalArray("Region")
f.SetLabelFractions(True)
f.Update()
out = f.GetOutput()
y = points_of(out)
label = point_array(out, "Region")
far = np.abs(y[:, 0] - 0.5) > 0.2
check(np.array_equal(label[far], (y[far, 0] > 0.5) * 2),
      "point labels on quad9 nodes: each node away from the interface takes its region's label")
check(set(np.unique(label)) <= {0, 2}, "point labels on quad9 nodes: only the labels given (%r)" % np.unique(label))
fractions = [out.GetPointData().GetArray(k) for k in range(out.GetPointData().GetNumberOfArrays())
             if "Fraction" in (out.GetPointData().GetArrayName(k) or "")]
check(fractions and all(0.0 <= vtk_to_numpy(a).min() and vtk_to_numpy(a).max() <= 1.0 for a in fractions),
      "point label fractions on quad9 nodes within [0, 1] (%d arrays)" % len(fractions))

finish()
