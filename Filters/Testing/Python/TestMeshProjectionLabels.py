"""Categorical arrays (labels) on Gmsh pairs whose regions do not follow
the target's cells, checked against an independent polygon overlap
computation (Sutherland-Hodgman clipping of each target triangle by each
Source triangle, in the test):

    a. cells: every covered target cell takes the label of largest overlap
       (ties: the smallest), uncovered ones the fill label; the fractions
       sum to 1 and, weighed by the covered area, give each label's Source
       area over the covered part to 1e-12; no value that is not a Source
       label; the output keeps the Source array's type (int, unsigned char);
    b. points: the label of largest weight int phi_i chi_L, for a cell label
       and for a point label (the row of M_ts);
    c. CategoricalMode: SELECTED with nothing named projects integers as
       numbers (with the "holds integers" warning), a real array named is
       a label array; no warning for labels in the default mode;
    d. FillLabel on an unsigned array that cannot hold -1;
    e. a composite Input, a composite Source (two blocks) and a second
       execution on the kept operator give the same labels;
    f. the labels come from the overlap matrix: GetMatrix(CELLS_TO_CELLS,
       MIXED_MASS)'s columns summed per label are the overlap areas;
    g. CellDataReconstruction and Extrapolation leave labels alone: the same
       labels (a label has no gradient), the fill label where uncovered;
    h. 3D: Gmsh tetrahedra of a box, moved, with four materials: each
       target cell's label is the one of largest overlap volume, from the
       intersection pieces (OutputIntersections) summed per label, and the
       fractions keep each label's volume over the covered part to 1e-12.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import (VTK_DOUBLE, VTK_INT, VTK_SHORT, VTK_UNSIGNED_CHAR)
from vtkmodules.vtkCommonDataModel import vtkMultiBlockDataSet

from meshprojection import vtkMeshProjectionFilter
from mpsupport import gmshmeshes
from mpsupport.testing import check, finish, observed_filter

FILL = -1


def triangles(mesh):
    conn = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return vtk_to_numpy(mesh.GetPoints().GetData())[:, :2].astype(float), conn


def region(x, y):
    """The material of a point: three regions whose boundaries cross both meshes' cells."""
    if (x - 0.62) ** 2 + (y - 0.58) ** 2 < 0.07:
        return 3
    return 0 if y < 0.31 + 0.27 * x else 7


def with_labels(mesh):
    x, tri = triangles(mesh)
    centroids = x[tri].mean(axis=1)
    material = np.array([region(*c) for c in centroids], dtype=np.int32)
    out = mesh.NewInstance()
    out.ShallowCopy(mesh)
    a = numpy_to_vtk(material, deep=True, array_type=VTK_INT)
    a.SetName("MaterialId")
    out.GetCellData().AddArray(a)
    cls = numpy_to_vtk((material == 3).astype(np.uint8) * 200 + 5, deep=True,
                       array_type=VTK_UNSIGNED_CHAR)
    cls.SetName("Class")
    out.GetCellData().AddArray(cls)
    tag = np.array([1 + int(px > 0.45) + 2 * int(py > 0.55 - 0.3 * px) for px, py in x],
                   dtype=np.int16)
    t = numpy_to_vtk(tag, deep=True, array_type=VTK_SHORT)
    t.SetName("NodeTag")
    out.GetPointData().AddArray(t)
    real = numpy_to_vtk(material.astype(float) * 0.5, deep=True)
    real.SetName("RealLabel")
    out.GetCellData().AddArray(real)
    return out, x, tri, material, tag


def clip(polygon, a, b, c):
    """`polygon` (counterclockwise) clipped by the counterclockwise triangle abc."""
    out = list(polygon)
    for p, q in ((a, b), (b, c), (c, a)):
        if not out:
            break
        edge = q - p

        def inside(v):
            return edge[0] * (v[1] - p[1]) - edge[1] * (v[0] - p[0]) >= 0

        cur, out = out, []
        for i, v in enumerate(cur):
            w = cur[(i + 1) % len(cur)]
            if inside(v):
                out.append(v)
            if inside(v) != inside(w):
                d = w - v
                t = (edge[0] * (p[1] - v[1]) - edge[1] * (p[0] - v[0])) / (edge[0] * d[1] - edge[1] * d[0])
                out.append(v + t * d)
    return out


def ccw(x, tri):
    a, b, c = x[tri[0]], x[tri[1]], x[tri[2]]
    return tri if (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0 else tri[[0, 2, 1]]


def barycentric(x, tri, p):
    a, b, c = x[tri]
    m = np.array([[b[0] - a[0], c[0] - a[0]], [b[1] - a[1], c[1] - a[1]]])
    l1, l2 = np.linalg.solve(m, p - a)
    return np.array([1 - l1 - l2, l1, l2])


def overlaps(xt, tt, xs, ts):
    """Per (target cell, source cell) meeting: the area and, per corner pair
    (a of the target cell, b of the source cell), int phi_a psi_b over the
    overlap (fan triangles, edge-midpoint rule: exact for the quadratic)."""
    smin, smax = xs[ts].min(axis=1), xs[ts].max(axis=1)
    result = []
    for t, tcell in enumerate(tt):
        tcell = ccw(xt, tcell)
        lo, hi = xt[tcell].min(axis=0), xt[tcell].max(axis=0)
        near = np.nonzero(np.all(smax >= lo - 1e-12, axis=1) & np.all(smin <= hi + 1e-12, axis=1))[0]
        for s in near:
            scell = ccw(xs, ts[s])
            poly = clip([xt[i] for i in tcell], *xs[scell])
            if len(poly) < 3:
                continue
            area = 0.0
            m = np.zeros((3, 3))
            for k in range(1, len(poly) - 1):
                p0, p1, p2 = poly[0], poly[k], poly[k + 1]
                a = 0.5 * ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]))
                area += a
                for mid in ((p0 + p1) / 2, (p1 + p2) / 2, (p2 + p0) / 2):
                    m += a / 3 * np.outer(barycentric(xt, tcell, mid), barycentric(xs, scell, mid))
            if area > 0:
                result.append((t, s, tcell, scell, area, m))
    return result


def winner(weights, labels):
    """The independent rule: largest weight; None when the two largest are too close to call."""
    order = np.argsort(-weights, kind="stable")
    top = weights[order[0]]
    if top <= 0:
        return FILL, True
    second = weights[order[1]] if len(order) > 1 else 0.0
    return labels[order[0]], top - second > 1e-9 * top


def project(target, source, **properties):
    f, warnings = observed_filter("WarningEvent")
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.SetLabelFractions(True)
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f, f.GetOutput(), warnings


# The pair: Source triangles (Frontal), target triangles (Delaunay, coarser),
# moved by (0.3, 0.1) so that part of it is uncovered.
source_mesh, xs, ts, material, tag = with_labels(gmshmeshes.planar(0.07, algorithm=6))
target = gmshmeshes.moved(gmshmeshes.planar(0.1, algorithm=5), translate=(0.3, 0.1, 0.0))
xt, tt = triangles(target)
f, out, warnings = project(target, source_mesh, PointDataTarget=3, CellDataTarget=3)
cd, pd = out.GetCellData(), out.GetPointData()
pieces = overlaps(xt, tt, xs, ts)
nt, npt = len(tt), len(xt)
mats = np.unique(material)
tags = np.unique(tag)

# a. Cells from cell labels.
area = np.zeros((nt, len(mats)))
for t, s, _, _, a, _ in pieces:
    area[t, np.searchsorted(mats, material[s])] += a
labels = cd.GetArray("MaterialId")
check(labels is not None and labels.GetDataType() == VTK_INT,
      "MaterialId to cells keeps vtkIntArray (%s)" % (labels.GetClassName() if labels else None))
got = vtk_to_numpy(labels)
valid = vtk_to_numpy(cd.GetArray("vtkValidCellMask")).astype(bool)
mixed = wrong = decided = 0
for t in range(nt):
    want, clear = winner(area[t], mats)
    mixed += np.count_nonzero(area[t] > 0) > 1
    if clear:
        decided += 1
        wrong += got[t] != want
check(wrong == 0, "a. %d of %d cells take another label than the largest overlap" % (wrong, decided))
check(mixed >= 15, "a. the regions cross target cells (%d mixed cells)" % mixed)
check(set(got[valid]) <= set(mats), "a. labels of covered cells are Source labels: %s" % set(got[valid]))
check(np.all(got[~valid] == FILL) and np.count_nonzero(~valid) > 20,
      "a. %d uncovered cells get the fill label" % np.count_nonzero(~valid))
check(np.all(valid == (area.sum(axis=1) > 0)), "a. the covered cells are those the clipping finds")
frac = vtk_to_numpy(cd.GetArray("MaterialId_Fractions"))
names = [cd.GetArray("MaterialId_Fractions").GetComponentName(k) for k in range(len(mats))]
check(names == [str(m) for m in mats], "a. the fractions' components are named by the labels: %s" % names)
check(np.max(np.abs(frac[valid].sum(axis=1) - 1)) <= 1e-12, "a. fractions sum to 1 on covered cells")
check(np.all(np.isnan(frac[~valid])), "a. fractions of uncovered cells are the fill value (NaN)")
covered = area.sum(axis=1)
for k, m in enumerate(mats):
    kept = float(np.sum(covered[valid] * frac[valid, k]))
    want = float(area[:, k].sum())
    check(abs(kept - want) <= 1e-12 * want,
          "a. label %d: covered-area-weighted fractions %r == its Source area over the covered part %r"
          % (m, kept, want))
unsigned = cd.GetArray("Class")
check(unsigned is not None and unsigned.GetDataType() == VTK_UNSIGNED_CHAR,
      "a. Class keeps vtkUnsignedCharArray")
cls = vtk_to_numpy(unsigned)
check(set(cls[valid]) <= {5, 205}, "a. Class's labels are Source labels: %s" % set(cls[valid]))
check(np.all(cls[~valid] == 255), "d. FillLabel -1 in an unsigned char array: 255, the type's largest")

# b. Points: a cell label (int phi_i over each label's overlap) and a point label (M_ts's row).
wcell = np.zeros((npt, len(mats)))
wpoint = np.zeros((npt, len(tags)))
wpoint_cells = np.zeros((nt, len(tags)))
for t, s, tcell, scell, a, m in pieces:
    wcell[tcell, np.searchsorted(mats, material[s])] += m.sum(axis=1)
    for b in range(3):
        k = np.searchsorted(tags, tag[scell[b]])
        wpoint[tcell, k] += m[:, b]
        wpoint_cells[t, k] += m[:, b].sum()
pvalid = vtk_to_numpy(pd.GetArray("vtkValidPointMask")).astype(bool)
for name, weights, labels_of, data, what in (
        ("MaterialId", wcell, mats, pd, "cell label to points"),
        ("NodeTag", wpoint, tags, pd, "point label to points"),
        ("NodeTag", wpoint_cells, tags, cd, "point label to cells")):
    array = data.GetArray(name)
    check(array is not None and array.GetDataType() in (VTK_INT, VTK_SHORT),
          "b. %s keeps its integer type" % what)
    values = vtk_to_numpy(array)
    # (Its own mask where its transfer's valid points differ: the fringe drops
    # points on the transfers with numbers, RealLabel's.)
    own = data.GetArray(("vtkValidPointMask_" if data is pd else "vtkValidCellMask_") + name)
    mask = vtk_to_numpy(own).astype(bool) if own else (pvalid if data is pd else valid)
    wrong = decided = 0
    for i in range(len(values)):
        if not mask[i]:
            check(values[i] == FILL, "b. %s: uncovered %d has the fill label" % (what, i))
            continue
        want, clear = winner(weights[i], labels_of)
        if clear:
            decided += 1
            wrong += values[i] != want
    check(wrong == 0 and decided > 50, "b. %s: %d of %d take another label than the largest weight"
          % (what, wrong, decided))
    fractions = vtk_to_numpy(data.GetArray(name + "_Fractions"))
    check(np.max(np.abs(fractions[mask].sum(axis=1) - 1)) <= 1e-12, "b. %s: fractions sum to 1" % what)
    share = weights[mask] / weights[mask].sum(axis=1)[:, None]
    check(np.max(np.abs(fractions[mask] - share)) <= 1e-9,
          "b. %s: the fractions are the weights' shares (%.3g)" % (what, np.max(np.abs(fractions[mask] - share))))
check(not any("holds integers" in str(w) for w in warnings), "c. no integer warning for labels")

# c. CategoricalMode SELECTED: nothing named, the integers as numbers (warned); a real array named.
f2, out2, warnings2 = project(target, source_mesh, CategoricalMode=1)
numbers = out2.GetCellData().GetArray("MaterialId")
check(numbers.GetDataType() == VTK_DOUBLE and any("'MaterialId' holds integers" in w for w in warnings2),
      "c. SELECTED, nothing named: MaterialId projected as numbers")
f3 = vtkMeshProjectionFilter()
f3.SetInputData(target)
f3.SetSourceData(source_mesh)
f3.SetCategoricalMode(f3.CATEGORICAL_SELECTED)
f3.AddCategoricalArray("RealLabel")
f3.AddCategoricalArray("MaterialId")
f3.Update()
real = f3.GetOutput().GetCellData().GetArray("RealLabel")
check(real.GetDataType() == VTK_DOUBLE and
      np.array_equal(vtk_to_numpy(real)[valid], got[valid] * 0.5),
      "c. a real array named in CategoricalArrays is projected as labels (the same winners)")
check(np.array_equal(vtk_to_numpy(f3.GetOutput().GetCellData().GetArray("MaterialId")), got),
      "c. MaterialId named: the same labels as by default")

# e. A composite Input (two copies) and a second execution on the kept operator.
blocks = vtkMultiBlockDataSet()
blocks.SetNumberOfBlocks(2)
blocks.SetBlock(0, target)
blocks.SetBlock(1, target)
f4 = vtkMeshProjectionFilter()
f4.SetInputData(blocks)
f4.SetSourceData(source_mesh)
f4.SetKeepMatrices(True)
f4.Update()
for b in range(2):
    leaf = f4.GetOutput().GetBlock(b).GetCellData().GetArray("MaterialId")
    check(leaf.GetDataType() == VTK_INT and np.array_equal(vtk_to_numpy(leaf), got),
          "e. composite block %d: the same labels" % b)
f4.SetFillLabel(-7)
f4.Update()
check(f4.GetOperatorReused(), "e. the second execution reuses the kept operator")
again = vtk_to_numpy(f4.GetOutput().GetBlock(0).GetCellData().GetArray("MaterialId"))
check(np.array_equal(again[valid], got[valid]) and np.all(again[~valid] == -7),
      "e. the kept operator serves the labels again (FillLabel -7 where uncovered)")

# e. A composite Source: the Source in two blocks (by cell parity) is one mesh.
from mpsupport.meshes import extract  # noqa: E402
halves = vtkMultiBlockDataSet()
halves.SetNumberOfBlocks(2)
parity = np.arange(source_mesh.GetNumberOfCells()) % 2
for b in range(2):
    halves.SetBlock(b, extract(source_mesh, parity == b))
f5, out5, _ = project(target, halves)
check(np.array_equal(vtk_to_numpy(out5.GetCellData().GetArray("MaterialId")), got),
      "e. a composite Source (two blocks) gives the same cell labels")

# f. GetMatrix: M_ts of cells to cells, its columns summed per label: the areas above.
from meshprojection import operator_matrices  # noqa: E402
m_tt, m_ts, _ = operator_matrices(f4, "cells_to_cells")
by_label = np.column_stack([np.asarray(m_ts[:, material == m].sum(axis=1)).ravel() for m in mats])
check(np.max(np.abs(by_label - area)) <= 1e-12 * area.max(),
      "f. GetMatrix's M_ts summed per label == the overlap areas (%.3g)" % np.max(np.abs(by_label - area)))

# g. Reconstruction (DP1 indicators) and Extrapolation.
f6, out6, _ = project(target, source_mesh, CellDataReconstruction=1, Extrapolation=2)
check(np.array_equal(vtk_to_numpy(out6.GetCellData().GetArray("MaterialId")), got),
      "g. with CellDataReconstruction and Extrapolation: the same cell labels, the fill label where uncovered")
f6f = vtk_to_numpy(out6.GetCellData().GetArray("MaterialId_Fractions"))
check(np.max(np.abs(f6f[valid] - frac[valid])) <= 1e-12,
      "g. with CellDataReconstruction: the same fractions (%.3g)" % np.max(np.abs(f6f[valid] - frac[valid])))

# h. 3D, against the intersection pieces' volumes summed per label.
box_source = gmshmeshes.volume("box", 0.11)
box_target = gmshmeshes.moved(gmshmeshes.volume("box", 0.14), translate=(0.23, 0.11, 0.07))
xs3 = vtk_to_numpy(box_source.GetPoints().GetData())
tets = vtk_to_numpy(box_source.GetCells().GetConnectivityArray()).reshape(-1, 4)
c3 = xs3[tets].mean(axis=1)
material3 = np.where(c3[:, 2] > 0.55 + 0.2 * c3[:, 0], 4,
                     np.where((c3[:, 0] - 0.5) ** 2 + (c3[:, 1] - 0.5) ** 2 < 0.09, 2,
                              np.where(c3[:, 1] > 0.6 - 0.3 * c3[:, 0], 1, 0))).astype(np.int32)
labelled3 = box_source.NewInstance()
labelled3.ShallowCopy(box_source)
m3 = numpy_to_vtk(material3, deep=True, array_type=VTK_INT)
m3.SetName("MaterialId")
labelled3.GetCellData().AddArray(m3)
f7, out7, _ = project(box_target, labelled3, OutputIntersections=True)
pieces3 = f7.GetOutput(2).GetCellData()
pt = vtk_to_numpy(pieces3.GetArray("TargetCellId"))
ps = vtk_to_numpy(pieces3.GetArray("SourceCellId"))
pv = vtk_to_numpy(pieces3.GetArray("Volume"))
mats3 = np.unique(material3)
volume = np.zeros((box_target.GetNumberOfCells(), len(mats3)))
np.add.at(volume, (pt, np.searchsorted(mats3, material3[ps])), pv)
got3 = vtk_to_numpy(out7.GetCellData().GetArray("MaterialId"))
valid3 = vtk_to_numpy(out7.GetCellData().GetArray("vtkValidCellMask")).astype(bool)
wrong = decided = mixed = 0
for t in range(len(got3)):
    want, clear = winner(volume[t], mats3)
    mixed += np.count_nonzero(volume[t] > 0) > 1
    if clear:
        decided += 1
        wrong += got3[t] != want
check(wrong == 0 and decided > 300 and mixed > 50,
      "h. 3D: %d of %d cells (%d mixed) take another label than the largest overlap volume"
      % (wrong, decided, mixed))
check(np.all(got3[~valid3] == FILL) and np.count_nonzero(~valid3) > 0, "h. 3D: uncovered cells get the fill label")
frac3 = vtk_to_numpy(out7.GetCellData().GetArray("MaterialId_Fractions"))
covered3 = volume.sum(axis=1)
for k, m in enumerate(mats3):
    kept = float(np.sum(covered3[valid3] * frac3[valid3, k]))
    want = float(volume[:, k].sum())
    check(abs(kept - want) <= 1e-12 * want,
          "h. 3D label %d: covered-volume-weighted fractions %r == its Source volume over the covered part %r"
          % (m, kept, want))
finish()
