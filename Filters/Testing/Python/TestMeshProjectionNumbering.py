"""Numbering-independent results (VTK Python: /usr/bin/python3 with the
build's python directory on PYTHONPATH).

The filter renumbers meshes whose numbering does not follow space
(Renumbering: Automatic, Always, Never). Whatever it does inside, what a
user sees must be the same:

    a. shuffled meshes (cells and points in random order) give, mapped back
       through the shuffle, the result of the meshes as generated: every
       point and cell array, the masks, CoveredFraction, the intersection
       pieces (with their cell ids) and the exported matrices, for each of
       Never, Always and Automatic;
    b. Automatic renumbers the shuffled meshes (NumberOfRenumberedMeshes) and
       leaves the generated ones (numbered along a sweep) alone;
    c. the same with cell data (intensive and extensive), a NaN hole in one
       array, and 3D; with split cells (Gmsh quads and triangles), whose
       split follows the file's point ids, the three modes on one shuffled
       file;
    d. NumberOfThreads: 1 and 2 threads give the same result, and the
       application's SMP backend is left as it was;
    e. interleaved sweeps (the triangles 2-coloured so that no two of a
       colour share an edge, one colour after the other, each in sweep
       order): Automatic renumbers them on one thread and on two (the
       cells across a face are half the list apart), with the result of
       the meshes as generated;
    f. operators kept at the first execution: their matrices in the
       datasets' numbering, also after Input changed numbering;
    g. without OutputIntersections (the meshes give their geometry back
       before the solve): every array and matrix bit for bit as with it;
    h. the Source's integrals, whose weights two threads sum over ranges of
       cells (a Source of more than 32768 cells, inside Input): the exact
       integral of a linear field and the cell sums of a cell field, on 1
       and 2 threads, renumbered (the ranges' own sums) or not (one loop).
"""
import math

import numpy as np
from scipy.sparse import csr_matrix
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIdTypeArray, vtkPoints, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkImageData, vtkUnstructuredGrid
from vtkmodules.vtkFiltersCore import vtkAppendFilter
from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter, vtkTransformFilter
from vtkmodules.vtkCommonTransforms import vtkTransform

from meshprojection import vtkMeshProjectionFilter
from mpsupport.testing import check, finish, read

NEVER, ALWAYS, AUTOMATIC = (vtkMeshProjectionFilter.NEVER_RENUMBER,
                            vtkMeshProjectionFilter.ALWAYS_RENUMBER,
                            vtkMeshProjectionFilter.AUTOMATIC_RENUMBERING)
MODES = {"Never": NEVER, "Always": ALWAYS, "Automatic": AUTOMATIC}


def simplices(dims, angle, dim):
    """A triangle (dim 2) or tetrahedron grid of the unit square or cube,
    turned by `angle` degrees about z, numbered along a sweep."""
    image = vtkImageData()
    image.SetDimensions(dims[0], dims[1], dims[2] if dim == 3 else 1)
    image.SetSpacing(1.0 / (dims[0] - 1), 1.0 / (dims[1] - 1),
                     1.0 / (dims[2] - 1) if dim == 3 else 1.0)
    split = vtkDataSetTriangleFilter()
    split.SetInputData(image)
    turn = vtkTransform()
    turn.Translate(0.5, 0.5, 0)
    turn.RotateZ(angle)
    turn.Translate(-0.5, -0.5, 0)
    moved = vtkTransformFilter()
    moved.SetTransform(turn)
    moved.SetInputConnection(split.GetOutputPort())
    append = vtkAppendFilter()  # an unstructured grid with double points
    append.SetOutputPointsPrecision(1)
    append.SetInputConnection(moved.GetOutputPort())
    append.Update()
    return append.GetOutput()


def with_fields(grid, nan=False):
    """Point arrays Linear (1 + 2x - 3y + 0.5z), Smooth, Hole (Smooth with a
    NaN when asked) and cell arrays Mean and Mass."""
    x = vtk_to_numpy(grid.GetPoints().GetData())
    out = vtkUnstructuredGrid()
    out.DeepCopy(grid)
    smooth = np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + x[:, 2]
    hole = smooth.copy()
    if nan:
        hole[len(hole) // 3] = np.nan
    for name, values in (("Linear", 1 + 2 * x[:, 0] - 3 * x[:, 1] + 0.5 * x[:, 2]),
                         ("Smooth", smooth), ("Hole", hole)):
        a = numpy_to_vtk(values, deep=1)
        a.SetName(name)
        out.GetPointData().AddArray(a)
    n = grid.GetNumberOfCells()
    for name, values in (("Mean", np.cos(np.arange(n) * 0.37)), ("Mass", 1 + np.arange(n) % 7)):
        a = numpy_to_vtk(values.astype(float), deep=1)
        a.SetName(name)
        out.GetCellData().AddArray(a)
    return out


def shuffled(grid, seed):
    """`grid` with cells and points in random order, and the permutations
    (new -> old) of its cells and points. Arrays follow their points and cells."""
    rng = np.random.default_rng(seed)
    n, np_ = grid.GetNumberOfCells(), grid.GetNumberOfPoints()
    cells = rng.permutation(n)
    points = rng.permutation(np_)
    new_id = np.empty(np_, dtype=np.int64)
    new_id[points] = np.arange(np_)
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray()).astype(np.int64)
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).astype(np.int64)
    types = vtk_to_numpy(grid.GetCellTypesArray())
    sizes = np.diff(offsets)[cells]
    new_offsets = np.concatenate(([0], np.cumsum(sizes)))
    new_conn = np.concatenate([new_id[conn[offsets[c]:offsets[c + 1]]] for c in cells])
    out = vtkUnstructuredGrid()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(vtk_to_numpy(grid.GetPoints().GetData())[points].copy(), deep=1))
    out.SetPoints(pts)
    ca = vtkCellArray()
    o = vtkIdTypeArray()
    o.DeepCopy(numpy_to_vtk(new_offsets, deep=1, array_type=vtkIdTypeArray().GetDataType()))
    c = vtkIdTypeArray()
    c.DeepCopy(numpy_to_vtk(new_conn, deep=1, array_type=vtkIdTypeArray().GetDataType()))
    ca.SetData(o, c)
    out.SetCells(numpy_to_vtk(types[cells].copy(), deep=1), ca)
    for data, order in ((grid.GetPointData(), points), (grid.GetCellData(), cells)):
        target = out.GetPointData() if data is grid.GetPointData() else out.GetCellData()
        for i in range(data.GetNumberOfArrays()):
            a = numpy_to_vtk(vtk_to_numpy(data.GetArray(i))[order].copy(), deep=1)
            a.SetName(data.GetArrayName(i))
            target.AddArray(a)
    return out, cells, points


def project(target, source, mode, extensive=False, threads=0, intersections=True, bounds=False):
    f = vtkMeshProjectionFilter()
    f.SetRenumbering(mode)
    f.SetNumberOfThreads(threads)
    f.SetOutputIntersections(intersections)
    f.SetCellDataQuantity(f.EXTENSIVE if extensive else f.INTENSIVE)
    f.SetPreserveBounds(bounds)
    f.SetInputData(target)
    f.SetSourceData(source)
    f.Update()
    return f


def arrays(data):
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)).astype(float)
            for i in range(data.GetNumberOfArrays())}


def pieces(f, dim):
    """Sorted rows (target cell, source cell, measure) of the intersection pieces."""
    out = f.GetOutput(1) if dim == 2 else f.GetOutput(2)
    cd = out.GetCellData()
    t = vtk_to_numpy(cd.GetArray("TargetCellId"))
    s = vtk_to_numpy(cd.GetArray("SourceCellId"))
    m = vtk_to_numpy(cd.GetArray("Area" if dim == 2 else "Volume"))
    rows = {}
    for a, b, v in zip(t, s, m):
        rows[(int(a), int(b))] = rows.get((int(a), int(b)), 0.0) + float(v)
    return rows


def matrix(f, transfer, which):
    """f's matrix, asked for as the meshprojection helpers do: KeepMatrices
    on and f updated (which executes it again after a one-off execution)."""
    f.SetKeepMatrices(True)
    f.Update()
    rows, cols, vals = vtkIdTypeArray(), vtkIdTypeArray(), vtkDoubleArray()
    ncols = f.GetMatrix(transfer, which, rows, cols, vals)
    start = vtk_to_numpy(rows)
    return csr_matrix((vtk_to_numpy(vals), vtk_to_numpy(cols), start),
                      shape=(len(start) - 1, ncols))


def same_matrices(label, plain, f, points_t, points_s):
    """The point transfer's (P1 -> P1) M_tt and M_ts of f, rows and columns
    mapped back through the shuffles, equal plain's."""
    for which in (f.TARGET_MASS, f.MIXED_MASS):
        m0 = matrix(plain, 0, which)
        m1 = matrix(f, 0, which)
        cols = points_t if which == f.TARGET_MASS else points_s
        back = m1.tocoo()
        remapped = csr_matrix((back.data, (points_t[back.row], cols[back.col])), shape=m0.shape)
        d = abs(remapped - m0).max() / abs(m0).max()
        check(d < 1e-13, "%s: matrix %d differs by %.3g" % (label, which, d))


def compare(label, plain, f, dim, cells_t, points_t, cells_s, points_s, tol=1e-11):
    """f ran on shuffled meshes; plain on the meshes as generated."""
    po, so = plain.GetOutput(), f.GetOutput()
    for kind, get, order in (("point", lambda o: o.GetPointData(), points_t),
                             ("cell", lambda o: o.GetCellData(), cells_t)):
        a, b = arrays(get(po)), arrays(get(so))
        check(sorted(a) == sorted(b), "%s: %s arrays %s vs %s" % (label, kind, sorted(a), sorted(b)))
        for name in a:
            if name not in b:
                continue
            x, y = a[name][order], b[name]
            same_nan = np.array_equal(np.isnan(x), np.isnan(y))
            ok = np.isfinite(x) & np.isfinite(y)
            scale = max(1.0, np.max(np.abs(x[ok])) if ok.any() else 1.0)
            d = np.max(np.abs(x[ok] - y[ok])) / scale if ok.any() else 0.0
            check(same_nan and d < tol, "%s: %s array %s differs by %.3g (NaN pattern %s)"
                  % (label, kind, name, d, same_nan))
    # Pieces: the same pairs (shuffled ids mapped back) and measures.
    new_t = np.empty(len(cells_t), dtype=np.int64)
    new_t[cells_t] = np.arange(len(cells_t))
    new_s = np.empty(len(cells_s), dtype=np.int64)
    new_s[cells_s] = np.arange(len(cells_s))
    a = pieces(plain, dim)
    b = pieces(f, dim)
    mapped = {(int(cells_t[t]), int(cells_s[s])): v for (t, s), v in b.items()}
    check(set(a) == set(mapped), "%s: %d vs %d intersecting pairs" % (label, len(a), len(mapped)))
    worst = max((abs(a[k] - mapped[k]) for k in a if k in mapped), default=0.0)
    check(worst < 1e-14, "%s: piece measures differ by %.3g" % (label, worst))
    same_matrices(label, plain, f, points_t, points_s)
    print("%-32s renumbered %d of 2, %d pieces" % (label, f.GetNumberOfRenumberedMeshes(), len(b)))


def case(label, target, source, dim, extensive=False, tidy_renumbered=0, split=False):
    st, ct, pt = shuffled(target, 1)
    ss, cs, ps = shuffled(source, 2)
    if split:
        # Cells that are not simplices are split by their point ids (the
        # lowest corner rule), so a shuffled file is split otherwise and its
        # P1 space differs: compare the renumbering modes on the same file.
        plain = project(st, ss, NEVER, extensive)
        ct, cs = np.arange(len(ct)), np.arange(len(cs))
        pt, ps = np.arange(len(pt)), np.arange(len(ps))
    else:
        plain = project(target, source, NEVER, extensive)
    for name, mode in MODES.items():
        f = project(st, ss, mode, extensive)
        compare("%s, shuffled, %s" % (label, name), plain, f, dim, ct, pt, cs, ps)
        if mode == AUTOMATIC:
            big = min(target.GetNumberOfCells(), source.GetNumberOfCells()) >= 4096
            check(f.GetNumberOfRenumberedMeshes() == (2 if big else 0),
                  "%s: Automatic renumbered %d shuffled meshes" % (label, f.GetNumberOfRenumberedMeshes()))
    auto = project(target, source, AUTOMATIC, extensive)
    check(auto.GetNumberOfRenumberedMeshes() == tidy_renumbered,
          "%s: Automatic renumbered %d meshes numbered along a sweep"
          % (label, auto.GetNumberOfRenumberedMeshes()))


# a, b. Triangles and tetrahedra, numbered along a sweep, then shuffled.
t2 = with_fields(simplices((61, 67, 1), 0.0, 2))
s2 = with_fields(simplices((57, 59, 1), 7.0, 2), nan=True)
case("2D triangles", t2, s2, 2)
case("2D triangles, extensive", t2, s2, 2, extensive=True)
t3 = with_fields(simplices((11, 12, 13), 0.0, 3))
s3 = with_fields(simplices((12, 11, 10), 5.0, 3), nan=True)
case("3D tetrahedra", t3, s3, 3)

# c. Split cells: Gmsh's quads and triangles (small: Automatic leaves them).
disk_t = with_fields(read("../Testing/Data/Gmsh/mixed_disk.vtu"))
disk_s = with_fields(read("../Testing/Data/Gmsh/tris_disk.vtu"), nan=True)
case("Gmsh mixed disk", disk_t, disk_s, 2, split=True)

# d. Threads: the filter's own scope, the application's backend untouched.
backend = vtkSMPTools.GetBackend()
one = project(t2, s2, AUTOMATIC, threads=1)
two = project(t2, s2, AUTOMATIC, threads=2)
a, b = arrays(one.GetOutput().GetPointData()), arrays(two.GetOutput().GetPointData())
d = max(np.nanmax(np.abs(a[k] - b[k])) for k in a)
check(d < 1e-12, "1 and 2 threads differ by %.3g" % d)
check(vtkSMPTools.GetBackend() == backend, "the SMP backend changed to " + vtkSMPTools.GetBackend())
print("threads: 1 vs 2 differ by %.3g, backend %s" % (d, backend))


# e. Interleaved sweeps: the cells 2-coloured across their edges (the grid's
# points have 4 or 8 triangles around them: the colouring exists), one colour
# after the other (points as they were).
def interleaved(grid):
    n = grid.GetNumberOfCells()
    tri = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).astype(np.int64).reshape(n, 3)
    by_edge = {}
    for c, (a, b, d) in enumerate(tri):
        for e in ((a, b), (b, d), (d, a)):
            by_edge.setdefault((min(e), max(e)), []).append(c)
    colour = np.full(n, -1)
    for start in range(n):
        if colour[start] >= 0:
            continue
        colour[start] = 0
        stack = [start]
        while stack:
            c = stack.pop()
            a, b, d = tri[c]
            for e in ((a, b), (b, d), (d, a)):
                for o in by_edge[(min(e), max(e))]:
                    if colour[o] < 0:
                        colour[o] = 1 - colour[c]
                        stack.append(o)
                    check(o == c or colour[o] != colour[c], "interleaved: the triangles have no 2-colouring")
    order = np.concatenate((np.flatnonzero(colour == 0), np.flatnonzero(colour == 1)))
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray()).astype(np.int64)
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).astype(np.int64)
    sizes = np.diff(offsets)[order]
    ca = vtkCellArray()
    o = vtkIdTypeArray()
    o.DeepCopy(numpy_to_vtk(np.concatenate(([0], np.cumsum(sizes))), deep=1, array_type=vtkIdTypeArray().GetDataType()))
    c = vtkIdTypeArray()
    c.DeepCopy(numpy_to_vtk(np.concatenate([conn[offsets[k]:offsets[k + 1]] for k in order]), deep=1,
                            array_type=vtkIdTypeArray().GetDataType()))
    ca.SetData(o, c)
    out = vtkUnstructuredGrid()
    out.SetPoints(grid.GetPoints())
    out.SetCells(numpy_to_vtk(vtk_to_numpy(grid.GetCellTypesArray())[order].copy(), deep=1), ca)
    out.GetPointData().ShallowCopy(grid.GetPointData())
    for i in range(grid.GetCellData().GetNumberOfArrays()):
        a = numpy_to_vtk(vtk_to_numpy(grid.GetCellData().GetArray(i))[order].copy(), deep=1)
        a.SetName(grid.GetCellData().GetArrayName(i))
        out.GetCellData().AddArray(a)
    return out, order


it, ct = interleaved(t2)
is_, cs = interleaved(s2)
plain = project(t2, s2, NEVER, threads=1)
same_t, same_s = np.arange(t2.GetNumberOfPoints()), np.arange(s2.GetNumberOfPoints())
for threads, expected in ((1, 2), (2, 2)):
    f = project(it, is_, AUTOMATIC, threads=threads)
    check(f.GetNumberOfRenumberedMeshes() == expected,
          "interleaved sweeps, %d thread(s): Automatic renumbered %d meshes (expected %d)"
          % (threads, f.GetNumberOfRenumberedMeshes(), expected))
    compare("interleaved sweeps, %d thread(s)" % threads, plain, f, 2, ct, same_t, cs, same_s)


# f. Operators assembled and kept at the first execution (PreserveBounds
# needs M_ts at once, so no second execution is needed): their matrices
# are read out in the datasets' numbering at the first execution, and again
# after Input changes to the same mesh in another numbering (a mutation that
# forgets the new point order fails both).
bounded = vtkMeshProjectionFilter()
bounded.SetRenumbering(ALWAYS)
bounded.SetPreserveBounds(True)
bounded.SetInputData(t2)
bounded.SetSourceData(s2)
bounded.Update()
check(bounded.GetNumberOfRenumberedMeshes() == 2, "bounded: renumbered %d meshes" % bounded.GetNumberOfRenumberedMeshes())
same_matrices("kept at the first execution", plain, bounded, same_t, same_s)
st2, _, pt2 = shuffled(t2, 5)
bounded.SetInputData(st2)
bounded.Update()
same_matrices("kept after Input changed", plain, bounded, pt2, same_s)
# A Source without arrays: the point transfer is assembled all the same
# (the mask and coverage), and kept; the Source's point order, which its
# columns are mapped back through, must outlive the release of its
# geometry (dropping it with the geometry fails this).
bare = vtkUnstructuredGrid()
bare.DeepCopy(s2)
bare.GetPointData().Initialize()
bare.GetCellData().Initialize()
kept = vtkMeshProjectionFilter()
kept.SetRenumbering(ALWAYS)
kept.SetInputData(t2)
kept.SetSourceData(bare)
kept.Update()
check(kept.GetNumberOfRenumberedMeshes() == 2, "no arrays: renumbered %d meshes" % kept.GetNumberOfRenumberedMeshes())
check(kept.GetNumberOfOperatorsBuilt() == 1, "no arrays: built %d operators" % kept.GetNumberOfOperatorsBuilt())
same_matrices("no Source arrays, kept at the first execution", plain, kept, same_t, same_s)
print("matrices of operators kept at once: in the datasets' numbering")


# g. Without OutputIntersections the meshes of the last Input leaf give
# their geometry back before the solve (renumbered copies, the Source's
# neighbours and locator): every array bit for bit what it is with the
# intersections output (which keeps them), whatever the renumbering, the
# threads, the cell data's quantity, PreserveBounds, a kept operator's
# second execution, and the matrices read out afterwards.
st3, _, _ = shuffled(t3, 7)
ss3, _, _ = shuffled(s3, 8)
st2s, _, _ = shuffled(t2, 9)
ss2s, _, _ = shuffled(s2, 10)
for label, target, source in (("2D", st2s, ss2s), ("3D", st3, ss3)):
    for name, mode in MODES.items():
        for extensive, threads, bounds in ((False, 1, False), (True, 2, False), (False, 2, True)):
            runs = [project(target, source, mode, extensive, threads, keep, bounds) for keep in (True, False)]
            for f in runs:  # a second execution: the kept operators again
                f.Modified()
                f.Update()
            what = "%s %s, %s, %d thread(s)%s" % (label, name, "extensive" if extensive else "intensive",
                                                  threads, ", bounds" if bounds else "")
            for get in (lambda o: o.GetPointData(), lambda o: o.GetCellData()):
                a, b = arrays(get(runs[0].GetOutput())), arrays(get(runs[1].GetOutput()))
                check(sorted(a) == sorted(b), "%s: arrays %s vs %s" % (what, sorted(a), sorted(b)))
                for k in a:
                    check(np.array_equal(a[k], b[k], equal_nan=True),
                          "%s: array %s differs without the intersections output" % (what, k))
            for which in (runs[0].TARGET_MASS, runs[0].MIXED_MASS):
                m0, m1 = matrix(runs[0], 0, which), matrix(runs[1], 0, which)
                check(m0.shape == m1.shape and abs(m0 - m1).max() == 0.0,
                      "%s: matrix %d differs without the intersections output" % (what, which))
print("geometry given back before the solve: the same arrays and matrices")

# h. The Source weights of the integrals, summed over ranges of cells on two
# threads (in cell order: each range adds into the points no earlier range
# uses, the others after). A shuffled Source of 33800 triangles on the unit
# square inside an Input on [-0.1, 1.1]^2, so that every Source cell is
# covered whole: the integrals of Linear and of the cell array Mean are those
# over the Source's own triangles (areas and corner means from its points).
source = with_fields(simplices((131, 131, 1), 0.0, 2))
source, cells_s, points_s = shuffled(source, 11)
target = simplices((70, 70, 1), 0.0, 2)
x = vtk_to_numpy(target.GetPoints().GetData()).astype(float)
x[:, :2] = 1.2 * x[:, :2] - 0.1
target.GetPoints().SetData(numpy_to_vtk(x, deep=1))
xs = vtk_to_numpy(source.GetPoints().GetData()).astype(float)
tri = vtk_to_numpy(source.GetCells().GetConnectivityArray()).reshape(-1, 3)
u, v = xs[tri[:, 1]] - xs[tri[:, 0]], xs[tri[:, 2]] - xs[tri[:, 0]]
area = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
linear = vtk_to_numpy(source.GetPointData().GetArray("Linear")).astype(float)
mean = vtk_to_numpy(source.GetCellData().GetArray("Mean")).astype(float)
expected = {"SourceIntegral_Linear": float(np.sum(area * linear[tri].mean(axis=1))),
            "SourceIntegral_Mean (cell data)": float(np.sum(area * mean))}
found = {}
for name, mode in (("Always", ALWAYS), ("Never", NEVER)):
    for threads in (1, 2):
        f = project(target, source, mode, threads=threads)
        fd = f.GetOutput().GetFieldData()
        check(f.GetNumberOfRenumberedMeshes() == (2 if mode == ALWAYS else 0),
              "h: %s renumbered %d meshes" % (name, f.GetNumberOfRenumberedMeshes()))
        for key, value in expected.items():
            got = fd.GetArray(key).GetValue(0)
            found.setdefault(key, []).append(got)
            check(abs(got - value) <= 1e-12 * abs(value),
                  "h: %s, %d thread(s): %s = %.17g, expected %.17g" % (name, threads, key, got, value))
for key, values in found.items():
    spread = (max(values) - min(values)) / abs(expected[key])
    check(spread <= 1e-13, "h: %s differs by %.3g across modes and threads" % (key, spread))
print("Source integrals over ranges of cells: %s" % {k: v[0] for k, v in found.items()})

finish()
