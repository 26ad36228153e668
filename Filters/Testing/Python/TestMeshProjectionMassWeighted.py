"""Mass-weighted projection (DensityArray, MassWeightedArrays), on Gmsh pairs
of the unit square (VTK Python). q is projected so that the integral of
rho q is kept: rho q and rho are projected, q is their ratio.

    a. cell data, a target that covers part of the Source: the sum over
       target cells of covered measure x rho_t x q_t equals the Source's
       integral of rho q over the covered part, computed independently from
       the intersection pieces, to 1e-12; the plain projection of q differs
       and does not keep it; TargetIntegral_/SourceIntegral_ are of rho q;
    b. point data, meshes of the same square: the nodal quadrature of
       rho_t q_t (the integral of the projected product) equals the exact
       integral of the Source's P1 rho q, to 1e-12; to cells too;
    c. a constant q stays constant (cells, points, points to cells, with
       reconstruction, with PreserveBounds);
    d. the density guard: where the projected density is zero (a Source
       with rho = 0 on part of it), q is invalid, with its own count said;
    e. NaN in q or in rho: a hole, the rest conserved;
    f. PreserveBounds: q within its Source range; the density not selected
       is projected but not written, with the same q; cells to points;
       Extrapolation (finite, within q's range, the valid values unchanged);
    g. errors (a missing density, a three-component one, a density with no
       finite value, an array of the other association): a warning by
       name, q projected plainly;
    h. a time series: the operators are reused and give a fresh run's result;
    i. two facetizations of a sphere: with ConserveSourceIntegral the written
       rho_t q_t keeps the Source's integral of rho q to 1e-12 (cells; points:
       the product's integral) and a constant stays constant.
"""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

from meshprojection import vtkMeshProjectionFilter
from mpsupport import gmshmeshes
from mpsupport.testing import check, finish, observed_filter

TIGHT = 1e-12


def rho(x):
    return 1.0 + 0.5 * np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + x[:, 0]


def q(x):
    return np.cos(2 * x[:, 0]) + x[:, 1] ** 2


def centres(g):
    x = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return x[conn].mean(axis=1), x, conn


def with_arrays(mesh, cells=None, points=None):
    """A shallow copy of `mesh` with the given cell and point arrays (name -> values)."""
    copy = mesh.NewInstance()
    copy.ShallowCopy(mesh)
    for data, arrays in ((copy.GetCellData(), cells or {}), (copy.GetPointData(), points or {})):
        for name, values in arrays.items():
            a = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float64), deep=True)
            a.SetName(name)
            data.AddArray(a)
    return copy


def run(target, source, density="rho", weighted=(), observe=False, **properties):
    if observe:
        f, texts = observed_filter("WarningEvent")
    else:
        f, texts = vtkMeshProjectionFilter(), []
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.SetDensityArray(density)
    for name in weighted:
        f.AddMassWeightedArray(name)
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f, texts


def cells_of(f, name):
    a = f.GetOutput().GetCellData().GetArray(name)
    return None if a is None else vtk_to_numpy(a)


def points_of(f, name):
    a = f.GetOutput().GetPointData().GetArray(name)
    return None if a is None else vtk_to_numpy(a)


def field(f, name):
    a = f.GetOutput().GetFieldData().GetArray(name)
    return None if a is None else a.GetValue(0)


def relative(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


SOURCE = gmshmeshes.planar(0.07)
TARGET = gmshmeshes.planar(0.11)  # the same square, another mesh
SHIFTED = gmshmeshes.moved(TARGET, translate=(0.31, 0.17, 0.0))  # covers part of the Source
SC, SX, SCONN = centres(SOURCE)
TC, TX, TCONN = centres(TARGET)


def covered_source_integral(f, values):
    """Sum over the intersection pieces of area x the Source cell's value."""
    pieces = f.GetOutput(1).GetCellData()
    area = vtk_to_numpy(pieces.GetArray("Area"))
    cell = vtk_to_numpy(pieces.GetArray("SourceCellId"))
    return float(np.sum(area * values[cell]))


def covered_target_integral(f, target, values):
    covered = vtk_to_numpy(f.GetOutput().GetCellData().GetArray("CoveredFraction")) * nodal_weights(target)[1]
    return float(np.sum(np.where(covered > 0, covered * values, 0.0)))


def test_cells():
    source = with_arrays(SOURCE, cells={"rho": rho(SC), "q": q(SC), "one": np.full(len(SC), 2.5)})
    f, _ = run(SHIFTED, source, OutputIntersections=True)
    exact = covered_source_integral(f, rho(SC) * q(SC))
    kept = covered_target_integral(f, SHIFTED, cells_of(f, "rho") * cells_of(f, "q"))
    check(relative(kept, exact) < TIGHT, "cells: integral of rho_t q_t %.16g, Source's over the covered part %.16g"
          % (kept, exact))
    check(relative(field(f, "TargetIntegral_q (cell data)"), exact) < TIGHT,
          "cells: TargetIntegral_q is that of rho q (%r, %r)" % (field(f, "TargetIntegral_q (cell data)"), exact))
    check(relative(field(f, "SourceIntegral_q (cell data)"), exact) < TIGHT, "cells: SourceIntegral_q is that of rho q")
    valid = vtk_to_numpy(f.GetOutput().GetCellData().GetArray("vtkValidCellMask")) == 1
    one = cells_of(f, "one")[valid]
    check(np.max(np.abs(one - 2.5)) < 2.5 * TIGHT, "cells: a constant stays constant (off by %g)"
          % np.max(np.abs(one - 2.5)))
    # The plain projection of q: another field, which does not keep the integral of rho q.
    plain, _ = run(SHIFTED, source, density="", OutputIntersections=True)
    differ = np.max(np.abs(cells_of(plain, "q")[valid] - cells_of(f, "q")[valid]))
    check(differ > 1e-4, "cells: the plain projection differs (by %g)" % differ)
    plainly = covered_target_integral(plain, SHIFTED, cells_of(plain, "rho") * cells_of(plain, "q"))
    check(relative(plainly, exact) > 1e-6, "cells: the plain projection does not keep it (%g)"
          % relative(plainly, exact))
    # Only q named: 'one' is projected plainly (a constant stays one all the same).
    named, _ = run(SHIFTED, source, weighted=["q"])
    check(np.array_equal(cells_of(named, "q"), cells_of(f, "q"), equal_nan=True), "cells: q named gives the same q")
    check(field(named, "TargetIntegral_one (cell data)") == field(plain, "TargetIntegral_one (cell data)"),
          "cells: an array not named is projected plainly")
    # Cells to points: the ratio of two P1 projections of cell data; a constant stays.
    both, _ = run(SHIFTED, source, CellDataTarget=3)
    on_points = vtk_to_numpy(both.GetOutput().GetPointData().GetArray("vtkValidPointMask")) == 1
    check(np.max(np.abs(points_of(both, "one")[on_points] - 2.5)) < 2.5 * 1e-11,
          "cells to points: a constant stays constant")
    check(np.array_equal(cells_of(both, "q"), cells_of(f, "q"), equal_nan=True),
          "cells to points and cells: the cells' q as to cells only")
    # Extrapolation: every target cell gets a value, within q's range.
    ext, _ = run(SHIFTED, source, Extrapolation=1)
    qe = cells_of(ext, "q")
    check(np.isfinite(qe).all() and qe.min() >= q(SC).min() and qe.max() <= q(SC).max(),
          "cells, extrapolated: finite, within q's range")
    check(np.array_equal(qe[valid], cells_of(f, "q")[valid]), "cells, extrapolated: the valid values as without")
    # Reconstruction: conservation and constants as well.
    for mode in (1, 2):
        r, _ = run(SHIFTED, source, CellDataReconstruction=mode)
        check(relative(field(r, "TargetIntegral_q (cell data)"), field(r, "SourceIntegral_q (cell data)")) < TIGHT,
              "cells, reconstruction %d: the integral of rho q is kept" % mode)
        ok = vtk_to_numpy(r.GetOutput().GetCellData().GetArray("vtkValidCellMask")) == 1
        check(np.max(np.abs(cells_of(r, "one")[ok] - 2.5)) < 1e-11,
              "cells, reconstruction %d: a constant stays constant" % mode)
        k = covered_target_integral(r, SHIFTED, cells_of(r, "rho") * cells_of(r, "q"))
        check(relative(k, field(r, "SourceIntegral_q (cell data)")) < TIGHT,
              "cells, reconstruction %d: integral of rho_t q_t kept" % mode)


def nodal_weights(grid):
    """Per point, the integral of its hat function over a triangle mesh."""
    x = vtk_to_numpy(grid.GetPoints().GetData())
    conn = vtk_to_numpy(grid.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    e1, e2 = x[conn[:, 1]] - x[conn[:, 0]], x[conn[:, 2]] - x[conn[:, 0]]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    w = np.zeros(len(x))
    for k in range(3):
        np.add.at(w, conn[:, k], area / 3)
    return w, area


def test_points():
    source = with_arrays(SOURCE, points={"rho": rho(SX), "q": q(SX), "one": np.full(len(SX), -1.5)})
    _, area = nodal_weights(SOURCE)
    # The exact integral of the Source's P1 rho q (its nodal product, interpolated).
    exact = float(np.sum(area * (rho(SX) * q(SX))[SCONN].mean(axis=1)))
    w, _ = nodal_weights(TARGET)
    f, _ = run(TARGET, source, PointDataTarget=3)
    kept = float(np.sum(w * points_of(f, "rho") * points_of(f, "q")))
    check(relative(kept, exact) < TIGHT, "points: nodal integral of rho_t q_t %.16g, Source's %.16g" % (kept, exact))
    check(relative(field(f, "TargetIntegral_q"), exact) < TIGHT, "points: TargetIntegral_q is that of rho q")
    check(np.max(np.abs(points_of(f, "one") + 1.5)) < 1.5 * 1e-11, "points: a constant stays constant")
    check(np.max(np.abs(cells_of(f, "one") + 1.5)) < 1.5 * 1e-11, "points to cells: a constant stays constant")
    tc = covered_target_integral(f, TARGET, cells_of(f, "rho") * cells_of(f, "q"))
    check(relative(tc, exact) < TIGHT, "points to cells: integral of rho_t q_t kept (%g)" % relative(tc, exact))
    plain, _ = run(TARGET, source, density="")
    plainly = float(np.sum(w * points_of(plain, "rho") * points_of(plain, "q")))
    check(relative(plainly, exact) > 1e-6, "points: the plain projection does not keep it (%g)"
          % relative(plainly, exact))
    # A target that covers part (the fringe aggregated): the projected
    # product is the plain projection of the product, with its integrals.
    g, _ = run(SHIFTED, source)
    product = with_arrays(SOURCE, points={"rhoq": rho(SX) * q(SX), "rho": rho(SX)})
    h, _ = run(SHIFTED, product, density="")
    for which in ("Source", "Target"):
        check(relative(field(g, which + "Integral_q"), field(h, which + "Integral_rhoq")) < TIGHT,
              "points, part covered: %sIntegral_q is the plain one of rho q" % which)
    valid = points_of(g, "vtkValidPointMask") == 1
    ratio = points_of(h, "rhoq")[valid] / points_of(h, "rho")[valid]
    check(np.max(np.abs(points_of(g, "q")[valid] - ratio)) < 1e-12 * np.max(np.abs(ratio)),
          "points, part covered: q is the ratio of the plain projections")
    check(np.max(np.abs(points_of(g, "one")[valid] + 1.5)) < 1.5 * 1e-11,
          "points, part covered: a constant stays constant")


def test_guard():
    # rho = 0 left of x = 0.5 (exactly, cell by cell), positive right of it.
    r = np.where(SC[:, 0] < 0.5, 0.0, SC[:, 0] - 0.4)
    source = with_arrays(SOURCE, cells={"rho": r, "q": q(SC)})
    f, texts = run(TARGET, source, observe=True)
    rt = cells_of(f, "rho")
    qt = cells_of(f, "q")
    small = rt <= 1e-10 * r.max()
    check(small.sum() > 10, "guard: target cells with no density (%d)" % small.sum())
    check(np.all(np.isnan(qt[small])) and np.all(np.isfinite(qt[~small])),
          "guard: q is NaN exactly where the projected density is zero")
    mask = f.GetOutput().GetCellData().GetArray("vtkValidCellMask_q")
    check(mask is not None and np.array_equal(vtk_to_numpy(mask) == 1, ~small),
          "guard: q has a mask of its own")
    said = [t for t in texts if "mass-weighted array 'q'" in t]
    check(len(said) == 1 and ("): %d Input cells have" % small.sum()) in said[0],
          "guard: the count (%d) is said once: %r" % (small.sum(), said))
    check(relative(field(f, "TargetIntegral_q (cell data)"), field(f, "SourceIntegral_q (cell data)")) < TIGHT,
          "guard: the integral of rho q is kept")
    # Points beyond the Source extrapolated next to guarded ones: finite
    # (the guarded ones alone get the fill value).
    rp = np.where(SX[:, 0] < 0.5, 0.0, SX[:, 0] - 0.4)
    points = with_arrays(SOURCE, points={"rho": rp, "q": q(SX)})
    e, texts = run(SHIFTED, points, observe=True, Extrapolation=1)
    qe = points_of(e, "q")
    own = points_of(e, "vtkValidPointMask_q")
    guarded = (own == 0) & (points_of(e, "vtkValidPointMask") == 1) if own is not None else np.zeros(len(qe), bool)
    check(guarded.sum() > 0 and np.array_equal(np.isnan(qe), guarded),
          "guard, extrapolated points: NaN exactly at the %d guarded points (%d NaN)"
          % (guarded.sum(), np.isnan(qe).sum()))
    valid = points_of(e, "vtkValidPointMask") == 1
    kept = qe[valid & ~guarded]
    beyond = qe[~valid]
    check(len(beyond) > 0 and beyond.min() >= kept.min() - 1e-12 and beyond.max() <= kept.max() + 1e-12,
          "guard, extrapolated points: within the valid values' range")
    plain, _ = run(SHIFTED, points)
    check(np.array_equal(qe[valid & ~guarded], points_of(plain, "q")[valid & ~guarded]),
          "guard, extrapolated points: the valid values as without")
    # With a fill value instead of NaN.
    g, _ = run(TARGET, source, FillWithNaN=False, FillValue=-7.0)
    check(np.all(cells_of(g, "q")[small] == -7.0), "guard: the fill value")


def test_nan():
    qq = np.where(np.hypot(SC[:, 0] - 0.6, SC[:, 1] - 0.6) < 0.2, np.nan, q(SC))
    r = np.where(np.hypot(SC[:, 0] - 0.8, SC[:, 1] - 0.4) < 0.15, np.nan, rho(SC))
    source = with_arrays(SOURCE, cells={"rho": r, "q": qq})
    f, _ = run(SHIFTED, source, OutputIntersections=True)
    product = r * qq
    good = np.isfinite(product)
    exact = covered_source_integral(f, np.where(good, product, 0.0))
    check(relative(field(f, "TargetIntegral_q (cell data)"), exact) < TIGHT,
          "NaN: the integral of rho q over the rest (%r, %r)" % (field(f, "TargetIntegral_q (cell data)"), exact))
    valid_q = f.GetOutput().GetCellData().GetArray("vtkValidCellMask_q")
    check(valid_q is not None and np.isnan(cells_of(f, "q")[vtk_to_numpy(valid_q) == 0]).all(),
          "NaN: a hole in q, marked")
    rho_valid = f.GetOutput().GetCellData().GetArray("vtkValidCellMask_rho")
    if valid_q is not None and rho_valid is not None:
        q_out, rho_out = vtk_to_numpy(valid_q) == 0, vtk_to_numpy(rho_valid) == 0
        check(np.all(q_out[rho_out]) and q_out.sum() > rho_out.sum() > 0,
              "NaN: q's hole holds rho's (%d, %d)" % (q_out.sum(), rho_out.sum()))
    else:
        check(False, "NaN: rho has a mask of its own")


def test_bounds_and_hidden():
    points = with_arrays(SOURCE, points={"rho": rho(SX), "s": np.where(SX[:, 0] > 0.5, 1.0, 0.0)})
    f, _ = run(TARGET, points, PreserveBounds=True)
    qt = points_of(f, "s")
    check(qt.min() >= 0.0 and qt.max() <= 1.0, "bounds: s in [0, 1] (%g, %g)" % (qt.min(), qt.max()))
    unbounded, _ = run(TARGET, points)
    check(points_of(unbounded, "s").max() > 1.0 + 1e-3 or points_of(unbounded, "s").min() < -1e-3,
          "bounds: without them s leaves [0, 1] (%g, %g)" % (points_of(unbounded, "s").min(),
                                                            points_of(unbounded, "s").max()))
    # Cells to cells: a ratio of means with the same weights, within [0, 1] without bounds.
    source = with_arrays(SOURCE, cells={"rho": rho(SC), "q": np.where(SC[:, 0] > 0.5, 1.0, 0.0)})
    unbounded, _ = run(TARGET, source)
    qt = cells_of(unbounded, "q")
    check(qt.min() >= 0.0 and qt.max() <= 1.0 + 1e-15, "bounds: cell q in [0, 1] (%g, %g)" % (qt.min(), qt.max()))
    # The density not selected: projected, not written; the same q.
    hidden = vtkMeshProjectionFilter()
    hidden.SetInputData(TARGET)
    hidden.SetSourceData(source)
    hidden.SetDensityArray("rho")
    hidden.GetCellDataArraySelection().DisableArray("rho")
    hidden.Update()
    check(hidden.GetOutput().GetCellData().GetArray("rho") is None, "hidden: rho not written")
    check(np.array_equal(vtk_to_numpy(hidden.GetOutput().GetCellData().GetArray("q")), cells_of(unbounded, "q")),
          "hidden: the same q")


def test_errors():
    source = with_arrays(SOURCE, cells={"rho": rho(SC), "q": q(SC), "nan": np.full(len(SC), np.nan)},
                         points={"p": q(SX), "v3": np.ones((len(SX), 3))})
    plain, _ = run(TARGET, source, density="")
    for density, words in (("nope", "'nope' is not an array of Source"),
                           ("v3", "'v3' is not one-component"),
                           ("nan", "'nan' has no finite non-zero value")):
        f, texts = run(TARGET, source, density=density, observe=True)
        check(any(words in t for t in texts), "errors: %s said: %r" % (density, texts))
        check(np.array_equal(cells_of(f, "q"), cells_of(plain, "q")), "errors: %s: q projected plainly" % density)
    f, texts = run(TARGET, source, weighted=["q", "p", "missing"], observe=True)
    check(any("point array 'p' is projected without mass weighting" in t for t in texts),
          "errors: a point array with a cell density said: %r" % texts)
    check(any("'missing', which is not an array of Source" in t for t in texts), "errors: a missing name said")
    check(np.array_equal(points_of(f, "p"), points_of(plain, "p")), "errors: p projected plainly")


def test_time_series():
    f = vtkMeshProjectionFilter()
    f.SetInputData(TARGET)
    f.SetDensityArray("rho")
    results = []
    for step in range(3):
        source = with_arrays(SOURCE, cells={"rho": rho(SC) + step, "q": q(SC) * (1 + step)})
        f.SetSourceData(source)
        f.Update()
        results.append(vtk_to_numpy(f.GetOutput().GetCellData().GetArray("q")).copy())
        fresh, _ = run(TARGET, source)
        check(np.max(np.abs(results[-1] - cells_of(fresh, "q"))) < 1e-12, "time series: step %d as a fresh run" % step)
    check(f.GetOperatorReused(), "time series: the operators are reused")


def triangles_of(g):
    x = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    area = 0.5 * np.linalg.norm(np.cross(x[conn[:, 1]] - x[conn[:, 0]], x[conn[:, 2]] - x[conn[:, 0]]), axis=1)
    return x, conn, x[conn].mean(axis=1), area


def test_sphere():
    """Two facetizations of a sphere (areas differ by O(h^2)): with
    ConserveSourceIntegral the written density times the written q keeps the
    Source's integral of rho q and a constant stays constant."""
    source_mesh = gmshmeshes.surface("sphere", 0.15)
    target = gmshmeshes.surface("sphere", 0.2, algorithm=1)
    sx, sconn, sc, sa = triangles_of(source_mesh)
    _, _, _, ta = triangles_of(target)

    def density(x):
        return 1.5 + x[:, 0] * x[:, 1] + 0.3 * x[:, 2]

    cells = with_arrays(source_mesh, cells={"rho": density(sc), "q": q(sc), "one": np.full(len(sc), 3.0)})
    whole = float(np.sum(sa * density(sc) * q(sc)))
    for conserve in (False, True):
        f, _ = run(target, cells, ConserveSourceIntegral=conserve)
        covered = vtk_to_numpy(f.GetOutput().GetCellData().GetArray("CoveredFraction")) * ta
        kept = float(np.sum(covered * cells_of(f, "rho") * cells_of(f, "q")))
        check(relative(field(f, "SourceIntegral_q (cell data)"), whole) < TIGHT,
              "sphere: SourceIntegral_q is the Source's integral of rho q")
        check(np.max(np.abs(cells_of(f, "one") - 3.0)) < 3e-12, "sphere, conserve %d: a constant stays" % conserve)
        if conserve:
            check(relative(kept, whole) < TIGHT, "sphere, conserved: integral of rho_t q_t %.16g, Source's %.16g"
                  % (kept, whole))
        else:
            check(relative(kept, field(f, "TargetIntegral_q (cell data)")) < TIGHT,
                  "sphere: integral of rho_t q_t is TargetIntegral_q")
    points = with_arrays(source_mesh, points={"rho": density(sx), "q": q(sx), "one": np.full(len(sx), 3.0)})
    exact = float(np.sum(sa * (density(sx) * q(sx))[sconn].mean(axis=1)))
    f, _ = run(target, points, ConserveSourceIntegral=True)
    check(relative(field(f, "TargetIntegral_q"), exact) < TIGHT, "sphere, points: TargetIntegral_q conserved")
    check(np.max(np.abs(points_of(f, "one") - 3.0)) < 3e-12, "sphere, points: a constant stays")


test_cells()
test_points()
test_sphere()
test_guard()
test_nan()
test_bounds_and_hidden()
test_errors()
test_time_series()
finish()
