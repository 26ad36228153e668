"""The filter's other services on second-order cells (Gmsh order-2 meshes,
mpsupport.gmshmeshes.second_order):

    a. a kept operator: a change of the Source's field only reuses it, and
       gives a fresh filter's values (1e-10 of the range);
    b. GetMatrix: M_tt's functions are the Input's points, M_ts's the
       Source's; solved (with the fringe's extension P) they give the
       output, on an Input the Source covers and on one it covers in part;
    c. OutputIntersections: every piece names its parents; the pieces'
       measures sum to the covered measure, and per Input cell to its
       CoveredFraction of the cell's measure (straight cells);
    d. progress reaches 1 on a large tet10 pair, and an abort stops the
       run cleanly (Input as it came, a warning), the next run whole;
    e. hostile input, on the Source and on the Input: a mid node with an id
       out of range or negative, a missing mid node, a mid node at a NaN
       point, a node named twice, two mid nodes swapped, a mid node pulled
       beyond its cell: an error that names the cell, and the output is
       Input as it came.
"""
import numpy as np
import scipy.sparse.linalg
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid

import meshprojection
from meshprojection import fringe_extension, operator_matrices
from mpsupport import gmshmeshes
from mpsupport.fringe import with_fields
from mpsupport.testing import check, finish, mortar, observed_filter

so = gmshmeshes.second_order
moved = gmshmeshes.moved


def array(out, name, cells=False):
    data = out.GetCellData() if cells else out.GetPointData()
    return vtk_to_numpy(data.GetArray(name))


def corner_measures(g):
    """Per cell of g (straight 6-node triangles, 10-node tetrahedra) the measure of its corners' simplex."""
    x = vtk_to_numpy(g.GetPoints().GetData())
    out = []
    for c in range(g.GetNumberOfCells()):
        cell = g.GetCell(c)
        d = cell.GetCellDimension()
        p = x[[cell.GetPointId(k) for k in range(d + 1)]]
        edges = (p[1:] - p[0])[:, :d]
        out.append(abs(np.linalg.det(edges)) / (2.0 if d == 2 else 6.0))
    return np.array(out)


# a. A field-only change: the operator reused, a fresh filter's values.
target = so("cube", 0.2)
source = with_fields(moved(so("hexes", 0.25, False, True), translate=(0.2, 0.1, -0.15)))
f = meshprojection.vtkMeshProjectionFilter()
f.SetInputData(target)
f.SetSourceData(source)
f.SetCacheOperator(True)
for step in range(3):  # (data, not a time series: the second execution keeps an assembled operator)
    f.Modified()
    f.Update()
check(f.GetOperatorReused(), "kept operator: reused when nothing changed")
s = array(source, "s")
s[:] = np.cos(s) + 2.0
source.GetPointData().GetArray("s").Modified()
f.Update()
check(f.GetOperatorReused(), "a field-only change: the operator reused")
fresh = mortar(target, source, pieces=False).GetOutput()
valid = array(fresh, "vtkValidPointMask").astype(bool)
kept, again = array(f.GetOutput(), "s"), array(fresh, "s")
off = np.max(np.abs(kept - again)[valid]) / np.ptp(again[valid])
# (A one-off execution sums its right-hand side directly, a kept operator
# through M_ts: round-off apart, through the second-order mass matrix's
# conditioning.)
check(np.array_equal(array(f.GetOutput(), "vtkValidPointMask").astype(bool), valid) and off <= 1e-10,
      "a field-only change: a fresh filter's values (%.2g of the range off)" % off)

# b. GetMatrix on second-order Inputs: functions are the datasets' points.
for name, target, source_mesh, fringe in (
        ("tri6 <- quad9, covered", so("square", 0.1), moved(so("square", 0.12, True), translate=(-0.1, -0.1, 0)), False),
        ("tet10 <- hex20, covered", moved(so("cube", 0.2), translate=(0.3, 0.2, 0.25)),
         moved(so("hexes", 0.25, False, True), translate=(0.2, 0.1, 0.15)), False),
        ("quad9 <- tri6, in part", moved(so("square", 0.12, True), translate=(0.4, 0.1, 0)), so("square", 0.1), True),
        ("hex27 <- tet10, in part", moved(so("hexes", 0.25), translate=(-0.33, 0.41, 0.07)), so("cube", 0.2), True)):
    if not fringe:  # (the Source covering the Input: shrink the Input into it)
        x = vtk_to_numpy(source_mesh.GetPoints().GetData())
        lo, hi = x.min(axis=0), x.max(axis=0)
        t = vtkUnstructuredGrid()
        t.DeepCopy(target)
        y = vtk_to_numpy(t.GetPoints().GetData())
        y[:] = lo + 0.05 * (hi - lo) + 0.9 * (y - y.min(axis=0)) / np.maximum(np.ptp(y, axis=0), 1e-30) * (hi - lo)
        y[:, 2] = 0.0 if target.GetCell(0).GetCellDimension() == 2 else y[:, 2]
        target = t
    source = with_fields(source_mesh)
    f = mortar(target, source, pieces=False, CacheOperator=True)
    out = f.GetOutput()
    m_tt, m_ts, reached = operator_matrices(f)
    check(m_tt.shape == (target.GetNumberOfPoints(),) * 2 and
          m_ts.shape == (target.GetNumberOfPoints(), source.GetNumberOfPoints()),
          "%s: M_tt %s, M_ts %s over the datasets' points" % (name, m_tt.shape, m_ts.shape))
    valid = array(out, "vtkValidPointMask").astype(bool)
    P = fringe_extension(f)
    b = m_ts @ array(source, "s")
    if P.shape[0]:
        free = P.getnnz(axis=0) > 0
        A = (P.T @ m_tt @ P).tocsc()[free][:, free]
        u = P[:, free] @ scipy.sparse.linalg.spsolve(A, (P.T @ b)[free])
    else:
        u = np.full(len(valid), np.nan)
        u[reached] = scipy.sparse.linalg.spsolve(m_tt.tocsc()[reached][:, reached], b[reached])
    off = np.max(np.abs(u - array(out, "s"))[valid]) / np.ptp(array(out, "s")[valid])
    check(valid.any() and (valid.all() or fringe) and off <= 1e-9,
          "%s: the matrices give the output (%.2g of the range off, %d of %d valid)"
          % (name, off, valid.sum(), len(valid)))

# c. OutputIntersections on second-order pairs.
for name, target, source_mesh, port in (
        ("tri6 <- quad9", moved(so("square", 0.1), translate=(0.31, 0.17, 0)), so("square", 0.12, True), 1),
        ("tet10 <- hex20", moved(so("cube", 0.25), translate=(0.27, 0.13, 0.21)), so("hexes", 0.25, False, True), 2)):
    source = with_fields(source_mesh)
    f = mortar(target, source, pieces=True)
    pieces = f.GetOutputDataObject(port)
    measure = "Area" if port == 1 else "Volume"
    t_ids, s_ids = array(pieces, "TargetCellId", True), array(pieces, "SourceCellId", True)
    sizes = array(pieces, measure, True)
    check(pieces.GetNumberOfCells() > 0 and t_ids.min() >= 0 and t_ids.max() < target.GetNumberOfCells() and
          s_ids.min() >= 0 and s_ids.max() < source.GetNumberOfCells(),
          "%s: %d pieces, each naming an Input and a Source cell" % (name, pieces.GetNumberOfCells()))
    covered = f.GetCoveredMeasure()
    check(abs(sizes.sum() - covered) <= 1e-12 * covered,
          "%s: the pieces' measures sum to the covered measure (%.15g, %.15g)" % (name, sizes.sum(), covered))
    per_cell = np.bincount(t_ids, weights=sizes, minlength=target.GetNumberOfCells())
    expected = array(f.GetOutput(), "CoveredFraction", True) * corner_measures(target)
    off = np.max(np.abs(per_cell - expected)) / corner_measures(target).max()
    check(off <= 1e-12, "%s: per Input cell, its CoveredFraction of its measure (%.2g off)" % (name, off))

# d. Progress and abort on a large tet10 pair.
target = so("cube", 0.1)
source = with_fields(moved(so("hexes", 0.1, False, True), translate=(0.2, 0.1, -0.15)))
f, warnings = observed_filter("WarningEvent", "ErrorEvent")
progress = []
f.AddObserver("ProgressEvent", lambda obj, event: progress.append(obj.GetProgress()))
f.SetInputData(target)
f.SetSourceData(source)
f.Update()
out = f.GetOutput()
check(progress and max(progress) == 1.0 and all(b >= a for a, b in zip(progress, progress[1:])),
      "large tet10 pair (%d cells): progress rises to 1 (%d events)" % (target.GetNumberOfCells(), len(progress)))
# The run after the abort meets these meshes again, so its operator is
# formed (a kept one): its values are those of an uninterrupted run that
# meets them again, the right-hand sides of M_ts rather than the one-off
# sums, which differ from them by round-off.
f.Modified()
f.Update()
whole = array(f.GetOutput(), "s").copy()


def abort_halfway(obj, event):
    if obj.GetProgress() > 0.3:
        obj.SetAbortExecute(1)


tag = f.AddObserver("ProgressEvent", abort_halfway)
del warnings[:]
f.Modified()
f.Update()
out = f.GetOutput()
check(out.GetNumberOfPoints() == target.GetNumberOfPoints() and out.GetPointData().GetArray("s") is None and
      any("bort" in w for w in warnings), "an abort: Input as it came, a warning (%r)" % warnings[-1:])
f.RemoveObserver(tag)
f.SetAbortExecute(0)
f.Modified()
f.Update()
check(np.array_equal(array(f.GetOutput(), "s"), whole, equal_nan=True), "after an abort: the next run whole")


# e. Hostile input on either port: an error naming the cell, Input passed through.
def spoiled(g, how, cell):
    """A copy of g with cell `cell` spoiled `how`."""
    x = vtk_to_numpy(g.GetPoints().GetData()).copy()
    cells = [(g.GetCellType(c), [g.GetCell(c).GetPointId(k) for k in range(g.GetCell(c).GetNumberOfPoints())])
             for c in range(g.GetNumberOfCells())]
    ids = cells[cell][1]
    last = len(ids) - 1
    if how == "a mid node's id out of range":
        ids[last] = len(x) + 7
    elif how == "a negative mid node id":
        ids[last] = -3
    elif how == "a missing mid node":
        del ids[last]
    elif how == "a mid node at a NaN point":
        x[ids[last]] = np.nan
    elif how == "a node named twice":
        ids[last] = ids[0]
    elif how == "two mid nodes swapped":
        ids[4], ids[5] = ids[5], ids[4]
    elif how == "a mid node beyond its cell":
        x[ids[last]] = x[ids[0]] + 3.0 * (x[ids[0]] - x[ids[last]])
    out = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x), deep=True))
    out.SetPoints(points)
    for t, c in cells:
        out.InsertNextCell(t, len(c), c)
    return out


says = {"a mid node's id out of range": "cell %d refers to point", "a negative mid node id": "cell %d refers to point -3",
        "a missing mid node": "cell %d has %d points where its type needs",
        "a mid node at a NaN point": "cell %d (%s) has a node with a NaN or infinite coordinate",
        "a node named twice": "cell %d (%s) names one node twice", "two mid nodes swapped": "cell %d (%s) is folded",
        "a mid node beyond its cell": "cell %d (%s) is folded"}
for mesh_name, mesh, other in (("tet10", so("cube", 0.3), so("hexes", 0.34, False, True)),
                               ("tri6", so("square", 0.25), so("square", 0.3, True)),
                               ("hex20", so("hexes", 0.34, False, True), so("cube", 0.3))):
    for how, words in says.items():
        bad = spoiled(mesh, how, 5)
        # (A shared node spoils every cell around it: the error names the first.)
        first = min(c for c in range(mesh.GetNumberOfCells()) if mesh.GetCell(5).GetPointId(
            mesh.GetCell(5).GetNumberOfPoints() - 1) in [mesh.GetCell(c).GetPointId(k) for k in range(
                mesh.GetCell(c).GetNumberOfPoints())]) if how in ("a mid node at a NaN point",
                                                                  "a mid node beyond its cell") else 5
        expected = words % ((first, mesh.GetCell(5).GetNumberOfPoints() - 1) if "%d points" in words else
                            (first, mesh.GetCell(first).GetClassName()) if "%s" in words else (first,))
        for port in ("Source", "Input"):
            f, texts = observed_filter("ErrorEvent")
            target, source = (other, with_fields(bad)) if port == "Source" else (bad, with_fields(other))
            f.SetInputData(target)
            f.SetSourceData(source)
            f.Update()
            out = f.GetOutput()
            text = " ".join(texts)
            check(port in text and expected in text,
                  "%s, %s, as %s: an error naming the cell (%r in %r)" % (mesh_name, how, port, expected, texts[:1]))
            check(out.GetNumberOfPoints() == target.GetNumberOfPoints() and
                  out.GetPointData().GetArray("vtkValidPointMask") is None,
                  "%s, %s, as %s: Input passed through" % (mesh_name, how, port))

finish()
