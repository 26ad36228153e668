"""What the second-order tests share (Python.SecondOrder, SecondOrderSpace):
copies of a mesh with other points or cell types, the fields they give
their Sources, the projection and its arrays."""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy


def linear(x):
    """1 + 2x - 3y + 0.5z at the rows of x."""
    return 1.0 + 2.0 * x[:, 0] - 3.0 * x[:, 1] + 0.5 * x[:, 2]


def points_of(g):
    """g's points as numpy (its own array: writing to it moves them)."""
    return vtk_to_numpy(g.GetPoints().GetData())


def copy_grid(g, transform=None, types=None, cell=None):
    """A copy of g without arrays: its points through `transform`, each
    cell's type replaced (types: {old: new}) or the cell through
    cell(type, ids) -> (type, ids)."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
    out = vtkUnstructuredGrid()
    points = vtkPoints()
    x = points_of(g).copy()
    points.SetData(numpy_to_vtk(transform(x) if transform else x, deep=True))
    out.SetPoints(points)
    out.Allocate(g.GetNumberOfCells())
    for c in range(g.GetNumberOfCells()):
        ids = g.GetCell(c).GetPointIds()
        t, kept = g.GetCellType(c), [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
        t = types.get(t, t) if types else t
        if cell:
            t, kept = cell(t, kept)
        out.InsertNextCell(t, len(kept), kept)
    return out


def with_fields(g, fields):
    """A copy of g (copy_grid) with the point arrays of `fields` ((name,
    f(x)) pairs, in that order) and the cell array Constant (7)."""
    g = copy_grid(g)
    x = points_of(g)
    for name, f in fields:
        a = numpy_to_vtk(np.ascontiguousarray(f(x)), deep=True)
        a.SetName(name)
        g.GetPointData().AddArray(a)
    c = numpy_to_vtk(np.full(g.GetNumberOfCells(), 7.0), deep=True)
    c.SetName("Constant")
    g.GetCellData().AddArray(c)
    return g


def project(target, source, filter_class=None, **properties):
    """The output of a filter of filter_class (vtkMeshProjectionFilter
    unless told: vtkPMeshProjectionFilter on MPI processes) on target and
    source, with any property by name (CacheOperator=False calls
    SetCacheOperator(False))."""
    import meshprojection
    f = (filter_class or meshprojection.vtkMeshProjectionFilter)()
    f.SetInputData(target)
    f.SetSourceData(source)
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f.GetOutput()


def point_array(out, name):
    """The point array `name` of out, as numpy."""
    return vtk_to_numpy(out.GetPointData().GetArray(name))


def curved_level_pairs():
    """Curved pairs that overlap in part, for CurvedCellSubdivision on
    several processes (Python.SecondOrderMPI2, SecondOrderMPI3): (name,
    Input with the point array origId, Source with fringe.with_fields'
    arrays). Gmsh tri6 and quad9 disks and tet10 balls (their boundary mid
    nodes on the circle, the sphere), each as Input and as Source; and a
    linear ball (the tet10 ball's corners) whose Source, a tet10 ball, holds
    away from the Input a bent hex27 cube (curved hexahedra: the whole
    Source keeps its nodes' split, also on the processes that gather none
    of them)."""
    from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray
    from vtkmodules.vtkFiltersCore import vtkAppendFilter
    from mpsupport import gmshmeshes
    from mpsupport.fringe import with_fields as fields

    def numbered(g):
        g = copy_grid(g)
        a = numpy_to_vtkIdTypeArray(np.arange(g.GetNumberOfPoints(), dtype=np.int64), deep=True)
        a.SetName("origId")
        g.GetPointData().AddArray(a)
        return g

    def bent(x):
        return x + 0.04 * np.stack([np.sin(3 * x[:, 1]), np.sin(3 * x[:, 2]), np.sin(3 * x[:, 0])], 1)

    so = gmshmeshes.second_order
    tri6, quad9, ball = so("disk", 0.25), so("disk", 0.3, True), so("ball", 0.3)
    append = vtkAppendFilter()
    append.AddInputData(copy_grid(ball, lambda x: x + [0.3, 0.15, -0.2]))
    append.AddInputData(copy_grid(so("hexes", 0.5), lambda x: bent(x) + [3.0, 0.0, 0.0]))
    append.Update()
    return [
        ("curved tri6 disk <- quad9 disk", numbered(tri6), fields(copy_grid(quad9, lambda x: x + [0.6, -0.3, 0.0]))),
        ("curved quad9 disk <- tri6 disk", numbered(quad9), fields(copy_grid(tri6, lambda x: x + [-0.5, 0.45, 0.0]))),
        ("curved tet10 ball <- tet10 ball", numbered(ball), fields(copy_grid(ball, lambda x: x + [0.3, 0.15, -0.2]))),
        ("linear ball <- tet10 ball + far bent hex27", numbered(copy_grid(ball, cell=lambda t, ids: (10, ids[:4]))),
         fields(append.GetOutput())),
    ]


def check_curved_levels(controller, check, levels=(2, 3)):
    """On MPI processes (mpsupport.mpi.begin's controller and check): each
    pair of curved_level_pairs() at each CurvedCellSubdivision of `levels`,
    the fringe on (FringeThreshold at its default), Input in blocks along x
    and the Source dealt at random, projected by vtkPMeshProjectionFilter
    against the serial filter. On every process, for its points: the valid
    mask is the serial one, the values of a smooth field equal the serial
    ones to 1e-10 of its range, a linear field is exact (1e-9), the integral
    over the covered part (summed over the processes) is the serial one
    (1e-12), the warnings are the serial ones (none, but the far hex27's:
    its curved cells are not split finer); the serial values at that level
    differ from level 1's (the finer split is in use: a level-1 fallback
    would fail), but with the far hex27 equal them (to 1e-14); the count in
    the far hex27's warning is the serial one, also when each process's
    part of Source carries the others' cells as ghost cells
    (check_unrefined_count)."""
    import meshprojection
    from mpsupport import meshes, mpi
    from mpsupport.fringe import linear as linear_field
    rank, size = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()

    def run(filter_class, target, source, level):
        f = filter_class()
        said = mpi.messages(f)
        f.SetInputData(target)
        f.SetSourceData(source)
        f.SetCacheOperator(False)
        f.SetCurvedCellSubdivision(level)
        f.Update()
        # (Each text without its "Warning: In ..., vtk...Filter (address): " head.)
        return f.GetOutput(), [t.split("): ", 1)[-1].strip() for t in said["WarningEvent"] + said["ErrorEvent"]]

    for name, target, source in curved_level_pairs():
        part = meshes.extract(target, mpi.blocks_along_x(target, size) == rank)
        keep = np.random.default_rng(9).integers(0, size, source.GetNumberOfCells()) == rank
        local_source = meshes.extract(source, keep)
        x = points_of(target)
        level1, _ = run(meshprojection.vtkMeshProjectionFilter, target, source, 1)
        far = "hex27" in name
        for level in levels[:1] if far else levels:
            serial, serial_said = run(meshprojection.vtkMeshProjectionFilter, target, source, level)
            out, said = run(meshprojection.vtkPMeshProjectionFilter, part, local_source, level)
            what = "%s, CurvedCellSubdivision %d" % (name, level)
            check(sorted(said) == sorted(serial_said) and len(said) == (1 if far else 0),
                  "%s: the serial warnings (%s)" % (what, said))
            ids = point_array(out, "origId")
            serial_valid = point_array(serial, "vtkValidPointMask").astype(bool)
            valid = point_array(out, "vtkValidPointMask").astype(bool)
            check(serial_valid.any() and not serial_valid.all(), "%s: the pair overlaps in part" % what)
            check(np.array_equal(valid, serial_valid[ids]), "%s: valid mask as serial" % what)
            s = point_array(serial, "s")
            scale = np.ptp(s[serial_valid])
            both = serial_valid & point_array(level1, "vtkValidPointMask").astype(bool)
            finer = np.max(np.abs(s - point_array(level1, "s"))[both]) / scale
            check(finer > 1e-6 if not far else finer <= 1e-14,
                  "%s: serial %s level 1's (%.2g of the range apart)"
                  % (what, "equals" if far else "differs from", finer))
            off = np.max(np.abs(point_array(out, "s") - s[ids])[valid], initial=0.0) / scale
            largest = max(a[0] for a in mpi.allgather(controller, np.array([off])))
            if rank == 0:
                print("%s: %d processes, largest difference to serial %.3g of the range" % (what, size, largest))
            check(off <= 1e-10, "%s: the serial values (%.2g of the range off)" % (what, off))
            lin = np.max(np.abs(point_array(out, "l") - linear_field(x[ids]))[valid], initial=0.0)
            check(lin <= 1e-9 * np.ptp(linear_field(x)), "%s: linear exact at every valid node (%.2g)" % (what, lin))
            total = out.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
            reference = serial.GetFieldData().GetArray("TargetIntegral_s").GetValue(0)
            check(abs(total - reference) <= 1e-12 * max(1.0, abs(reference)),
                  "%s: integral %.15g, serial %.15g" % (what, total, reference))
            if far:
                check_unrefined_count(controller, check, run, part, source, keep, level,
                                      serial_said, said, what)


def check_unrefined_count(controller, check, run, part, source, keep, level, serial_said, plain, what):
    """The count N of "N curved cells are not split finer" on MPI processes
    (`plain`: the warnings of the run on the processes' parts of Source) is
    the serial one, also when each process's part carries the other
    processes' cells as ghost cells (DUPLICATECELL: counted by their owners
    alone)."""
    import re
    import meshprojection
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkDataSetAttributes
    rank = controller.GetLocalProcessId()

    def count(said):
        found = [re.search(r"(\d+) curved cells are not split finer", t) for t in said]
        found = [int(m.group(1)) for m in found if m]
        return found[0] if len(found) == 1 else None

    ghosted = source.NewInstance()
    ghosted.DeepCopy(source)
    flags = numpy_to_vtk(np.where(keep, 0, vtkDataSetAttributes.DUPLICATECELL).astype(np.uint8), deep=True)
    flags.SetName(vtkDataSetAttributes.GhostArrayName())
    ghosted.GetCellData().AddArray(flags)
    _, ghost_said = run(meshprojection.vtkPMeshProjectionFilter, part, ghosted, level)
    serial = count(serial_said)
    if rank == 0:
        print("%s: %s curved cells not split finer serially, %s on the processes' parts, %s with ghost cells"
              % (what, serial, count(plain), count(ghost_said)))
    check(serial is not None and serial > 0, "%s: the serial count said (%s)" % (what, serial_said))
    check(count(plain) == serial, "%s: the serial count on the parts (%s)" % (what, plain))
    check(count(ghost_said) == serial, "%s: the serial count with ghost cells (%s)" % (what, ghost_said))
    check(sorted(ghost_said) == sorted(serial_said),
          "%s: with ghost cells, the serial warnings (%s)" % (what, ghost_said))

