"""Helpers shared by the Python tests: sample data, exact P1 integrals, image comparison,
meshes cut into blocks and multiblock files."""
import os
import sys

try:
    # The build's copy of the package: CMake writes where the sources are.
    from ._paths import SOURCE_DIR
except ImportError:
    # Imported from the source tree (Testing/Support/Python/mpsupport).
    SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.dirname(os.path.abspath(__file__))))))
DATA = os.path.join(SOURCE_DIR, "Data")
GMSH = os.path.join(SOURCE_DIR, "Testing", "Data", "Gmsh")
BASELINES = os.path.join(SOURCE_DIR, "Plugin", "Testing", "Python", "Baseline")

failures = []


def check(condition, what):
    """Record a failed check and go on, so one run shows every problem."""
    if not condition:
        failures.append(what)
        print("FAILED: " + what, file=sys.stderr)


def finish():
    if failures:
        print("%d check(s) failed" % len(failures), file=sys.stderr)
        sys.exit(1)
    print("all checks passed")
    sys.exit(0)


def read(name):
    """A .vtu file of Data/, or any path."""
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(DATA, name))
    reader.Update()
    return reader.GetOutput()


def read_step(pvd, k):
    """Step k of a series written by write_series, read directly."""
    return read(os.path.join(os.path.dirname(pvd), "%s_%d.vtu" % (os.path.basename(pvd)[:-4], k)))


def fresh_projection(target_grid, source_grid):
    """The wrapped filter's output on two grids, nothing kept."""
    import meshprojection
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetCacheOperator(False)
    f.SetInputData(target_grid)
    f.SetSourceData(source_grid)
    f.Update()
    return f.GetOutput()


def mortar(target, source, brute=False, pieces=True, **properties):
    """The wrapped filter, updated on two datasets (nothing kept), with the
    intersection pieces unless told otherwise and any property by name
    (SurfaceReach=0.05 calls SetSurfaceReach(0.05))."""
    import meshprojection
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetOutputIntersections(pieces)
    f.SetCacheOperator(False)
    if brute:
        f.SetSearchMethodToBruteForce()
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f


def observed_filter(*events):
    """A fresh filter and the list its messages of the given events
    ("WarningEvent", "ErrorEvent": also the executive's) are collected in."""
    import meshprojection
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.vtkCommonCore import VTK_STRING
    texts = []

    @calldata_type(VTK_STRING)
    def collect(obj, event, text):
        texts.append(str(text))

    f = meshprojection.vtkMeshProjectionFilter()
    for event in events:
        f.AddObserver(event, collect)
        if event == "ErrorEvent":
            f.GetExecutive().AddObserver(event, collect)
    return f, texts


def covered_by_pieces(f, target):
    """Per target cell, the summed measure of the filter `f`'s pieces (port 1:
    "Area" of polygons, or "Length" of segments when the target has lines)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    pieces = f.GetOutput(1)
    name = "Length" if target.GetNumberOfLines() else "Area"
    measure = vtk_to_numpy(pieces.GetCellData().GetArray(name))
    cell = vtk_to_numpy(pieces.GetCellData().GetArray("TargetCellId"))
    covered = np.zeros(target.GetNumberOfCells())
    np.add.at(covered, cell, measure)
    return covered


def integral(grid, name, component=0):
    """Exact integral of a P1 point array over a triangle or tetrahedron mesh
    (numpy, no VTK filter); returns (integral, area or volume)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    cells = _cells(grid)
    u = vtk_to_numpy(grid.GetPointData().GetArray(name))
    if u.ndim > 1:
        u = u[:, component]
    measure = cell_measures(grid)
    return float(np.sum(measure * u[cells].mean(axis=1))), float(measure.sum())


def compare_image(png, baseline_name, temp_dir, threshold=10):
    """Compare a PNG against Baseline/<baseline_name> (alternates _1, _2 allowed)."""
    from vtkmodules.vtkTestingRendering import vtkTesting
    testing = vtkTesting()
    for argument in ("-V", os.path.join(BASELINES, baseline_name), "-T", temp_dir):
        testing.AddArgument(argument)
    return testing.RegressionTest(png, threshold) == vtkTesting.PASSED


def write_series(directory, name, grid, steps, wave=True, move=None):
    """Writes `grid` at each time of `steps` as <name>_<k>.vtu (inline binary:
    Debian's expat cannot read VTK's appended data) and <name>.pvd, with a
    point array Wave and a cell array Heat that change with time; `move`
    (t -> (dx, dy, dz)) moves the points. Returns the PVD's path."""
    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
    os.makedirs(directory, exist_ok=True)
    entries = []
    for k, t in enumerate(steps):
        step = vtkUnstructuredGrid()
        step.DeepCopy(grid)
        x = vtk_to_numpy(step.GetPoints().GetData()).copy()
        if move is not None:
            x += np.asarray(move(t))
            step.GetPoints().SetData(numpy_to_vtk(x, deep=True))
        if wave:
            u = np.sin(2 * x[:, 0] + t) * np.cos(x[:, 1]) + t
            a = numpy_to_vtk(u, deep=True)
            a.SetName("Wave")
            step.GetPointData().AddArray(a)
            cells = _cells(step)
            c = x[cells].mean(axis=1)
            h = numpy_to_vtk(1 + (c[:, 0] > 0.5 + 0.1 * t) * (1 + t), deep=True)
            h.SetName("Heat")
            step.GetCellData().AddArray(h)
        path = os.path.join(directory, "%s_%d.vtu" % (name, k))
        writer = vtkXMLUnstructuredGridWriter()
        writer.SetFileName(path)
        writer.SetInputData(step)
        writer.SetDataModeToBinary()
        writer.Write()
        entries.append('    <DataSet timestep="%r" file="%s"/>' % (t, os.path.basename(path)))
    pvd = os.path.join(directory, name + ".pvd")
    with open(pvd, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n')
        f.write("\n".join(entries) + "\n  </Collection>\n</VTKFile>\n")
    return pvd


def _cells(grid):
    """The point ids of a mesh of triangles or of tetrahedra, one row per cell."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    offsets = vtk_to_numpy(grid.GetCells().GetOffsetsArray())
    corners = int(offsets[1] - offsets[0]) if len(offsets) > 1 else 3
    return vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, corners)


def cell_measures(grid):
    """Areas (triangles) or volumes (tetrahedra) of the cells (numpy)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    x = vtk_to_numpy(grid.GetPoints().GetData())
    cells = _cells(grid)
    e = x[cells[:, 1:]] - x[cells[:, :1]]
    if cells.shape[1] == 3:
        return 0.5 * np.abs(e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0])
    return np.abs(np.einsum("ij,ij->i", e[:, 0], np.cross(e[:, 1], e[:, 2]))) / 6


def cut(grid, keep):
    """The cells of `grid` whose centre satisfies keep(centres) (an (n, 3)
    array -> booleans), as a grid of their own (vtkExtractCells: the block has
    its own copies of the interface points)."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkIdList
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
    from vtkmodules.vtkFiltersCore import vtkCellCenters, vtkExtractCells
    centres = vtkCellCenters()
    centres.SetInputData(grid)
    centres.Update()
    c = vtk_to_numpy(centres.GetOutput().GetPoints().GetData()).astype(float)
    ids = vtkIdList()
    for i in np.nonzero(keep(c))[0]:
        ids.InsertNextId(int(i))
    extract = vtkExtractCells()
    extract.SetInputData(grid)
    extract.SetCellList(ids)
    extract.Update()
    block = vtkUnstructuredGrid()
    block.ShallowCopy(extract.GetOutput())
    for attributes in (block.GetPointData(), block.GetCellData()):
        for name in ("vtkOriginalCellIds", "vtkOriginalPointIds"):
            attributes.RemoveArray(name)  # ids, not fields: not for projecting
    return block


def write_multiblock(path, blocks):
    """Writes [(name, dataset), ...] as a .vtm of named blocks, inline binary
    (Debian's expat cannot read appended data); True on success."""
    from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkMultiBlockDataSet
    from vtkmodules.vtkIOXML import vtkXMLMultiBlockDataWriter
    mb = vtkMultiBlockDataSet()
    for i, (name, grid) in enumerate(blocks):
        mb.SetBlock(i, grid)
        mb.GetMetaData(i).Set(vtkCompositeDataSet.NAME(), name)
    writer = vtkXMLMultiBlockDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(mb)
    writer.SetDataModeToBinary()
    return writer.Write() == 1


def end_client_script(result, failures):
    """The end of a paraview --script test: PASS or the failures into the file
    `result`, then ParaView ended with the status (unless MP_KEEP_OPEN=1, to
    look at the window)."""
    with open(result, "w") as f:
        f.write("PASS\n" if not failures else "FAIL\n" + "\n".join(failures) + "\n")
    if os.environ.get("MP_KEEP_OPEN") != "1":
        os._exit(0 if not failures else 1)
