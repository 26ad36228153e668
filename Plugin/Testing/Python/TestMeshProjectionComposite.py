"""Composite datasets through the ParaView plugin (pvpython): a .vtm multiblock
Input (hexes_box cut at x = 0.5 into two blocks) projected from tets_box
(with a nonlinear point field U), each output leaf checked against the
wrapped filter run directly on that leaf; then a .vtm Source (tets_box cut
into three blocks, each with its own copy of the interface points) checked
against the uncut Source.

    pvpython TestMeshProjectionComposite.py PLUGIN.so TEMP_DIR
"""
import os
import sys

import numpy as np  # noqa: E402
from paraview import servermanager  # noqa: E402
from paraview.simple import Delete, LoadPlugin, OpenDataFile  # noqa: E402

from mpsupport.testing import GMSH, check, cut, finish, read, write_multiblock  # noqa: E402
# Before any client-side object is wrapped: VTK's Python wrapping would
# otherwise remember the filter as its nearest wrapped base class.
from meshprojection import vtkMeshProjectionFilter  # noqa: E402

from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet, vtkMultiBlockDataSet  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter  # noqa: E402

plugin, temp_dir = sys.argv[1], sys.argv[2]
os.makedirs(temp_dir, exist_ok=True)
LoadPlugin(plugin, ns=globals())
check("MeshProjection" in globals(), "the plugin defines MeshProjection")


def write_vtm(path, blocks):
    check(write_multiblock(path, blocks), "wrote %s" % path)
    return path


def relative_difference(a, b):
    if a is None or b is None or a.shape != b.shape:
        return float("inf")
    fa, fb = np.isfinite(a), np.isfinite(b)
    if not np.array_equal(fa, fb):
        return float("inf")
    if not fa.any():
        return 0.0
    return float(np.max(np.abs(a[fa] - b[fb]))) / max(float(np.max(np.abs(b[fb]))), 1e-300)


def arrays(attributes):
    return {attributes.GetArrayName(i): vtk_to_numpy(attributes.GetArray(i)).astype(float)
            for i in range(attributes.GetNumberOfArrays())}


def same(got, expected, what, tol=1e-12, names=None):
    """Every array of `expected` (or those named) is in `got`, equal to 1e-12 relative."""
    for kind, g, e in (("point", got.GetPointData(), expected.GetPointData()),
                       ("cell", got.GetCellData(), expected.GetCellData())):
        ga, ea = arrays(g), arrays(e)
        for name, values in ea.items():
            if names is not None and name not in names:
                continue
            d = relative_difference(ga.get(name), values)
            check(d <= tol, "%s: %s array %s differs by %g (relative)" % (what, kind, name, d))


# The data: tets_box with U = sin(3x) cos(2y) + z^2, hexes_box without its
# own Linear (the output's must come from Source), cut into two blocks.
tets = read(os.path.join(GMSH, "tets_box.vtu"))
x = vtk_to_numpy(tets.GetPoints().GetData())
u = numpy_to_vtk(np.sin(3 * x[:, 0]) * np.cos(2 * x[:, 1]) + x[:, 2] ** 2, deep=True)
u.SetName("U")
tets.GetPointData().AddArray(u)
source_vtu = os.path.join(temp_dir, "tets_box_u.vtu")
writer = vtkXMLUnstructuredGridWriter()
writer.SetFileName(source_vtu)
writer.SetInputData(tets)
writer.SetDataModeToBinary()
check(writer.Write() == 1, "wrote %s" % source_vtu)

hexes = read(os.path.join(GMSH, "hexes_box.vtu"))
hexes.GetPointData().RemoveArray("Linear")
blocks = [("hexes x < 0.5", cut(hexes, lambda c: c[:, 0] < 0.5)),
          ("hexes x >= 0.5", cut(hexes, lambda c: c[:, 0] >= 0.5))]
check(all(b.GetNumberOfCells() > 0 for _, b in blocks) and
      sum(b.GetNumberOfCells() for _, b in blocks) == hexes.GetNumberOfCells(), "two blocks of hexes")
input_vtm = write_vtm(os.path.join(temp_dir, "hexes_blocks.vtm"), blocks)
source_vtm = write_vtm(os.path.join(temp_dir, "tets_blocks.vtm"), [
    ("tets x < 0.35", cut(tets, lambda c: c[:, 0] < 0.35)),
    ("tets x >= 0.35, y < 0.6", cut(tets, lambda c: (c[:, 0] >= 0.35) & (c[:, 1] < 0.6))),
    ("tets x >= 0.35, y >= 0.6", cut(tets, lambda c: (c[:, 0] >= 0.35) & (c[:, 1] >= 0.6)))])

target = OpenDataFile(input_vtm)
source = OpenDataFile(source_vtu)
source.UpdatePipeline()
projection = MeshProjection(Input=target, Source=source)  # noqa: F821
projection.PointDataTarget = "Points and Cells"
projection.UpdatePipeline()
out = servermanager.Fetch(projection)
inp = servermanager.Fetch(target)
src = servermanager.Fetch(source)
check(isinstance(inp, vtkMultiBlockDataSet) and inp.GetNumberOfBlocks() == 2,
      "the .vtm reads as two blocks (%s)" % inp.GetClassName())
check(isinstance(out, vtkMultiBlockDataSet) and out.GetNumberOfBlocks() == 2,
      "the output is a multiblock of two blocks (%s)" % out.GetClassName())
check(abs(projection.GetClientSideObject().GetCoveredMeasure() - 1) <= 1e-12,
      "covered volume %r == 1" % projection.GetClientSideObject().GetCoveredMeasure())
results = []
if isinstance(out, vtkMultiBlockDataSet) and out.GetNumberOfBlocks() == 2:
    for i, (name, block) in enumerate(blocks):
        leaf, given = out.GetBlock(i), inp.GetBlock(i)
        what = "block %d (%s)" % (i, name)
        check(leaf is not None and leaf.GetNumberOfCells() == block.GetNumberOfCells() and
              leaf.GetNumberOfPoints() == block.GetNumberOfPoints(), "%s: cells and points kept" % what)
        meta = out.GetMetaData(i) if out.HasMetaData(i) else None
        check(meta is not None and meta.Get(vtkCompositeDataSet.NAME()) == name,
              "%s: the block's name kept" % what)
        if leaf is None:
            continue
        direct = vtkMeshProjectionFilter()
        direct.SetInputData(given)
        direct.SetSourceData(src)
        direct.SetPointDataTarget(vtkMeshProjectionFilter.TO_POINTS_AND_CELLS)
        direct.Update()
        expected = direct.GetOutput()
        names = set(arrays(expected.GetPointData())) | set(arrays(expected.GetCellData()))
        check({"U", "Linear", "vtkValidPointMask", "CellIndex", "CoveredFraction",
               "vtkValidCellMask"} <= names, "%s: the direct run's arrays %r" % (what, sorted(names)))
        same(leaf, expected, what + " == the direct filter on the leaf")
        lx = vtk_to_numpy(leaf.GetPoints().GetData())
        linear = leaf.GetPointData().GetArray("Linear")
        if linear is not None:
            err = float(np.max(np.abs(vtk_to_numpy(linear) - (1 + 2 * lx[:, 0] - 3 * lx[:, 1] + 0.5 * lx[:, 2]))))
            check(err <= 1e-12, "%s: Linear exact (%g)" % (what, err))
        results.append(leaf)

# A .vtm Source of the tets cut into blocks == the uncut Source.
cut_source = OpenDataFile(source_vtm)
cut_source.UpdatePipeline()
fetched_source = servermanager.Fetch(cut_source)
check(isinstance(fetched_source, vtkMultiBlockDataSet) and fetched_source.GetNumberOfBlocks() == 3,
      "the Source .vtm reads as three blocks")
from_blocks = MeshProjection(Input=target, Source=cut_source)  # noqa: F821
from_blocks.PointDataTarget = "Points and Cells"
from_blocks.UpdatePipeline()
out2 = servermanager.Fetch(from_blocks)
check(isinstance(out2, vtkMultiBlockDataSet) and out2.GetNumberOfBlocks() == 2,
      "composite Source: the output is a multiblock of two blocks")
check(abs(from_blocks.GetClientSideObject().GetCoveredMeasure() - 1) <= 1e-12,
      "composite Source: covered volume %r" % from_blocks.GetClientSideObject().GetCoveredMeasure())
if isinstance(out2, vtkMultiBlockDataSet) and out2.GetNumberOfBlocks() == 2 and len(results) == 2:
    for i, leaf in enumerate(results):
        same(out2.GetBlock(i), leaf, "block %d: composite Source == uncut Source" % i,
             names={"U", "Linear", "vtkValidPointMask", "CellIndex", "CoveredFraction",
                    "vtkValidCellMask"})
        check(out2.GetBlock(i).GetPointData().GetArray("U") is not None and
              out2.GetBlock(i).GetCellData().GetArray("CellIndex") is not None,
              "block %d: U and CellIndex projected from the composite Source" % i)

for proxy in (from_blocks, projection, cut_source, source, target):
    Delete(proxy)
finish()
