"""MassMatrix Lumped and PreserveBounds on second-order Inputs (point data
in the cells' own space, lumped and bounded in its Bernstein form:
Transfer/BernsteinForm.h), on Gmsh order-2 meshes (mpsupport.gmshmeshes):
6-node triangles, 9-node quadrilaterals, 10-node tetrahedra, 27-node
hexahedra and 18-node wedges, from linear and second-order Sources, and a
mixed Input of linear and quadratic triangles:

    a. Lumped: a constant stays constant at every node (1e-12), the integral
       over the covered part is the Source's (TargetIntegral_ against
       SourceIntegral_, 1e-12), and neither the old warnings nor any other
       is said; from a linear Source a positive field stays positive and a
       0/1 indicator gives values within [0, 1] at every node (the
       consistent projection leaves [0, 1] on the same pairs: the check can
       fail; a second-order Source's own field overshoots its nodes, and
       its lumped means with it: b bounds them);
    b. PreserveBounds (consistent mass): every node value within the
       Source's range, and the field inside every cell too (sampled with
       VTK's own shape functions; not the 18-node wedges, whose Python
       InterpolateFunctions takes 15 values), the integral kept (1e-12),
       also with Lumped; without it the same pairs overshoot;
    c. the accuracy of the lumped projection of a smooth field, against the
       consistent one and against the lumped projection onto the linear
       cells on the same corners and onto the split of the cells on all
       their nodes (printed; the lumped second-order error at most that of
       the linear cells on the same corners);
    d. serendipity cells (quad8 recombined by Gmsh: not parallelograms,
       the quad9 space with a hidden centre; hex20 and wedge15 on straight
       structured cells, VTK's own functions; hex20 warped into curved
       cells) and pyramid13 (a cube of pyramids about its subcubes'
       centres), in their form (BernsteinForm.h: 7/16 of a mid-edge node
       on each corner, 1/4 on the pyramid): Lumped alone, PreserveBounds
       alone and both: no warning, a constant stays constant (1e-12), the
       integral kept (1e-11), every node within the Source's range
       (Lumped alone too: these forms' coefficients are always clipped; a
       positive field positive), and on the affine hex20 and wedge15 (whose
       form's functions are non-negative) the field inside the cells too
       (sampled with VTK's shape functions); and the node error of a
       smooth field lumped against consistent and against lumped on the
       linear cells of its corners (printed; the lumped one between them).
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import (VTK_HEXAHEDRON, VTK_QUAD, VTK_QUADRATIC_TETRA, VTK_QUADRATIC_TRIANGLE,
                                           VTK_TETRA, VTK_TRIANGLE, VTK_TRIQUADRATIC_HEXAHEDRON,
                                           VTK_BIQUADRATIC_QUAD, VTK_BIQUADRATIC_QUADRATIC_WEDGE, VTK_QUADRATIC_PYRAMID,
                                           VTK_QUADRATIC_QUAD, VTK_QUADRATIC_HEXAHEDRON, VTK_QUADRATIC_WEDGE,
                                           VTK_PYRAMID, VTK_WEDGE,
                                           vtkUnstructuredGrid)

from mpsupport import gmshmeshes
from mpsupport.testing import check, finish, observed_filter


def points_of(g):
    return vtk_to_numpy(g.GetPoints().GetData())


def rebuilt(g, cell=lambda c, t, ids: (t, ids)):
    """A copy of g without arrays, each cell through cell(index, type, ids)."""
    out = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(points_of(g).copy(), deep=True))
    out.SetPoints(points)
    out.Allocate(g.GetNumberOfCells())
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        t, kept = cell(c, g.GetCellType(c), [ids.GetId(k) for k in range(ids.GetNumberOfIds())])
        out.InsertNextCell(t, len(kept), kept)
    return out


LINEAR_OF = {VTK_QUADRATIC_TRIANGLE: (VTK_TRIANGLE, 3), VTK_QUADRATIC_TETRA: (VTK_TETRA, 4),
             VTK_BIQUADRATIC_QUAD: (VTK_QUAD, 4), VTK_TRIQUADRATIC_HEXAHEDRON: (VTK_HEXAHEDRON, 8),
             VTK_QUADRATIC_QUAD: (VTK_QUAD, 4), VTK_QUADRATIC_HEXAHEDRON: (VTK_HEXAHEDRON, 8),
             VTK_QUADRATIC_WEDGE: (VTK_WEDGE, 6), VTK_QUADRATIC_PYRAMID: (VTK_PYRAMID, 5)}


def corners_only(g, which=lambda c: True):
    """g with the cells `which` selects linear on their corners."""
    def cell(c, t, ids):
        return (LINEAR_OF[t][0], ids[:LINEAR_OF[t][1]]) if which(c) else (t, ids)
    return rebuilt(g, cell)


SPLITS = {VTK_QUADRATIC_TRIANGLE: (VTK_TRIANGLE, [(0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5)]),
          VTK_BIQUADRATIC_QUAD: (VTK_QUAD, [(0, 4, 8, 7), (4, 1, 5, 8), (8, 5, 2, 6), (7, 8, 6, 3)]),
          VTK_QUADRATIC_TETRA: (VTK_TETRA, [(0, 4, 6, 7), (4, 1, 5, 8), (6, 5, 2, 9), (7, 8, 9, 3), (4, 9, 5, 8),
                                            (4, 9, 8, 7), (4, 9, 7, 6), (4, 9, 6, 5)])}


def split_on_nodes(g):
    """g's cells split into linear cells on all their nodes."""
    out = rebuilt(g)
    out.Reset()
    out.Allocate(8 * g.GetNumberOfCells())
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        t, parts = SPLITS[g.GetCellType(c)]
        for part in parts:
            out.InsertNextCell(t, len(part), [ids.GetId(k) for k in part])
    return out


def smooth(x):
    return np.sin(3.0 * x[:, 0]) + x[:, 1] ** 2 + np.cos(2.0 * x[:, 2])


def bump(x):
    """Positive everywhere, nearly 0 away from its centre."""
    return np.exp(-40.0 * np.sum((x - [0.4, 0.55, 0.45 * (np.ptp(x[:, 2]) > 0)]) ** 2, axis=1))


def with_fields(g):
    g = rebuilt(g)
    x = points_of(g)
    for name, values in (("Constant", np.full(len(x), 7.0)), ("Smooth", smooth(x)), ("Bump", bump(x)),
                         ("Step", (x[:, 0] + 0.3 * x[:, 1] > 0.52).astype(float))):
        a = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
        a.SetName(name)
        g.GetPointData().AddArray(a)
    return g


def project(target, source, lumped=False, bounded=False):
    f, warnings = observed_filter("WarningEvent")
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetMassMatrix(1 if lumped else 0)
    f.SetPreserveBounds(bounded)
    f.Update()
    return f.GetOutput(), warnings


def values(out, name):
    return vtk_to_numpy(out.GetPointData().GetArray(name))


def valid_of(out):
    return values(out, "vtkValidPointMask").astype(bool)


def used_points(g):
    """The points some cell of g uses (a mixed mesh's linear cells leave mid nodes unused)."""
    used = np.zeros(g.GetNumberOfPoints(), bool)
    for c in range(g.GetNumberOfCells()):
        cell = g.GetCell(c)
        used[[cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]] = True
    return used


def integrals(out, name):
    fd = out.GetFieldData()
    return fd.GetArray("TargetIntegral_" + name).GetValue(0), fd.GetArray("SourceIntegral_" + name).GetValue(0)


def check_bounded(pair, how, out, source, name, valid, tolerance):
    """Every valid node of `name` within the Source's range, its integral
    the Source's (to `tolerance`, relative)."""
    low, high = values(source, name).min(), values(source, name).max()
    u = values(out, name)[valid]
    slack = 1e-13 * (high - low)
    check(u.min() >= low - slack and u.max() <= high + slack,
          "%s %s: every node of %s within the Source's range (%.3g, %.3g in [%.3g, %.3g])"
          % (pair, how, name, u.min(), u.max(), low, high))
    got, wanted = integrals(out, name)
    check(abs(got - wanted) <= tolerance * max(1.0, abs(wanted)),
          "%s %s: the integral of %s kept (%.17g, Source %.17g)" % (pair, how, name, got, wanted))


def cell_samples(out, name, count=12):
    """The field inside every cell that has only valid nodes, at `count`
    random parametric points per cell, with VTK's shape functions."""
    rng = np.random.default_rng(3)
    u = values(out, name)
    valid = valid_of(out)
    samples = []
    for c in range(out.GetNumberOfCells()):
        cell = out.GetCell(c)
        ids = [cell.GetPointId(k) for k in range(cell.GetNumberOfPoints())]
        if not valid[ids].all() or cell.GetCellType() == VTK_BIQUADRATIC_QUADRATIC_WEDGE:
            continue
        name_ = cell.GetClassName()
        for _ in range(count):
            p = rng.random(3)
            if "Triangle" in name_ or "Tetra" in name_ or "Wedge" in name_:
                # a point of the simplex (of the wedge's triangle)
                k = 2 if ("Triangle" in name_ or "Wedge" in name_) else 3
                e = rng.exponential(size=k + 1)
                p[:k] = (e / e.sum())[:k]
            weights = [0.0] * len(ids)
            cell.InterpolateFunctions(list(p), weights)
            samples.append(np.dot(weights, u[ids]))
    return np.array(samples)


square = {"tri6": gmshmeshes.second_order("square", 0.23), "quad9": gmshmeshes.second_order("square", 0.31, True)}
cube = {"tet10": gmshmeshes.second_order("cube", 0.4), "hex27": gmshmeshes.second_order("hexes", 0.5),
        "wedge18": gmshmeshes.second_order("prisms", 0.5)}
tri = square["tri6"]
square["tri3 + tri6"] = corners_only(tri, lambda c: c % 3 == 0)
tet = cube["tet10"]
cube["tet4 + tet10"] = corners_only(tet, lambda c: c % 3 == 0)
sources = {
    "square": {"tri3": with_fields(corners_only(gmshmeshes.second_order("square", 0.17))),
               "tri6": with_fields(gmshmeshes.second_order("square", 0.19))},
    "cube": {"tet4": with_fields(corners_only(gmshmeshes.second_order("cube", 0.3))),
             "tet10": with_fields(gmshmeshes.second_order("cube", 0.33))},
}

overshoot_seen = 0
for family, targets in (("square", square), ("cube", cube)):
    for s, source in sources[family].items():
        for t, target in targets.items():
            pair = "%s -> %s" % (s, t)
            # a. Lumped.
            out, warnings = project(target, source, lumped=True)
            valid = valid_of(out)
            check(np.array_equal(valid, used_points(target)),
                  "%s lumped: every node of a cell valid (%d of %d)" % (pair, valid.sum(), len(valid)))
            off = np.max(np.abs(values(out, "Constant")[valid] - 7.0)) / 7.0
            check(off <= 1e-12, "%s lumped: a constant stays constant (%.2g)" % (pair, off))
            for name in ("Smooth", "Bump", "Step"):
                got, wanted = integrals(out, name)
                check(abs(got - wanted) <= 1e-12 * max(1.0, abs(wanted)),
                      "%s lumped: the integral of %s kept (%.17g, Source %.17g)" % (pair, name, got, wanted))
            if s in ("tri3", "tet4"):
                check(values(out, "Bump")[valid].min() > 0.0,
                      "%s lumped: a positive field stays positive (%.3g)" % (pair, values(out, "Bump")[valid].min()))
                step = values(out, "Step")[valid]
                check(step.min() >= -1e-14 and step.max() <= 1 + 1e-14,
                      "%s lumped: a 0/1 indicator within [0, 1] (%.3g, %.3g)" % (pair, step.min(), step.max()))
            check(not warnings, "%s lumped: no warning (%r)" % (pair, warnings))
            consistent, _ = project(target, source)
            cstep = values(consistent, "Step")[valid]
            overshoot_seen += cstep.min() < -1e-6 or cstep.max() > 1 + 1e-6
            # b. PreserveBounds (consistent mass), and Lumped with it.
            for lumped in (False, True):
                how = "bounds" + (" lumped" if lumped else "")
                out, warnings = project(target, source, lumped=lumped, bounded=True)
                valid = valid_of(out)
                for name in ("Step", "Bump", "Smooth"):
                    check_bounded(pair, how, out, source, name, valid, 1e-12)
                inside = cell_samples(out, "Step")
                check(t == "wedge18" or (inside.size and inside.min() >= -1e-13 and inside.max() <= 1 + 1e-13),
                      "%s %s: the field inside the cells within [0, 1] (%.3g, %.3g)"
                      % (pair, how, inside.min(initial=0), inside.max(initial=1)))
                off = np.max(np.abs(values(out, "Constant")[valid] - 7.0)) / 7.0
                check(off <= 1e-12, "%s %s: a constant stays constant (%.2g)" % (pair, how, off))
                check(not warnings, "%s %s: no warning (%r)" % (pair, how, warnings))
check(overshoot_seen > 0, "the consistent projection of the indicator leaves [0, 1] on some pair (%d)"
      % overshoot_seen)

# c. Accuracy of a smooth field at the nodes: lumped on the second-order
# Input, consistent on it, lumped on its linear split.
for family, t, target in (("square", "tri6", square["tri6"]), ("square", "quad9", square["quad9"]),
                          ("cube", "tet10", cube["tet10"]), ("cube", "hex27", cube["hex27"])):
    source = sources[family]["tri6" if family == "square" else "tet10"]
    x = points_of(target)
    exact = smooth(x)
    scale = np.ptp(exact)
    errors = {}
    runs = [("lumped", target, True), ("consistent", target, False), ("linear lumped", corners_only(target), True)]
    if target.GetCellType(0) in SPLITS:
        runs.append(("split lumped", split_on_nodes(target), True))
    for how, mesh, lumped in runs:
        out, _ = project(mesh, source, lumped=lumped)
        valid = valid_of(out) & used_points(mesh)
        errors[how] = np.max(np.abs(values(out, "Smooth") - exact)[valid]) / scale
    print("%s <- %s, smooth field, largest node error / range: lumped %.3g, consistent %.3g, lumped on the "
          "linear cells of its corners %.3g, lumped on its split on all its nodes %s"
          % (t, "tri6" if family == "square" else "tet10", errors["lumped"], errors["consistent"],
             errors["linear lumped"], "%.3g" % errors["split lumped"] if "split lumped" in errors else "-"))
    check(errors["consistent"] < errors["lumped"] <= errors["linear lumped"],
          "%s: lumped error between the consistent one and the linear cells' lumped one (%r)" % (t, errors))

# d. Serendipity cells and pyramids: lumped and bounded in their signed form.
def warped(g):
    """g with its points moved inside the unit cube (the boundary kept): curved cells."""
    g = rebuilt(g)
    x = points_of(g)
    bubble = np.sin(np.pi * x[:, 0]) * np.sin(np.pi * x[:, 1]) * np.sin(np.pi * x[:, 2])
    moved = x + 0.06 * bubble[:, None] * np.array([1.0, -0.7, 0.5])
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(moved), deep=True))
    g.SetPoints(points)
    return g


def pyramids(k):
    """The unit cube in k^3 subcubes, each in the 6 pyramid13 on its faces about its centre."""
    ids = {}
    coords = []

    def point(p):
        key = tuple(np.round(np.asarray(p) * 4 * k).astype(int))
        if key not in ids:
            ids[key] = len(coords)
            coords.append(np.asarray(p, float))
        return ids[key]

    cells = []
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    for i in range(k):
        for j in range(k):
            for m in range(k):
                o = np.array([i, j, m], float) / k
                corner = [o + np.array([a, b, c], float) / k for a in (0, 1) for b in (0, 1) for c in (0, 1)]
                centre = o + 0.5 / k
                for f in faces:
                    base = [corner[v] for v in f]
                    if np.dot(np.cross(base[1] - base[0], base[3] - base[0]), centre - base[0]) < 0:
                        base = base[::-1]
                    nodes = base + [centre]
                    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 4), (2, 4), (3, 4)]
                    cells.append([point(p) for p in nodes] + [point(0.5 * (nodes[a] + nodes[b])) for a, b in edges])
    g = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(coords), deep=True))
    g.SetPoints(points)
    for c in cells:
        g.InsertNextCell(VTK_QUADRATIC_PYRAMID, 13, c)
    return g


signed = {"quad8": gmshmeshes.second_order("square", 0.31, True, True),
          "hex20": gmshmeshes.second_order("hexes", 0.5, incomplete=True),
          "hex20 warped": warped(gmshmeshes.second_order("hexes", 0.34, incomplete=True)),
          "wedge15": gmshmeshes.second_order("prisms", 0.5, incomplete=True),
          "pyramid13": pyramids(2)}
for t, target in signed.items():
    family = "square" if t == "quad8" else "cube"
    for s, source in sources[family].items():
        pair = "%s -> %s" % (s, t)
        for how, lumped, bounded in (("lumped", True, False), ("bounds", False, True),
                                     ("bounds lumped", True, True)):
            out, warnings = project(target, source, lumped=lumped, bounded=bounded)
            valid = valid_of(out)
            check(np.array_equal(valid, used_points(target)),
                  "%s %s: every node of a cell valid (%d of %d)" % (pair, how, valid.sum(), len(valid)))
            off = np.max(np.abs(values(out, "Constant")[valid] - 7.0)) / 7.0
            check(off <= 1e-12, "%s %s: a constant stays constant (%.2g)" % (pair, how, off))
            for name in ("Step", "Bump", "Smooth"):
                check_bounded(pair, how, out, source, name, valid, 1e-11)
            bump = values(out, "Bump")[valid]
            check(bump.min() > 0.0, "%s %s: a positive field stays positive (%.3g)" % (pair, how, bump.min()))
            if t in ("hex20", "wedge15"):
                # (affine cells: their form's functions are non-negative)
                inside = cell_samples(out, "Step")
                check(inside.size and inside.min() >= -1e-13 and inside.max() <= 1 + 1e-13,
                      "%s %s: the field inside the cells within [0, 1] (%.3g, %.3g)"
                      % (pair, how, inside.min(initial=0), inside.max(initial=1)))
            check(not warnings, "%s %s: no warning (%r)" % (pair, how, warnings))
    # The node error of a smooth field: lumped against consistent and
    # against lumped on the linear cells of its corners.
    source = sources[family]["tri6" if family == "square" else "tet10"]
    x = points_of(target)
    exact = smooth(x)
    errors = {}
    for how, mesh, lumped in (("lumped", target, True), ("consistent", target, False),
                              ("linear lumped", corners_only(target), True)):
        out, _ = project(mesh, source, lumped=lumped)
        valid = valid_of(out) & used_points(mesh)
        errors[how] = np.max(np.abs(values(out, "Smooth") - exact)[valid]) / np.ptp(exact)
    print("%s <- %s, smooth field, largest node error / range: lumped %.3g, consistent %.3g, lumped on the "
          "linear cells of its corners %.3g" % (t, "tri6" if family == "square" else "tet10", errors["lumped"],
                                                errors["consistent"], errors["linear lumped"]))
    check(errors["consistent"] < errors["lumped"] <= errors["linear lumped"],
          "%s: lumped error between the consistent one and the linear cells' lumped one (%r)" % (t, errors))

finish()
