"""vtkPMeshProjectionFilter on several MPI processes (run under mpiexec with
Debian's python3): every partitioning gives the serial result.

Each process builds the same meshes, projects them whole with the serial
filter (the reference), then takes its part of them by a partitioning and
runs the parallel filter. Checked on every process, for its own points and
cells: values equal the serial ones (1e-10 of the field's range), the valid
masks equal the serial ones, points shared by processes have the same
value everywhere (bit for bit), and the integrals in the field data (totals
over the processes) equal the serial ones (conservation), and the warning
on points valid through slivers only gives the serial count, once.
Partitionings:
Redistribute DataSet (DIY), a random split of the cells, blocks in x, all
Source on one process and all Input on another, one process without Input.
Meshes: triangles (2D), tetrahedra (3D), hexahedra with GlobalIds, surfaces,
curves and traces in 3D; point and
cell data; lumped mass; PreserveBounds; the direct solver; a composite Input; a time step reusing the operator;
a run stopped on one process only (no process waits for it).
"""
import sys

import re

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import VTK_STRING
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdList
from vtkmodules.vtkCommonDataModel import (VTK_HEXAHEDRON, VTK_LINE, VTK_POLYHEDRON, VTK_QUAD, VTK_TETRA, VTK_TRIANGLE,
                                           vtkMultiBlockDataSet, vtkUnstructuredGrid)

from mpsupport import meshes, mpi

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)


# ---- meshes ---------------------------------------------------------------
def triangles(n, lo, hi, seed):
    return meshes.grid(*meshes.triangles(n, lo, hi, seed), VTK_TRIANGLE)


def hexahedra(n, lo, hi, seed):
    return meshes.grid(*meshes.hexahedra(n, lo, hi, seed), VTK_HEXAHEDRON)


def tetrahedra(n, lo, hi, seed):
    return meshes.grid(*meshes.tetrahedra(n, lo, hi, seed), VTK_TETRA)


def with_fields(g, name="f"):
    x = vtk_to_numpy(g.GetPoints().GetData())
    f = np.sin(3 * x[:, 0]) + x[:, 1] ** 2 + 0.5 * x[:, 2]
    a = numpy_to_vtk(f, deep=True)
    a.SetName(name)
    g.GetPointData().AddArray(a)
    lin = numpy_to_vtk(np.stack([1 + 2 * x[:, 0] - x[:, 1] + 3 * x[:, 2], x[:, 0]], 1).copy(), deep=True)
    lin.SetName("linear")
    g.GetPointData().AddArray(lin)
    centres = np.array([np.mean([g.GetPoint(i) for i in _ids(g, c)], axis=0) for c in range(g.GetNumberOfCells())])
    cf = numpy_to_vtk(np.cos(2 * centres[:, 0]) + centres[:, 1], deep=True)
    cf.SetName("cellf")
    g.GetCellData().AddArray(cf)
    return g


def _ids(g, c):
    ids = g.GetCell(c).GetPointIds()
    return [ids.GetId(k) for k in range(ids.GetNumberOfIds())]


def centres(g):
    x = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray())
    offs = vtk_to_numpy(g.GetCells().GetOffsetsArray())
    n = offs[1] - offs[0]
    return x[conn.reshape(-1, n)].mean(axis=1)


# ---- partitionings ----------------------------------------------------------
def extract(g, keep, global_ids=False):
    out = meshes.extract(g, keep)
    if global_ids:
        out.GetPointData().SetGlobalIds(out.GetPointData().GetArray("origId"))
    return out


def split(g, how, role, global_ids=False):
    n = g.GetNumberOfCells()
    if how == "random":
        owner = np.random.default_rng(7 if role == "input" else 8).integers(0, size, n)
    elif how == "blocks":
        x = centres(g)[:, 0]
        owner = np.minimum((np.argsort(np.argsort(x)) * size) // n, size - 1)
    elif how == "apart":
        owner = np.full(n, size - 1 if role == "input" else 0)
    elif how == "empty":
        # Input on every process but the last, Source split at random.
        owner = np.random.default_rng(9).integers(0, size - 1 if role == "input" else size, n)
    else:
        raise ValueError(how)
    return extract(g, owner == rank, global_ids)


def redistributed(g):
    """Redistribute DataSet as a ParaView user does: all on process 0 first."""
    from vtkmodules.vtkFiltersParallelDIY2 import vtkRedistributeDataSetFilter
    r = vtkRedistributeDataSetFilter()
    r.SetController(controller)
    r.SetInputData(g if rank == 0 else vtkUnstructuredGrid())
    r.Update()
    out = r.GetOutputDataObject(0)
    if not isinstance(out, vtkUnstructuredGrid):
        from vtkmodules.vtkFiltersCore import vtkAppendFilter
        a = vtkAppendFilter()
        a.AddInputData(out)
        a.Update()
        out = a.GetOutput()
    result = vtkUnstructuredGrid()
    result.ShallowCopy(out)
    return result


# ---- the comparison ---------------------------------------------------------
def run(filter_class, target, source, **props):
    f = filter_class()
    texts = []

    @calldata_type(VTK_STRING)
    def collect(obj, event, text):
        texts.append(str(text))

    f.AddObserver("WarningEvent", collect)
    f.warnings = texts
    f.SetInputData(target)
    f.SetSourceData(source)
    for k, v in props.items():
        getattr(f, "Set" + k)(v)
    f.Update()
    return f


def slivers_said(f):
    """The number of points valid through slivers only in f's warning (0: none)."""
    for text in f.warnings:
        m = re.search(r"(\d+) \S+ points are valid through slivers only", text)
        if m:
            return int(m.group(1))
    return 0


def arrays_of(data):
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)) for i in range(data.GetNumberOfArrays())}


def compare(what, serial_out, local_out, ranges):
    """The local output against the serial one, by original ids."""
    for assoc in ("point", "cell"):
        sd = serial_out.GetPointData() if assoc == "point" else serial_out.GetCellData()
        ld = local_out.GetPointData() if assoc == "point" else local_out.GetCellData()
        if local_out.GetNumberOfPoints() == 0:
            continue
        ids = vtk_to_numpy(ld.GetArray("origId"))
        sid = vtk_to_numpy(sd.GetArray("origId"))
        pos = np.full(int(max(sid.max(initial=0), ids.max(initial=0))) + 1, -1)
        pos[sid] = np.arange(len(sid))
        check(np.all(pos[ids] >= 0), "%s: %s ids all in the serial output" % (what, assoc))
        ids = pos[ids]
        if assoc == "cell" and ld.GetArray("vtkGhostType") is not None:
            # Ghost cells are left out (their owners have them): compare the others.
            keep = vtk_to_numpy(ld.GetArray("vtkGhostType")) == 0
        else:
            keep = np.ones(len(ids), bool)
        mask_name = "vtkValidPointMask" if assoc == "point" else "vtkValidCellMask"
        sm = vtk_to_numpy(sd.GetArray(mask_name))[ids] if sd.GetArray(mask_name) else None
        lm = vtk_to_numpy(ld.GetArray(mask_name)) if ld.GetArray(mask_name) else None
        check((sm is None) == (lm is None), "%s: %s mask present alike" % (what, assoc))
        if sm is not None and lm is not None:
            bad = np.count_nonzero((sm != lm) & keep)
            check(bad == 0, "%s: %d %s masks differ from serial" % (what, bad, assoc))
        for name, lv in arrays_of(ld).items():
            if name in ("origId", mask_name, "CoveredFraction") or name.startswith("vtk"):
                continue
            if sd.GetArray(name) is None:
                check(False, "%s: %s array %s not in the serial output" % (what, assoc, name))
                continue
            sv = vtk_to_numpy(sd.GetArray(name))[ids]
            valid = (lm.astype(bool) if lm is not None else np.ones(len(ids), bool)) & keep
            if lv.ndim == 1:
                lv, sv = lv[:, None], sv[:, None]
            scale = ranges.get(name, 1.0)
            err = np.max(np.abs(lv[valid] - sv[valid])) / scale if valid.any() else 0.0
            check(err <= 1e-10, "%s: %s %s differs from serial by %.3g of its range" % (what, assoc, name, err))
            check(np.array_equal(np.isnan(lv[~valid & keep]), np.isnan(sv[~valid & keep])),
                  "%s: %s %s fill values differ" % (what, assoc, name))


def shared_points_agree(what, out):
    """Points on several processes: the same values everywhere, bit for bit."""
    pd = out.GetPointData()
    ids = vtk_to_numpy(pd.GetArray("origId")) if out.GetNumberOfPoints() else np.zeros(0, np.int64)
    name = "f" if pd.GetArray("f") is not None else None
    vals = vtk_to_numpy(pd.GetArray(name)) if name and out.GetNumberOfPoints() else np.zeros(0)
    # Every process's (id, value) pairs to every process.
    parts = allgather(np.concatenate([ids.astype(np.float64), vals.astype(np.float64)]))
    seen = {}
    differ = 0
    for part in parts:
        m = len(part) // 2
        for i, v in zip(part[:m].astype(np.int64), part[m:]):
            if i in seen and not (seen[i] == v or (np.isnan(seen[i]) and np.isnan(v))):
                differ += 1
            seen.setdefault(i, v)
    check(differ == 0, "%s: %d shared points differ between processes" % (what, differ))


def allgather(values):
    return mpi.allgather(controller, values)


def integrals(out):
    fd = out.GetFieldData()
    return {fd.GetArrayName(i): vtk_to_numpy(fd.GetArray(i)).copy() for i in range(fd.GetNumberOfArrays())
            if fd.GetArrayName(i).startswith(("SourceIntegral_", "TargetIntegral_"))}


def case(what, target, source, how, global_ids=False, composite=False, ghosts=False,
         polydata=False, **props):
    mpi.numbered(target)
    serial = run(meshprojection.vtkMeshProjectionFilter, target, source, CacheOperator=False, **props)
    sout = serial.GetOutputDataObject(0)
    if how == "redistribute":
        lt, ls = redistributed(target), redistributed(source)
    else:
        lt, ls = split(target, how, "input", global_ids), split(source, how, "source")
    if polydata:
        # Each process's part of Source as polydata (its cells reach the
        # others through the generic cell calls, not an unstructured grid's arrays).
        from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
        g = vtkGeometryFilter()
        g.SetInputData(ls)
        g.MergingOff()
        g.Update()
        ls = g.GetOutput()
    if ghosts:
        # A layer of ghost cells, as ParaView's Ghost Cells filter makes it
        # (without GlobalIds it copies the interface points: one process
        # then holds two points at one place).
        from vtkmodules.vtkFiltersParallelDIY2 import vtkGhostCellsGenerator
        g = vtkGhostCellsGenerator()
        g.SetController(controller)
        g.SetInputData(lt)
        g.SetNumberOfGhostLayers(1)
        g.BuildIfRequiredOff()
        g.Update()
        lt = vtkUnstructuredGrid()
        lt.ShallowCopy(g.GetOutputDataObject(0))
    ranges = {}
    for name in ("f", "linear", "cellf"):
        for data in (source.GetPointData(), source.GetCellData()):
            if data.GetArray(name) is not None:
                v = vtk_to_numpy(data.GetArray(name))
                ranges[name] = float(np.ptp(v)) or 1.0
    if composite:
        # Two blocks: the local part cut in two by y (a block may be empty here).
        y = centres(lt)[:, 1] if lt.GetNumberOfCells() else np.zeros(0)
        mb = vtkMultiBlockDataSet()
        mb.SetNumberOfBlocks(2)
        for b, keep in enumerate((y < 0.5, y >= 0.5)):
            mb.SetBlock(b, extract(lt, keep) if lt.GetNumberOfCells() else vtkUnstructuredGrid())
        lt = mb
    par = run(meshprojection.vtkPMeshProjectionFilter, lt, ls, **props)
    out = par.GetOutputDataObject(0)
    if composite:
        # Each block is its own system: the serial run on the same two blocks, whole.
        yt = centres(target)[:, 1]
        whole = vtkMultiBlockDataSet()
        whole.SetNumberOfBlocks(2)
        for b, keep in enumerate((yt < 0.5, yt >= 0.5)):
            whole.SetBlock(b, extract(target, keep))
        sb = run(meshprojection.vtkMeshProjectionFilter, whole, source, CacheOperator=False, **props)
        for b in range(2):
            compare("%s block %d" % (what, b), sb.GetOutputDataObject(0).GetBlock(b), out.GetBlock(b), ranges)
        return par
    compare(what, sout, out, ranges)
    shared_points_agree(what, out)
    # Points valid through slivers only: the serial count, said once (by
    # process 0), however many processes share such a point's cells.
    said = [int(v[0]) for v in allgather([slivers_said(par)])]
    expected = [slivers_said(serial)] + [0] * (size - 1)
    check(said == expected, "%s: points valid through slivers said %s, serial %s" % (what, said, expected[0]))
    si, pi = integrals(sout), integrals(out)
    check(set(si) == set(pi), "%s: integral arrays %s vs %s" % (what, sorted(si), sorted(pi)))
    for k in si:
        if k in pi:
            err = np.max(np.abs(si[k] - pi[k])) / max(1e-300, np.max(np.abs(si[k])))
            check(err <= 1e-10, "%s: %s total %s vs serial %s" % (what, k, pi[k], si[k]))
    return par


# 2D: triangles, the Source reaching beyond Input on one side (partial cover).
t2 = with_fields(triangles(36, (0, 0, 0), (1, 1, 0), 1))
s2 = with_fields(triangles(29, (-0.13, 0.07, 0), (0.91, 1.2, 0), 2))
for how in ("random", "blocks", "apart", "empty", "redistribute"):
    case("2D " + how, t2, s2, how)
case("2D lumped, cells to points", t2, s2, "random", MassMatrix=1, CellDataTarget=3)
# Bounds: each point's from the Source values of its row of M_ts, whose
# columns a shared point has on several processes; the assured sum over all.
case("2D PreserveBounds", t2, s2, "random", PreserveBounds=1)
case("2D PreserveBounds, cells to points", t2, s2, "blocks", PreserveBounds=1, CellDataTarget=3)
# The direct solver (no iterations, or too few), the whole system gathered.
case("2D direct solver", t2, s2, "random", MaximumIterations=0)
case("2D direct solver after 3 iterations, Redistribute DataSet", t2, s2, "redistribute", MaximumIterations=3)
case("2D composite", t2, s2, "random", composite=True)
case("2D ghost cells", t2, s2, "blocks", ghosts=True)
case("2D polydata Source", t2, s2, "blocks", polydata=True)
# Source ending 2e-5 past the first column of a regular Input: the second
# column covered in slivers only. The points between the first two columns
# also have well-covered cells, maybe on another process (not slivers).
tr = with_fields(meshes.grid(*meshes.triangles(36, (0, 0, 0), (1, 1, 0), 7, jitter=0.0), VTK_TRIANGLE))
ss = with_fields(triangles(29, (-0.5, -0.1, 0), (1 / 36 + 2e-5, 1.1, 0), 8))
case("2D slivers at the Source's edge", tr, ss, "random")

# 3D: tetrahedra, and hexahedra whose points carry GlobalIds.
t3 = with_fields(tetrahedra(9, (0, 0, 0), (1, 1, 1), 3))
s3 = with_fields(tetrahedra(8, (0.05, -0.1, 0.02), (1.1, 0.95, 1.07), 4))
for how in ("random", "blocks", "apart", "redistribute"):
    case("3D " + how, t3, s3, how)
h3 = with_fields(hexahedra(7, (0, 0, 0), (1, 1, 1), 5))
hs = with_fields(hexahedra(6, (0.03, 0.02, -0.04), (1.04, 0.97, 1.02), 6))
gid = numpy_to_vtkIdTypeArray(np.arange(hs.GetNumberOfPoints(), dtype=np.int64), deep=True)
gid.SetName("gid")
hs.GetPointData().SetGlobalIds(gid)
mpi.numbered(h3)
h3.GetPointData().SetGlobalIds(h3.GetPointData().GetArray("origId"))
case("3D hexahedra with GlobalIds", h3, hs, "random", global_ids=True)
case("3D ghost cells", t3, s3, "blocks", ghosts=True)
case("3D PreserveBounds", t3, s3, "random", PreserveBounds=1)
case("3D direct solver, GlobalIds", t3, s3, "blocks", global_ids=True, MaximumIterations=0)
# The same hexahedra as polyhedra (face streams): the Source cells travel
# and merge one by one with their faces.
HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))
hp = vtkUnstructuredGrid()
hp.SetPoints(hs.GetPoints())
for corners in vtk_to_numpy(hs.GetCells().GetConnectivityArray()).reshape(-1, 8):
    stream = vtkIdList()
    stream.InsertNextId(6)
    for face in HEX_FACES:
        stream.InsertNextId(4)
        for i in face:
            stream.InsertNextId(int(corners[i]))
    hp.InsertNextCell(VTK_POLYHEDRON, stream)
hp.GetPointData().ShallowCopy(hs.GetPointData())
hp.GetCellData().ShallowCopy(hs.GetCellData())
check(hp.GetCellType(0) == VTK_POLYHEDRON, "polyhedra built")
case("3D polyhedra Source with GlobalIds", h3, hp, "random", global_ids=True)

# Surfaces and curves in 3D, and traces (a surface in a volume Source):
# the same partitionings give the serial result too.
def bent(g, height=0.3):
    """A flat mesh of the unit square lifted onto z = height (x^2 + y^2)."""
    x = vtk_to_numpy(g.GetPoints().GetData())
    x[:, 2] = height * (x[:, 0] ** 2 + x[:, 1] ** 2)
    g.GetPoints().Modified()
    return g


def helix(n, turns, seed):
    """n jittered segments along a helix (lines)."""
    rng = np.random.default_rng(seed)
    u = np.linspace(0.0, 1.0, n + 1)
    u[1:-1] += (rng.random(n - 1) - 0.5) * 0.4 / n
    a = 2 * np.pi * turns * u
    points = np.stack([0.5 + 0.4 * np.cos(a), 0.5 + 0.4 * np.sin(a), u], 1)
    cells = np.stack([np.arange(n), np.arange(1, n + 1)], 1)
    return meshes.grid(points, cells, VTK_LINE)


ts2 = with_fields(bent(triangles(30, (0, 0, 0), (1, 1, 0), 11)))
ss2 = with_fields(bent(triangles(23, (-0.05, 0.04, 0), (0.93, 1.1, 0), 12)))
for how in ("random", "blocks", "redistribute"):
    case("surface " + how, ts2, ss2, how)
case("surface scaled to the Source's integral", ts2, ss2, "random", ConserveSourceIntegral=1)
for how in ("apart", "empty"):
    case("surface " + how, ts2, ss2, how)


# Quads, split into triangles by the filter on every process alike.
sq = with_fields(bent(meshes.grid(*meshes.quads(17, (-0.05, 0.04, 0), (0.93, 1.1, 0), 16), VTK_QUAD)))
case("surface of quads as Source", ts2, sq, "random")


def folded(g):
    """Flat for x < 0.6, bent up beyond: in blocks, the first process's parts
    of both meshes lie in one plane, the last's do not."""
    x = vtk_to_numpy(g.GetPoints().GetData())
    x[:, 2] = np.where(x[:, 0] > 0.6, 0.8 * (x[:, 0] - 0.6) ** 2, 0.0)
    g.GetPoints().Modified()
    return g


tf = with_fields(folded(triangles(30, (0, 0, 0), (1, 1, 0), 17)))
sf = with_fields(folded(triangles(23, (-0.043, 0.031, 0), (0.97, 1.07, 0), 18)))
case("surface flat on one process", tf, sf, "blocks")


def sheets(n, inset, seed):
    """One flat sheet per process, side by side in x with gaps between, each
    in a plane of its own (slope and height of its own): in blocks, every
    process's parts of both meshes are flat, each in another plane, while
    the whole meshes are a surface."""
    points, cells = [], []
    for k in range(size):
        x, c = meshes.triangles(n, (k / size + inset, inset, 0), ((k + 1) / size - inset, 1 - inset, 0), seed + k)
        x[:, 2] = 0.4 * (k + 1) * (x[:, 0] - k / size) + 0.1 * k
        cells.append(c + sum(len(p) for p in points))
        points.append(x)
    return meshes.grid(np.concatenate(points), np.concatenate(cells), VTK_TRIANGLE)


case("surface of sheets flat in planes of their own", with_fields(sheets(9, 0.06, 21)),
     with_fields(sheets(7, 0.04, 31)), "blocks")
tc = with_fields(helix(300, 2, 13))
sc = with_fields(helix(217, 2, 14))
# "apart", "empty": processes without cells see no curve themselves.
for how in ("random", "blocks", "apart", "empty"):
    case("curve " + how, tc, sc, how)


def line(n, x0, x1, y, z):
    """n segments along x at height y, z."""
    xs = np.linspace(x0, x1, n + 1)
    points = np.stack([xs, np.full(n + 1, y), np.full(n + 1, z)], 1)
    return meshes.grid(points, np.stack([np.arange(n), np.arange(1, n + 1)], 1), VTK_LINE)


def lifted(g, z):
    x = vtk_to_numpy(g.GetPoints().GetData())
    x[:, 2] = z
    g.GetPoints().Modified()
    return g


# A curve in a 2D Source's plane (z = 0.25) running far beyond it: in
# blocks, the last process has curve but no Source cells.
case("curve trace in a plane z = 0.25", with_fields(line(80, 0.1, 4.0, 0.5, 0.25)),
     with_fields(lifted(triangles(20, (0, 0, 0), (1, 1, 0), 2), 0.25)), "blocks")
tt = with_fields(bent(triangles(20, (0.1, 0.1, 0), (0.9, 0.9, 0), 15), 0.5))
# "apart", "empty": processes without Input or Source cells, which cannot
# see the trace themselves, make the same outputs as the others.
for how in ("random", "blocks", "apart", "empty"):
    case("trace " + how, tt, s3, how)

# Linear fields are exact in parallel too (P1 to P1).
par = case("2D linear", t2, s2, "blocks")
out = par.GetOutputDataObject(0)
if out.GetNumberOfPoints():
    x = vtk_to_numpy(out.GetPoints().GetData())
    lin = vtk_to_numpy(out.GetPointData().GetArray("linear"))
    valid = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
    exact = 1 + 2 * x[:, 0] - x[:, 1] + 3 * x[:, 2]
    check(np.max(np.abs(lin[valid, 0] - exact[valid]), initial=0) < 1e-11, "2D linear field exact in parallel")

# A new time step of the Source field: the kept operator is reused on every
# process, and the result is the serial one for the new field.
lt, ls = split(mpi.numbered(t2), "random", "input"), split(s2, "random", "source")
f = meshprojection.vtkPMeshProjectionFilter()
f.SetInputData(lt)
f.SetSourceData(ls)
f.Update()
check(f.GetNumberOfOperatorsBuilt() > 0, "time: built at the first step")
# (Inputs given as data are not time series: the second execution sees the
# same meshes and keeps an assembled operator, the third reuses it.)
for step in (2, 3):
    for data in (ls, s2):
        a = data.GetPointData().GetArray("f")
        for i in range(a.GetNumberOfTuples()):
            a.SetValue(i, 2.0 * a.GetValue(i) + 1.0)
        a.Modified()
        data.Modified()
    f.Update()
check(f.GetNumberOfOperatorsBuilt() == 0, "time: the operator is reused at the third step (built %d)"
      % f.GetNumberOfOperatorsBuilt())
check(f.GetOperatorReused(), "time: OperatorReused at the third step")
serial = run(meshprojection.vtkMeshProjectionFilter, t2, s2, CacheOperator=False)
compare("time step 3", serial.GetOutputDataObject(0), f.GetOutputDataObject(0),
        {"f": float(np.ptp(vtk_to_numpy(s2.GetPointData().GetArray("f")))), "linear": 1.0, "cellf": 1.0})

# A corrupt Source or Input part (a cell naming a point that does not
# exist) on one process: an error on every process, as the serial filter
# gives, before the gathering reads any cell (it once read and wrote out of
# the arrays there), and no crash.
for role in ("Source", "Input"):
    for bad_id in (lambda n: n, lambda n: -1, lambda n: n + 100000000):
        lt, ls = split(mpi.numbered(t2), "blocks", "input"), split(s2, "blocks", "source")
        spoiled = ls if role == "Source" else lt
        if rank == size - 1 and spoiled.GetNumberOfCells() > 0:
            c = vtk_to_numpy(spoiled.GetCells().GetConnectivityArray())
            c[0] = bad_id(spoiled.GetNumberOfPoints())
            spoiled.GetCells().GetConnectivityArray().Modified()
        spoilt = meshprojection.vtkPMeshProjectionFilter()
        errors = []

        @calldata_type(VTK_STRING)
        def collect_error(obj, event, text):
            errors.append(str(text))

        spoilt.AddObserver("ErrorEvent", collect_error)
        spoilt.SetInputData(lt)
        spoilt.SetSourceData(ls)
        spoilt.Update()
        said = any(("%s: cell 0 refers to point" % role) in e for e in errors)
        check(all(int(v[0]) for v in allgather([1.0 if said else 0.0])),
              "corrupt %s: the error on every process (here: %s)" % (role, errors[:1]))
        out = spoilt.GetOutputDataObject(0)
        check(out is not None and out.GetPointData().GetArray("vtkValidPointMask") is None,
              "corrupt %s: nothing projected" % role)

# Stopped on one process only (AbortExecute, as the GUI's stop sets it),
# at several points of a composite Input's run: no process waits for the
# others, and all give the same kind of output (Input as it came, or all
# projected when the stop came too late to matter).
lt = split(mpi.numbered(t2), "random", "input")
ls = split(s2, "random", "source")
y = centres(lt)[:, 1] if lt.GetNumberOfCells() else np.zeros(0)
blocks = vtkMultiBlockDataSet()
blocks.SetNumberOfBlocks(3)
for b, keep in enumerate((y < 0.3, (y >= 0.3) & (y < 0.7), y >= 0.7)):
    blocks.SetBlock(b, extract(lt, keep) if lt.GetNumberOfCells() else vtkUnstructuredGrid())
for at in (0.01, 0.06, 0.2, 0.36, 0.5, 0.62, 0.9, 0.97):
    stopped = meshprojection.vtkPMeshProjectionFilter()

    def stop(obj, event, at=at):
        if rank == size - 1 and obj.GetProgress() >= at:
            obj.SetAbortExecute(1)

    stopped.AddObserver("ProgressEvent", stop)
    stopped.SetInputData(blocks)
    stopped.SetSourceData(ls)
    stopped.Update()
    out = stopped.GetOutputDataObject(0)
    projected = [out.GetBlock(b) is not None and out.GetBlock(b).GetPointData().GetArray("vtkValidPointMask") is not None
                 and out.GetBlock(b).GetNumberOfCells() > 0 for b in range(3)]
    kinds = allgather([float(any(projected))])
    check(len({int(v[0]) for v in kinds}) == 1,
          "stopped at %g on the last process: projected on processes %s" % (at, [int(v[0]) for v in kinds]))
    check(at > 0.9 or not any(int(v[0]) for v in kinds), "stopped at %g: nothing projected" % at)

# Global statistics: totals over the processes.
check(f.GetGlobalNumberOfIntersections() >= f.GetNumberOfIntersections(), "global pieces >= local")
check(abs(f.GetGlobalCoveredMeasure() - serial.GetCoveredMeasure()) < 1e-12,
      "global covered measure %.15g vs serial %.15g" % (f.GetGlobalCoveredMeasure(), serial.GetCoveredMeasure()))

check.finish("%d processes" % size)
