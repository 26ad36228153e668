"""Integer arrays with many distinct values (ids) and label arrays with many
labels, on triangulated planes (the target moved so that part of it is
uncovered), checked against the overlap matrix M_ts (GetMatrix):

    a. CATEGORICAL_AUTOMATIC, Generate Ids' "Ids" (vtkIdTypeArray, one value
       per cell and per point, more than MaximumAutomaticLabels = 1024) on
       a Source of 45,000 cells: projected as numbers, the same values as
       the array converted to double, one warning naming it and its count;
       small memory and time (its labels, side by side, would be 16 GB);
    b. CATEGORICAL_SELECTED with "Ids" named, 4,500 cells, all distinct: each
       covered target cell takes the Source cell of largest overlap (ties:
       the smallest id), with a small memory peak (the dense indicators
       and weights would be 200 MB) and a warning of the many labels; more
       labels than 256: no fractions array, a warning naming it, the
       labels still there;
    c. 40 labels (more than one block of 16): the labels and the fractions
       (M_ts summed per label, over the row) to 1e-12, as the dense rule;
       the same with 17 labels (blocks of 15 and 2).
"""
import resource
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_DOUBLE, VTK_ID_TYPE, VTK_INT
from vtkmodules.vtkFiltersCore import vtkIdFilter, vtkTriangleFilter
from vtkmodules.vtkFiltersGeneral import vtkTransformFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkCommonTransforms import vtkTransform

from meshprojection import operator_matrices, vtkMeshProjectionFilter  # noqa: F401
from mpsupport.testing import check, finish, observed_filter

FILL = -1


def plane(nx, ny, move=(0.0, 0.0), turn=0.0):
    """The unit square in nx x ny quads, triangulated, turned and moved."""
    p = vtkPlaneSource()
    p.SetResolution(nx, ny)
    tri = vtkTriangleFilter()
    tri.SetInputConnection(p.GetOutputPort())
    t = vtkTransform()
    t.Translate(move[0], move[1], 0.0)
    t.RotateZ(turn)
    moved = vtkTransformFilter()
    moved.SetTransform(t)
    moved.SetInputConnection(tri.GetOutputPort())
    moved.Update()
    out = moved.GetOutput().NewInstance()
    out.ShallowCopy(moved.GetOutput())
    return out


def with_ids(mesh):
    ids = vtkIdFilter()
    ids.SetInputData(mesh)
    ids.SetPointIds(True)
    ids.SetCellIds(True)
    ids.SetPointIdsArrayName("Ids")
    ids.SetCellIdsArrayName("Ids")
    ids.Update()
    out = ids.GetOutput().NewInstance()
    out.ShallowCopy(ids.GetOutput())
    return out


def project(target, source, **properties):
    f, warnings = observed_filter("WarningEvent")
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(bool(properties.get("KeepMatrices")))
    for name, value in properties.items():
        getattr(f, name if name.startswith("Add") else "Set" + name)(value)
    f.Update()
    return f, f.GetOutput(), warnings


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


target = plane(30, 30, move=(0.213, 0.137), turn=7.0)

# b first (the memory peak of the process is still the baseline's).
source_b = with_ids(plane(50, 45))
n_b = source_b.GetNumberOfCells()
before = peak_mb()
f_b, out_b, warn_b = project(target, source_b, CategoricalMode=1, AddCategoricalArray="Ids",
                             LabelFractions=True, PointDataTarget=0, KeepMatrices=True)
grown = peak_mb() - before
ids_b = out_b.GetCellData().GetArray("Ids")
check(ids_b is not None and ids_b.GetDataType() == VTK_ID_TYPE,
      "b. SELECTED: 'Ids' is a label array of the Source's type (%s)"
      % (ids_b.GetClassName() if ids_b else None))
check(grown < 60, "b. %d labels: the memory peak grows by %.1f MB (< 60)" % (n_b, grown))
check(any("cell label array 'Ids' has %d labels: they are projected 16 at a time" % n_b in w
          for w in warn_b), "b. a warning names the many labels of 'Ids' and their blocks")
check(out_b.GetCellData().GetArray("Ids_Fractions") is None,
      "b. more than 256 labels: no fractions array")
check(any("cell label array 'Ids' has %d labels, more than 256" % n_b in w for w in warn_b),
      "b. the fractions warning names the cell array 'Ids' and its count")
check(out_b.GetPointData().GetArray("Ids_Fractions") is None
      and any("point label array 'Ids' has %d labels" % source_b.GetNumberOfPoints() in w
              for w in warn_b),
      "b. and the point array 'Ids'")
_, m_ts, valid = operator_matrices(f_b, "cells_to_cells")
m_ts = m_ts.tocsr()
got = vtk_to_numpy(ids_b)
decided = wrong = 0
for i in range(m_ts.shape[0]):
    row = m_ts.getrow(i)
    if not valid[i]:
        wrong += got[i] != FILL
        continue
    order = np.lexsort((row.indices, -row.data))
    top = row.data[order[0]]
    second = row.data[order[1]] if len(order) > 1 else 0.0
    if top - second <= 1e-9 * top:
        continue  # too close to call here
    decided += 1
    wrong += got[i] != row.indices[order[0]]
check(wrong == 0 and decided > 1000 and np.count_nonzero(~valid) > 0,
      "b. %d of %d decided cells take another id than the Source cell of largest overlap"
      % (wrong, decided))

# a. AUTOMATIC: "Ids" is an id array, projected as numbers.
source_a = with_ids(plane(150, 150))
real = numpy_to_vtk(vtk_to_numpy(source_a.GetCellData().GetArray("Ids")).astype(float), deep=True)
real.SetName("IdsReal")
source_a.GetCellData().AddArray(real)
before = peak_mb()
start = time.perf_counter()
f_a, out_a, warn_a = project(target, source_a)
seconds = time.perf_counter() - start
grown = peak_mb() - before
n_a = source_a.GetNumberOfCells()
ids_a = out_a.GetCellData().GetArray("Ids")
check(ids_a is not None and ids_a.GetDataType() == VTK_DOUBLE,
      "a. AUTOMATIC: 'Ids' (%d distinct values) is projected as numbers (%s)"
      % (n_a, ids_a.GetClassName() if ids_a else None))
check(np.array_equal(vtk_to_numpy(ids_a), vtk_to_numpy(out_a.GetCellData().GetArray("IdsReal")),
                     equal_nan=True),
      "a. the numbers are the array's as doubles")
said = [w for w in warn_a if "'Ids' looks like an id array (%d distinct values" % n_a in w]
check(len(said) == 1 and "CategoricalArrays" in said[0] and "CATEGORICAL_SELECTED" in said[0],
      "a. one warning names the cell array 'Ids', its count and what to do")
check(any("point array 'Ids' looks like an id array (%d distinct values"
          % source_a.GetNumberOfPoints() in w for w in warn_a),
      "a. and the point array 'Ids'")
check(not any("holds integers" in w for w in warn_a), "a. no other integer warning for it")
check(grown < 200 and seconds < 30,
      "a. %d cells: the memory peak grows by %.1f MB (< 200), %.1f s" % (n_a, grown, seconds))

# c. 40 and 17 labels, a region per label: the dense rule, block by block.
source_c = plane(40, 40)
centers = np.array([source_c.GetCell(c).GetBounds() for c in range(source_c.GetNumberOfCells())])
cx = 0.5 * (centers[:, 0] + centers[:, 1])
cy = 0.5 * (centers[:, 2] + centers[:, 3])
for count in (40, 17):
    # Stripes that cross the target's cells, numbered out of order.
    band = np.floor((cx + 0.37 * cy + 0.5) * count / 1.37).astype(int) % count
    material = (band * 7919) % 1000 - 300
    source = source_c.NewInstance()
    source.ShallowCopy(source_c)
    a = numpy_to_vtk(material.astype(np.int32), deep=True, array_type=VTK_INT)
    a.SetName("Material")
    source.GetCellData().AddArray(a)
    f_c, out_c, _ = project(target, source, LabelFractions=True, PointDataTarget=0,
                            KeepMatrices=True)
    labels = np.unique(material)
    check(len(labels) == count, "c. %d labels in the Source" % len(labels))
    _, m_ts, valid = operator_matrices(f_c, "cells_to_cells")
    m_ts = m_ts.tocsr()
    weights = np.column_stack([np.asarray(m_ts[:, material == m].sum(axis=1)).ravel()
                               for m in labels])
    got = vtk_to_numpy(out_c.GetCellData().GetArray("Material"))
    frac = vtk_to_numpy(out_c.GetCellData().GetArray("Material_Fractions"))
    want = weights[valid] / weights[valid].sum(axis=1, keepdims=True)
    check(frac.shape == (target.GetNumberOfCells(), count)
          and np.max(np.abs(frac[valid] - want)) <= 1e-12,
          "c. %d labels: the fractions == M_ts summed per label over the row (%.3g)"
          % (count, np.max(np.abs(frac[valid] - want))))
    top = np.sort(want, axis=1)
    clear = top[:, -1] - top[:, -2] > 1e-9
    rule = labels[np.argmax(want, axis=1)]
    check(np.array_equal(got[valid][clear], rule[clear]) and np.count_nonzero(clear) > 500
          and np.all(got[~valid] == FILL),
          "c. %d labels: each covered cell takes the label of largest weight (%d cells)"
          % (count, np.count_nonzero(clear)))
    mixed = np.count_nonzero((want > 1e-9).sum(axis=1) > 1)
    check(mixed > 100, "c. %d labels: %d target cells meet several labels" % (count, mixed))
finish()
