#!/usr/bin/python3
"""Bit-for-bit comparison of the filter's outputs between two builds (a
refactoring must not change any output: issue #52).

    compare_outputs.py dump --build BUILD_DIR --out FILE.npz [--mpi 2]
    compare_outputs.py compare A.npz B.npz [--ignore REGEX] [--quiet]

`dump` runs vtkMeshProjectionFilter (or, with --mpi N, vtkPMeshProjectionFilter
on N processes under `mpiexec ... pvbatch --mpi --symmetric`) of BUILD_DIR's
`meshprojection` package over a fixed set of cases x settings x numberings
and writes every output array into one .npz: output 0's point, cell and
field data (projected arrays, masks, CoveredFraction, SourceIntegral_ and
TargetIntegral_), the intersection outputs 1 and 2 (setting "default", not
on the two large cases), the
deterministic statistics (counts, covered measure, operator reuse; no
times), the warning and error texts, and the exported matrices (setting
"matrices": M_tt, M_ts, P, E as CSR arrays). Keys read
case/setting/numbering/what; with --mpi, `what` starts with the rank (each
process's own arrays, in its own numbering, with the Input's origId arrays
mapping them to the whole meshes).

`compare` prints per case/setting how many arrays are bit-for-bit equal,
each array that differs (max abs and relative difference, NaN places), the
arrays present in one file only, and a last line
`N arrays: X identical, Y differ (max rel diff Z), W missing`; exit code 0
only when every array is identical and none is missing.

With the reference dumps of current main in /work/tools (ref-serial.npz,
ref-mpi2.npz; made from /work/main/build):
    /usr/bin/python3 Scripts/compare_outputs.py dump --build build --out /tmp/mine.npz
    /usr/bin/python3 Scripts/compare_outputs.py compare /work/tools/ref-serial.npz /tmp/mine.npz
    /usr/bin/python3 Scripts/compare_outputs.py dump --build build --mpi 2 --out /tmp/mine-mpi2.npz
    /usr/bin/python3 Scripts/compare_outputs.py compare /work/tools/ref-mpi2.npz /tmp/mine-mpi2.npz

Cases (jittered numpy grids of mpsupport.meshes, Gmsh meshes of mpsupport.gmshmeshes and
Testing/Data/Gmsh): 2D triangles, 2D quads, a 2D pair in a tilted plane, 3D
tetrahedra, mixed hexahedra/wedges/pyramids/tetrahedra, image data, a sphere
surface pair, a circle curve pair, a trace (plane in a volume), a composite
Input and Source, partly overlapping 2D and 3D Gmsh pairs (the fringe), NaN
holes in Source arrays, extensive cell data, and a larger 2D and 3D pair
(above the automatic renumbering's 4,096 simplices). Point and cell data in every
case (smooth and linear). Settings: default (with the intersection outputs),
lumped mass, PreserveBounds, linear limited and unlimited reconstruction,
Extrapolation smooth and nearest, FringeThreshold 0, the direct solver, a
one-off run (CacheOperator off), FillValue with ConserveSourceIntegral, one
thread, brute-force search (not on the large cases), a time series on a kept
operator (two executions, the Source's values changed between them) and the
exported matrices (two cases). Numberings: as generated ("gen"), points and
cells shuffled ("shuf"), and "renum" (MESHPROJECTION_RENUMBERING=always).
With --mpi: each process takes a random part of the cells of both meshes,
numberings gen and shuf, without the brute, threads1 and unlimited settings.
A serial dump takes about a minute, a 2-process one two to three.
"""
import argparse
import os
import re
import subprocess
import sys
import time

SETTINGS = {
    "default": {"OutputIntersections": True},
    "lumped": {"MassMatrix": 1},
    "bounds": {"PreserveBounds": True},
    "linlim": {"CellDataReconstruction": 1},
    "smooth": {"Extrapolation": 1},
    "nearest": {"Extrapolation": 2},
    "fringe0": {"FringeThreshold": 0.0},
    "unlimited": {"CellDataReconstruction": 2},
    "direct": {"MaximumIterations": 0},
    "oneoff": {"CacheOperator": False},
    "fill": {"FillWithNaN": False, "FillValue": -7.0, "ConserveSourceIntegral": True},
    "threads1": {"NumberOfThreads": 1},
    "brute": {"SearchMethod": 1},
    "time": {"CacheOperator": True},
    "matrices": {"CacheOperator": True, "Extrapolation": 1},
}
# The cases whose matrices are exported (setting "matrices").
MATRIX_CASES = ("tri2d", "fringe2d")
# Settings left out on the large cases (brute force is O(n m)).
SMALL_ONLY = ("brute",)
NUMBERINGS = ("gen", "shuf", "renum")
# On several processes (the same kernel runs on each): fewer runs, to keep the dump short.
MPI_NUMBERINGS = ("gen", "shuf")
MPI_SKIPPED = ("brute", "threads1", "unlimited")
STATISTICS = ("NumberOfIntersections", "NumberOfIntersectionTests", "NumberOfLocatorQueries", "CoveredMeasure",
              "OperatorReused", "NumberOfOperatorsBuilt", "NumberOfRenumberedMeshes", "OperatorMemory")


# ---------------------------------------------------------------- driver ----
def python_path(build):
    """The directory of BUILD's `meshprojection` and `mpsupport` packages."""
    for root, dirs, _ in os.walk(build):
        if "meshprojection" in dirs and "mpsupport" in dirs:
            return root
        dirs[:] = [d for d in dirs if d not in ("CMakeFiles", "Testing", "Benchmarks", "Examples", "Plugin", "bin")]
    sys.exit("no directory with meshprojection/ and mpsupport/ under " + build)


def dump(args):
    env = dict(os.environ)
    env["PYTHONPATH"] = python_path(os.path.abspath(args.build))
    env.pop("MESHPROJECTION_RENUMBERING", None)
    out = os.path.abspath(args.out)
    worker = [os.path.abspath(__file__), "_worker", "--out", out]
    if args.only:
        worker += ["--only", args.only]
    if args.verbose:
        worker += ["--verbose"]
    if args.mpi:
        command = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(args.mpi),
                   "pvbatch", "--mpi", "--symmetric"] + worker + ["--mpi"]
    else:
        command = ["/usr/bin/python3"] + worker
    start = time.time()
    status = subprocess.call(command, env=env)
    if status != 0 or not os.path.exists(out):
        sys.exit("dump failed (exit code %d)" % status)
    print("wrote %s in %.1f s" % (out, time.time() - start))


# ---------------------------------------------------------------- worker ----
def _load_vtk():
    """The names the worker's functions use, imported in the worker only (`compare`
    needs numpy alone, `dump` nothing)."""
    global np, meshprojection, gmshmeshes, meshes, GMSH, cut
    global calldata_type, numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy, VTK_STRING, vtkStringArray
    global VTK_HEXAHEDRON, VTK_QUAD, VTK_TETRA, VTK_TRIANGLE, vtkCellArray, vtkCompositeDataSet
    global vtkDataObjectTreeIterator, vtkDataSet, vtkImageData, vtkMultiBlockDataSet, vtkPolyData
    global vtkUnstructuredGrid, vtkTransform, vtkCellCenters, vtkTransformFilter, vtkXMLUnstructuredGridReader
    import numpy as np
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
    from vtkmodules.vtkCommonCore import VTK_STRING, vtkStringArray
    from vtkmodules.vtkCommonDataModel import (VTK_HEXAHEDRON, VTK_QUAD, VTK_TETRA, VTK_TRIANGLE, vtkCellArray,
                                               vtkCompositeDataSet, vtkDataObjectTreeIterator, vtkDataSet,
                                               vtkImageData, vtkMultiBlockDataSet, vtkPolyData, vtkUnstructuredGrid)
    from vtkmodules.vtkCommonTransforms import vtkTransform
    from vtkmodules.vtkFiltersCore import vtkCellCenters
    from vtkmodules.vtkFiltersGeneral import vtkTransformFilter
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    import meshprojection
    from mpsupport import gmshmeshes, meshes
    from mpsupport.testing import GMSH, cut


# ---- meshes and fields ----
def read(name):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(GMSH, name))
    reader.Update()
    return reader.GetOutput()

def bare(ds):
    """A deep copy of ds without point and cell arrays."""
    copy = ds.NewInstance()
    copy.DeepCopy(ds)
    for data in (copy.GetPointData(), copy.GetCellData()):
        while data.GetNumberOfArrays():
            data.RemoveArray(0)
    return copy

def smooth(x):
    return np.sin(2 * x[:, 0]) * np.cos(3 * x[:, 1]) + x[:, 2] ** 2

def linear(x):
    return np.stack([1 + 2 * x[:, 0] - 3 * x[:, 1] + 0.5 * x[:, 2], x[:, 0] - x[:, 2]], 1)

def add(data, name, values):
    a = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float64), deep=True)
    a.SetName(name)
    data.AddArray(a)

def points_of(ds):
    return np.array([ds.GetPoint(i) for i in range(ds.GetNumberOfPoints())]) if isinstance(ds, vtkImageData) \
        else vtk_to_numpy(ds.GetPoints().GetData())

def centres_of(ds):
    c = vtkCellCenters()
    c.SetInputData(ds)
    c.Update()
    return vtk_to_numpy(c.GetOutput().GetPoints().GetData())

def with_fields(ds, nan=False, extensive=False):
    """ds (bare) with point arrays s (smooth) and lin (2 components),
    cell array c (smooth at centres); NaN holes in s and c; an
    extensive cell array `mass` (the smooth field times a cell's share)."""
    ds = bare(ds)
    x, c = points_of(ds), centres_of(ds)
    s, cs = smooth(x), smooth(c)
    if nan:
        s[(x[:, 0] < 0.35) & (x[:, 1] < 0.3)] = np.nan
        cs[(c[:, 0] > 0.6) & (c[:, 1] > 0.55)] = np.nan
    add(ds.GetPointData(), "s", s)
    add(ds.GetPointData(), "lin", linear(x))
    add(ds.GetCellData(), "c", cs)
    if extensive:
        add(ds.GetCellData(), "mass", (2 + cs) / ds.GetNumberOfCells())
    return ds

def grid(points_cells, cell_type):
    return meshes.grid(*points_cells, cell_type)

def transformed(ds, angle, axis, translate=(0, 0, 0)):
    t = vtkTransform()
    t.Translate(*translate)
    t.RotateWXYZ(angle, *axis)
    f = vtkTransformFilter()
    f.SetTransform(t)
    f.SetInputData(ds)
    f.Update()
    out = f.GetOutput().NewInstance()
    out.ShallowCopy(f.GetOutput())
    return out

def image(n, lo, hi):
    im = vtkImageData()
    im.SetDimensions(n + 1, n + 1, n + 1)
    im.SetOrigin(lo, lo, lo)
    im.SetSpacing(*((hi - lo) / n,) * 3)
    return im

def multiblock(blocks):
    mb = vtkMultiBlockDataSet()
    for i, b in enumerate(blocks):
        mb.SetBlock(i, b)
    return mb


unit = ((0, 0, 0), (1, 1, 1))
big = ((-0.05, -0.05, -0.05), (1.05, 1.05, 1.05))


# ---- the cases ----
def c_tri2d():
    return (bare(grid(meshes.triangles(14, *unit, seed=1), VTK_TRIANGLE)),
            with_fields(grid(meshes.triangles(17, *unit, seed=2), VTK_TRIANGLE)),
            {"PointDataTarget": 3, "CellDataTarget": 3})

def c_quad2d():
    return (bare(grid(meshes.quads(12, *unit, seed=3), VTK_QUAD)),
            with_fields(grid(meshes.quads(15, *big, seed=4), VTK_QUAD)), {})

def c_tilted2d():
    t = grid(meshes.triangles(13, *unit, seed=5), VTK_TRIANGLE)
    s = with_fields(grid(meshes.quads(11, *unit, seed=6), VTK_QUAD))
    return (bare(transformed(t, 35, (1, 1, 0), (0.2, 0, 0.1))), transformed(s, 35, (1, 1, 0), (0.2, 0, 0.1)),
            {"CellDataTarget": 3})

def c_tets3d():
    return (bare(grid(meshes.tetrahedra(5, *unit, seed=7), VTK_TETRA)), with_fields(read("tets_box.vtu")),
            {"PointDataTarget": 3, "CellDataTarget": 3})

def c_mixed3d():
    return bare(read("mixed_box.vtu")), with_fields(read("hexes_box.vtu")), {"CellDataTarget": 3}

def c_image():
    return image(8, -0.02, 1.02), with_fields(grid(meshes.hexahedra(6, *unit, seed=8), VTK_HEXAHEDRON)), \
        {"CellDataTarget": 3}

def c_sphere():
    return (bare(gmshmeshes.surface("sphere", 0.25)), with_fields(gmshmeshes.surface("sphere", 0.3, algorithm=5)),
            {"CellDataTarget": 3})

def c_curve():
    return bare(gmshmeshes.curve("circle", 0.1)), with_fields(gmshmeshes.curve("circle", 0.137)), \
        {"CellDataTarget": 3}

def c_trace():
    return bare(gmshmeshes.surface("patch0.37", 0.1)), with_fields(gmshmeshes.volume("box", 0.2)), \
        {"CellDataTarget": 3}

def c_composite():
    t = grid(meshes.triangles(12, *unit, seed=9), VTK_TRIANGLE)
    s = with_fields(grid(meshes.quads(14, *big, seed=10), VTK_QUAD))
    return (multiblock([bare(cut(t, lambda c: c[:, 0] < 0.5)), bare(cut(t, lambda c: c[:, 0] >= 0.5))]),
            multiblock([cut(s, lambda c: c[:, 1] < 0.4), cut(s, lambda c: c[:, 1] >= 0.4)]),
            {"CellDataTarget": 3})

def c_fringe2d():
    return (bare(transformed(read("tris_disk.vtu"), 0, (0, 0, 1), (0.3, 0.2, 0))),
            with_fields(read("quads_disk.vtu")), {"PointDataTarget": 3, "CellDataTarget": 3})

def c_fringe3d():
    return (bare(transformed(read("wedges_cylinder.vtu"), 0, (0, 0, 1), (0.27, 0.13, 0.21))),
            with_fields(read("hexes_box.vtu")), {"CellDataTarget": 3})

def c_nan():
    return (bare(grid(meshes.quads(12, *unit, seed=11), VTK_QUAD)),
            with_fields(grid(meshes.triangles(15, *unit, seed=12), VTK_TRIANGLE), nan=True),
            {"CellDataTarget": 3})

def c_extensive():
    return (bare(grid(meshes.quads(13, *unit, seed=13), VTK_QUAD)),
            with_fields(grid(meshes.triangles(11, *big, seed=14), VTK_TRIANGLE), extensive=True),
            {"CellDataTarget": 3, "CellDataQuantity": 1})

def c_big2d():
    return (bare(grid(meshes.triangles(60, *unit, seed=15), VTK_TRIANGLE)),
            with_fields(grid(meshes.quads(50, *big, seed=16), VTK_QUAD)), {"CellDataTarget": 3})

def c_big3d():
    return (bare(grid(meshes.tetrahedra(13, *unit, seed=17, jitter=0.15), VTK_TETRA)),
            with_fields(grid(meshes.hexahedra(12, *big, seed=18), VTK_HEXAHEDRON)),
            {"PointDataTarget": 3, "CellDataTarget": 3})


# ---- numberings and partitions ----
def leaves(obj):
    """[(index, dataset)] of a dataset or the leaves of a composite one."""
    if isinstance(obj, vtkDataSet):
        return [("", obj)]
    it = vtkDataObjectTreeIterator()
    it.SetDataSet(obj)
    it.InitTraversal()
    found = []
    while not it.IsDoneWithTraversal():
        found.append(("b%d." % it.GetCurrentFlatIndex(), it.GetCurrentDataObject()))
        it.GoToNextItem()
    return found

def map_leaves(obj, fn):
    if isinstance(obj, vtkDataSet):
        return fn(obj)
    mb = vtkMultiBlockDataSet()
    for i in range(obj.GetNumberOfBlocks()):
        mb.SetBlock(i, fn(obj.GetBlock(i)))
    return mb

def cell_arrays(ds):
    cells = ds.GetCells() if isinstance(ds, vtkUnstructuredGrid) else \
        (ds.GetPolys() if ds.GetNumberOfPolys() else ds.GetLines())
    return vtk_to_numpy(cells.GetOffsetsArray()), vtk_to_numpy(cells.GetConnectivityArray())

def renumbered(ds, p, q):
    """ds with new point k = old point p[k] and new cell k = old cell q[k]."""
    offsets, conn = cell_arrays(ds)
    inv = np.empty(len(p), dtype=np.int64)
    inv[p] = np.arange(len(p))
    sizes = np.diff(offsets)[q]
    new_offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    take = np.repeat(offsets[:-1][q] - new_offsets[:-1], sizes) + np.arange(new_offsets[-1])
    ca = vtkCellArray()
    ca.SetData(numpy_to_vtkIdTypeArray(new_offsets, deep=True),
               numpy_to_vtkIdTypeArray(np.ascontiguousarray(inv[conn[take]]), deep=True))
    out = ds.NewInstance()
    pts = ds.GetPoints().NewInstance()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(vtk_to_numpy(ds.GetPoints().GetData())[p]), deep=True))
    out.SetPoints(pts)
    if isinstance(ds, vtkUnstructuredGrid):
        out.SetCells(numpy_to_vtk(np.ascontiguousarray(vtk_to_numpy(ds.GetCellTypesArray())[q]), deep=True,
                                  array_type=ds.GetCellTypesArray().GetDataType()), ca)
    elif ds.GetNumberOfPolys():
        out.SetPolys(ca)
    else:
        out.SetLines(ca)
    for src, dst, perm in ((ds.GetPointData(), out.GetPointData(), p), (ds.GetCellData(), out.GetCellData(), q)):
        for i in range(src.GetNumberOfArrays()):
            a = src.GetArray(i)
            b = numpy_to_vtk(np.ascontiguousarray(vtk_to_numpy(a)[perm]), deep=True, array_type=a.GetDataType())
            b.SetName(a.GetName())
            dst.AddArray(b)
    return out

def shuffled(ds, seed):
    if isinstance(ds, vtkImageData):
        return ds
    rng = np.random.default_rng(seed)
    return renumbered(ds, rng.permutation(ds.GetNumberOfPoints()), rng.permutation(ds.GetNumberOfCells()))

def part(ds, seed, origin, rank, size):
    """Process `rank`'s cells of ds (a random owner per cell among `size` processes),
    with origId arrays on the Input."""
    if isinstance(ds, vtkImageData):
        ug = vtkUnstructuredGrid()
        from vtkmodules.vtkFiltersCore import vtkAppendFilter
        a = vtkAppendFilter()
        a.AddInputData(ds)
        a.Update()
        ug.ShallowCopy(a.GetOutput())
        ds = ug
    if origin:
        copy = ds.NewInstance()
        copy.ShallowCopy(ds)
        for data, n in ((copy.GetPointData(), copy.GetNumberOfPoints()),
                        (copy.GetCellData(), copy.GetNumberOfCells())):
            a = numpy_to_vtkIdTypeArray(np.arange(n, dtype=np.int64), deep=True)
            a.SetName("origId")
            data.AddArray(a)
        ds = copy
    owner = np.random.default_rng(seed).integers(0, size, ds.GetNumberOfCells())
    return meshes.extract(ds, owner == rank)


# ---- the runs ----
def changed(source):
    """A copy of the Source with every field's values changed (2u + 1)."""
    copy = source.NewInstance()
    copy.DeepCopy(source)
    for _, ds in leaves(copy):
        for data in (ds.GetPointData(), ds.GetCellData()):
            for i in range(data.GetNumberOfArrays()):
                u = vtk_to_numpy(data.GetArray(i))
                u *= 2
                u += 1
                data.GetArray(i).Modified()
    return copy


def cleaned(text):
    """A message without what changes from run to run or with a refactoring: the object's
    address and the source file and line of the macro."""
    text = re.sub(r"^\w+: In [^\n]*, line \d+\n", "", str(text))
    return re.sub(r"\(0x[0-9a-fA-F]+\)", "", text).strip()


class Runs:
    """The runs of one process and everything they output, by key."""

    def __init__(self, mpi, rank):
        self.mpi = mpi
        self.rank = rank
        self.record = {}

    def put(self, key, value):
        self.record[key] = np.asarray(value)

    def harvest(self, prefix, f, ports):
        for port in ports:
            out = f.GetOutputDataObject(port)
            for index, ds in leaves(out):
                head = "%sout%d.%s" % (prefix, port, index)
                if port > 0:
                    pts = ds.GetPoints()
                    if pts is not None:
                        self.put(head + "points", vtk_to_numpy(pts.GetData()).copy())
                for kind, data in (("point", ds.GetPointData()), ("cell", ds.GetCellData()),
                                   ("field", ds.GetFieldData())):
                    for i in range(data.GetNumberOfArrays()):
                        a = data.GetAbstractArray(i)
                        name = "%s%s.%s" % (head, kind, a.GetName())
                        if isinstance(a, vtkStringArray):
                            self.put(name, np.array([a.GetValue(k) for k in range(a.GetNumberOfValues())], dtype=str))
                        else:
                            self.put(name, vtk_to_numpy(a).copy())
        for s in STATISTICS:
            if hasattr(f, "Get" + s):
                self.put(prefix + "stat." + s, getattr(f, "Get" + s)())

    def matrices(self, prefix, f):
        for t in meshprojection.matrices.TRANSFERS:
            for what, get in (("M", meshprojection.operator_matrices), ("P", meshprojection.fringe_extension),
                              ("E", meshprojection.extrapolation_matrix)):
                try:
                    m = get(f, t)
                except RuntimeError as e:
                    self.put("%smatrix.%s.%s.error" % (prefix, t, what), str(e))
                    continue
                for label, mat in ((("tt", m[0]), ("ts", m[1])) if what == "M" else ((what, m),)):
                    for part_name in ("indptr", "indices", "data"):
                        self.put("%smatrix.%s.%s.%s" % (prefix, t, label, part_name), getattr(mat, part_name))
                    self.put("%smatrix.%s.%s.shape" % (prefix, t, label), np.array(mat.shape))

    def run(self, key, target, source, props, setting):
        f = (meshprojection.vtkPMeshProjectionFilter if self.mpi else meshprojection.vtkMeshProjectionFilter)()
        texts = []

        @calldata_type(VTK_STRING)
        def collect(obj, event, text):
            texts.append("%s: %s" % (event, cleaned(text)))

        for event in ("WarningEvent", "ErrorEvent"):
            f.AddObserver(event, collect)
        f.GetExecutive().AddObserver("ErrorEvent", collect)
        f.SetInputData(target)
        f.SetSourceData(source)
        for name, value in list(props.items()) + list(SETTINGS[setting].items()):
            getattr(f, "Set" + name)(value)
        if setting == "matrices":
            # A setter keeping the matrices (M_ts) for GetMatrix, where the API has one.
            for name in dir(f):
                if re.match(r"^Set(Keep\w*Matri\w*)$", name):
                    getattr(f, name)(True)
        prefix = key + ("r%d." % self.rank if self.mpi else "")
        f.Update()
        # The intersection pieces on the small cases only (the large ones' tetrahedra would fill the file).
        pieces = setting == "default" and not key.startswith("big")
        self.harvest(prefix + ("step0." if setting == "time" else ""), f, (0, 1, 2) if pieces else (0,))
        if setting == "time":
            f.SetSourceData(changed(source))
            f.Update()
            self.harvest(prefix + "step1.", f, (0,))
        if setting == "matrices":
            self.matrices(prefix, f)
        self.put(prefix + "messages", "\n".join(texts))


def all_cases():
    """[(name, make)]: make() gives (Input, Source, the case's properties)."""
    return [("tri2d", c_tri2d), ("quad2d", c_quad2d), ("tilted2d", c_tilted2d), ("tets3d", c_tets3d),
            ("mixed3d", c_mixed3d), ("image", c_image), ("sphere", c_sphere), ("curve", c_curve),
            ("trace", c_trace), ("composite", c_composite), ("fringe2d", c_fringe2d), ("fringe3d", c_fringe3d),
            ("nan", c_nan), ("extensive", c_extensive), ("big2d", c_big2d), ("big3d", c_big3d)]


def worker(args):
    _load_vtk()
    rank, size, controller = 0, 1, None
    if args.mpi:
        from mpsupport import mpi
        controller, _ = mpi.start()
        rank, size = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
    runs = Runs(args.mpi, rank)
    record = runs.record
    run = runs.run
    cases = all_cases()

    only = re.compile(args.only) if args.only else None
    numberings = MPI_NUMBERINGS if args.mpi else NUMBERINGS
    for case, make in cases:
        started = time.time()
        target0, source0, props = make()
        for numbering in numberings:
            if numbering == "shuf":
                target = map_leaves(target0, lambda d: shuffled(d, 21))
                source = map_leaves(source0, lambda d: shuffled(d, 22))
            else:
                target, source = target0, source0
            if args.mpi:
                target = map_leaves(target, lambda d: part(d, 7, True, rank, size))
                source = map_leaves(source, lambda d: part(d, 8, False, rank, size))
            for setting in SETTINGS:
                if setting == "matrices" and (case not in MATRIX_CASES or numbering != "gen"):
                    continue
                if setting in SMALL_ONLY and case.startswith("big"):
                    continue
                if args.mpi and setting in MPI_SKIPPED:
                    continue
                key = "%s/%s/%s/" % (case, setting, numbering)
                if only and not only.search(key):
                    continue
                if numbering == "renum":
                    os.environ["MESHPROJECTION_RENUMBERING"] = "always"
                try:
                    run(key, target, source, props, setting)
                finally:
                    os.environ.pop("MESHPROJECTION_RENUMBERING", None)
        if args.verbose and rank == 0:
            print("%-10s %6.2f s" % (case, time.time() - started), file=sys.stderr, flush=True)

    if not args.mpi:
        np.savez(args.out, **record)
        return
    np.savez("%s.rank%d.npz" % (args.out, rank), **record)
    controller.Barrier()
    if rank == 0:
        merge_ranks(args.out, size)
    controller.Barrier()


def merge_ranks(out, size):
    """The processes' files OUT.rank<r>.npz merged into OUT (and removed)."""
    merged = {}
    for r in range(size):
        part_file = "%s.rank%d.npz" % (out, r)
        with np.load(part_file) as z:
            merged.update({k: z[k] for k in z.files})
        os.remove(part_file)
    np.savez(out, **merged)


# --------------------------------------------------------------- compare ----
def compare(args):
    import numpy as np
    ignore = re.compile(args.ignore) if args.ignore else None
    with np.load(args.a) as za, np.load(args.b) as zb:
        keys_a = {k for k in za.files if not (ignore and ignore.search(k))}
        keys_b = {k for k in zb.files if not (ignore and ignore.search(k))}
        groups = {}
        differ = []
        worst = 0.0
        for key in sorted(keys_a | keys_b):
            group = "/".join(key.split("/")[:2])
            g = groups.setdefault(group, [0, 0, 0, 0])  # arrays, identical, differ, missing
            g[0] += 1
            if key not in keys_a or key not in keys_b:
                g[3] += 1
                differ.append("%s: only in %s" % (key, args.a if key in keys_a else args.b))
                continue
            a, b = za[key], zb[key]
            if a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes():
                g[1] += 1
                continue
            g[2] += 1
            text, rel = describe(np, a, b)
            if rel == rel:  # (texts give NaN: no number)
                worst = max(worst, rel)
            differ.append("%s: %s" % (key, text))
    if not args.quiet:
        width = max(len(k) for k in groups) if groups else 0
        for group, (n, same, diff, missing) in groups.items():
            print("%-*s %4d arrays: %4d identical%s%s" % (width, group, n, same,
                  ", %d differ" % diff if diff else "", ", %d missing" % missing if missing else ""))
    if differ:
        print("\nNot identical:")
        for line in differ:
            print("  " + line)
    total = sum(g[0] for g in groups.values())
    same = sum(g[1] for g in groups.values())
    diff = sum(g[2] for g in groups.values())
    missing = sum(g[3] for g in groups.values())
    print("%d arrays: %d identical, %d differ (max rel diff %.3g), %d missing" % (total, same, diff, worst, missing))
    return 0 if same == total else 1


def describe(np, a, b):
    """What differs between two arrays of one key, and the relative difference (inf: not
    comparable numbers, NaN: texts)."""
    if a.shape != b.shape:
        return "shape %s vs %s" % (a.shape, b.shape), float("inf")
    if a.dtype.kind in "US" or b.dtype.kind in "US":
        ta, tb = str(a), str(b)
        at = next((k for k, (p, q) in enumerate(zip(ta, tb)) if p != q), min(len(ta), len(tb)))
        start = max(0, at - 60)
        return "text differs from character %d: %r vs %r" % (at, ta[start:at + 140], tb[start:at + 140]), \
            float("nan")
    x, y = a.astype(np.float64), b.astype(np.float64)
    nan_a, nan_b = np.isnan(x), np.isnan(y)
    both = ~nan_a & ~nan_b
    d = np.abs(x[both] - y[both])
    maxabs = float(d.max()) if d.size else 0.0
    scale = float(max(np.abs(x[both]).max(), np.abs(y[both]).max())) if d.size else 0.0
    rel = maxabs / scale if scale > 0 else (0.0 if maxabs == 0 else float("inf"))
    count = int(np.count_nonzero(x[both] != y[both]))
    text = "%d of %d values differ, max abs %.3g, max rel %.3g" % (count, x.size, maxabs, rel)
    if (nan_a != nan_b).any():
        text += ", NaN at %d other places" % int(np.count_nonzero(nan_a != nan_b))
        rel = float("inf")
    if a.dtype != b.dtype:
        text += ", dtype %s vs %s" % (a.dtype, b.dtype)
    return text, rel


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    d = sub.add_parser("dump", help="run the cases with a build and write every output array")
    d.add_argument("--build", required=True, help="the build directory (its meshprojection package)")
    d.add_argument("--out", required=True, help="the .npz to write")
    d.add_argument("--mpi", type=int, default=0, help="number of MPI processes (pvbatch), 0: serial")
    d.add_argument("--only", help="a regex on case/setting/numbering/: only the runs it matches")
    d.add_argument("--verbose", action="store_true", help="the seconds of each case")
    c = sub.add_parser("compare", help="compare two dumps bit for bit")
    c.add_argument("a")
    c.add_argument("b")
    c.add_argument("--ignore", help="a regex: keys it matches are left out")
    c.add_argument("--quiet", action="store_true", help="no per-group lines")
    w = sub.add_parser("_worker")
    w.add_argument("--out", required=True)
    w.add_argument("--mpi", action="store_true")
    w.add_argument("--only")
    w.add_argument("--verbose", action="store_true")
    args = parser.parse_args()
    if args.command == "dump":
        dump(args)
    elif args.command == "compare":
        sys.exit(compare(args))
    else:
        worker(args)


if __name__ == "__main__":
    main()
