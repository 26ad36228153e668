"""vtkPMeshProjectionFilter with TangentArrays on several MPI processes (run
under mpiexec with pvbatch --mpi --symmetric): every process gets the
serial result.

A target point's normal sums the cells around it, which may live on other
processes (the solver's hooks complete it); a Source point's normal needs
its whole star, which the gathering brings (the neighbour layer; points on
the cuts between the Source's pieces joined by their coordinates). Two
facetizations of a sphere, Input in slabs along z, Source cut at random
(its points copied on each side), a tangent point and cell array to points
and cells: the arrays and their _NormalPart equal the serial ones (1e-12
of the field's largest magnitude), and the result's normal part is at
round-off on every process.

Pieces that point opposite ways: a polyline (a turn of a helix) whose
segments are oriented one way on even processes' blocks and the other way
on odd ones, so that each point on a cut between two processes has sums of
opposite signs there (which a plain sum of the parts cancels, leaving the
chords' difference, across the curve). Its tangent array equals the serial
one (the serial sum flips them to agree) to 1e-12, and at the points it is
along the helix's tangent (its part across at most 0.05 of the field: the
end points' chords are half a segment's turn, pi/80, off the tangent).
"""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkCommonDataModel import VTK_LINE
from vtkmodules.vtkFiltersCore import vtkAppendFilter

from mpsupport import meshes, mpi
from mpsupport.mpi import add

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402  (after MPI is up)
F = meshprojection.vtkMeshProjectionFilter


def sphere(theta, phi):
    s = vtkSphereSource()
    s.SetThetaResolution(theta)
    s.SetPhiResolution(phi)
    s.SetOutputPointsPrecision(1)
    grid = vtkAppendFilter()
    grid.SetInputConnection(s.GetOutputPort())
    grid.Update()
    g = grid.GetOutput()
    g.GetPointData().Initialize()
    return g


def unit(v):
    return v / np.linalg.norm(v, axis=1)[:, None]


def field(x):
    r = unit(x)
    ez = np.array([0.0, 0.0, 1.0])
    return ez - r[:, 2:3] * r + 0.5 * np.cross(ez, r)


def centres(g):
    x = vtk_to_numpy(g.GetPoints().GetData())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 3)
    return x[conn].mean(axis=1)


def run(filter_class, target, source):
    f = filter_class()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.SetPointDataTarget(F.TO_POINTS_AND_CELLS)
    f.SetCellDataTarget(F.TO_POINTS_AND_CELLS)
    f.AddTangentArray("v")
    f.AddTangentArray("w")
    f.Update()
    return f


target = mpi.numbered(sphere(37, 29))
source = sphere(24, 18)
add(source.GetPointData(), "v", field(vtk_to_numpy(source.GetPoints().GetData())))
add(source.GetCellData(), "w", field(centres(source)))
scale = 1.5

tz = centres(target)[:, 2]
lt = meshes.extract(target, np.minimum(size - 1, ((tz + 1) / 2 * size).astype(int)) == rank)
ls = meshes.extract(source, np.random.default_rng(5).integers(0, size, source.GetNumberOfCells()) == rank)
serial = run(F, target, source).GetOutput()
out = run(meshprojection.vtkPMeshProjectionFilter, lt, ls).GetOutput()
for assoc in ("point", "cell"):
    ld = out.GetPointData() if assoc == "point" else out.GetCellData()
    sd = serial.GetPointData() if assoc == "point" else serial.GetCellData()
    if ld.GetNumberOfTuples() == 0:
        continue
    ids = vtk_to_numpy(ld.GetArray("origId"))
    for name in ("v", "w", "v_NormalPart", "w_NormalPart"):
        if ld.GetArray(name) is None or sd.GetArray(name) is None:
            check(False, "%s %s: missing (parallel %s, serial %s)"
                  % (assoc, name, ld.GetArray(name) is not None, sd.GetArray(name) is not None))
            continue
        lv = vtk_to_numpy(ld.GetArray(name))
        sv = vtk_to_numpy(sd.GetArray(name))[ids]
        err = float(np.max(np.abs(lv - sv), initial=0.0)) / scale
        check(err <= 1e-12, "%s %s differs from serial by %.3g of the field" % (assoc, name, err))

# The result's normal part on this process's points, with the normals the
# serial target has there (the whole sphere's cells around each point).
x = vtk_to_numpy(target.GetPoints().GetData())
conn = vtk_to_numpy(target.GetCells().GetConnectivityArray()).reshape(-1, 3)
area = 0.5 * np.cross(x[conn[:, 1]] - x[conn[:, 0]], x[conn[:, 2]] - x[conn[:, 0]])
normals = np.zeros_like(x)
for k in range(3):
    np.add.at(normals, conn[:, k], area)
if out.GetNumberOfPoints():
    ids = vtk_to_numpy(out.GetPointData().GetArray("origId"))
    v = vtk_to_numpy(out.GetPointData().GetArray("v"))
    normal = np.abs(np.sum(v * unit(normals[ids]), axis=1))
    check(np.max(normal) < 1e-12 * scale, "points: the normal part is at round-off (%.2e)" % np.max(normal))



def arc(n, blocks):
    """n segments on a helix's turn from 0 to pi, block b of `blocks` (in
    order along it) reversed when b is odd; and the blocks."""
    t = np.linspace(0.0, np.pi, n + 1)
    x = np.stack([np.cos(t), np.sin(t), 0.1 * t], 1)
    cells = np.stack([np.arange(n), np.arange(1, n + 1)], 1)
    block = np.minimum(blocks - 1, np.arange(n) * blocks // n)
    cells[block % 2 == 1] = cells[block % 2 == 1][:, ::-1]
    return meshes.grid(x, cells, VTK_LINE), block


def along_arc(x):
    """A field with parts along the arc, across it and out of its plane."""
    t = np.arctan2(x[:, 1], x[:, 0])
    tangent = unit(np.stack([-np.sin(t), np.cos(t), 0.1 * np.ones_like(t)], 1))
    return (1 + t)[:, None] * tangent + 0.3 * x * [1, 1, 0] + [0.0, 0.0, 0.2]


def run_curve(filter_class, target, source):
    f = filter_class()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.AddTangentArray("v")
    f.Update()
    return f


curve, block = arc(40, size)
curve = mpi.numbered(curve)
line = arc(57, 1)[0]
add(line.GetPointData(), "v", along_arc(vtk_to_numpy(line.GetPoints().GetData())))
serial = run_curve(F, curve, line).GetOutput()
mine = meshes.extract(line, np.random.default_rng(7).integers(0, size, line.GetNumberOfCells()) == rank)
out = run_curve(meshprojection.vtkPMeshProjectionFilter, meshes.extract(curve, block == rank), mine).GetOutput()
if out.GetNumberOfPoints():
    ids = vtk_to_numpy(out.GetPointData().GetArray("origId"))
    lv = vtk_to_numpy(out.GetPointData().GetArray("v"))
    sv = vtk_to_numpy(serial.GetPointData().GetArray("v"))[ids]
    magnitude = float(np.max(np.linalg.norm(sv, axis=1)))
    err = float(np.max(np.abs(lv - sv))) / magnitude
    check(err <= 1e-12, "curve: v differs from serial by %.3g of the field" % err)
    x = vtk_to_numpy(out.GetPoints().GetData())
    t = np.arctan2(x[:, 1], x[:, 0])
    tangent = unit(np.stack([-np.sin(t), np.cos(t), 0.1 * np.ones_like(t)], 1))
    across = np.linalg.norm(lv - np.sum(lv * tangent, axis=1)[:, None] * tangent, axis=1)
    check(np.max(across) <= 0.05 * magnitude,
          "curve: v is along the helix (its part across: %.3g of the field)" % (np.max(across) / magnitude))

check.finish("%d processes, tangent arrays" % size)
