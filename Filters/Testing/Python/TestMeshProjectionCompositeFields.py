"""A composite Source whose blocks hold different arrays (VTK Python, one
process), by the rule the processes' pieces follow (Adapter/PieceArrays.h):

 - a point array 'p' and a cell array 'c' that the second block lacks are
   projected where present: the output equals the projection of the uncut
   mesh with NaN where only the second block's cells have them (1e-10 of
   the range, NaN alike, masks alike), with one warning naming each array
   and the block without it, and no NaN warning for them;
 - 'v', with 1 component on the first block and 3 on the second, is not
   projected, and a warning names it and says how the blocks differ;
 - an empty block holding none of these arrays makes none missing;
 - 'f', on every block, equals the uncut mesh's projection;
 - deselected, 'v' and 'p' get no warning (they are not wanted).
"""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, VTK_TETRA, vtkMultiBlockDataSet, vtkUnstructuredGrid

from mpsupport import meshes
from mpsupport.testing import check, finish, observed_filter


def run(target, source, disabled=()):
    f, texts = observed_filter("WarningEvent", "ErrorEvent")
    for name in disabled:
        f.GetPointDataArraySelection().DisableArray(name)
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.Update()
    return f.GetOutput(), texts


# Source: hexahedra of a jittered 6^3 grid, cut between two columns of
# cells (each block's cell has points off the cut: none is all interface).
# The cut lies midway between the third and fourth columns' centroids
# (x up to 0.400, from 0.551): a jittered cell of the third column is
# then not cut off into the second block with all its points the first
# block's, which NaN point values could not make a hole.
x, hexes = meshes.hexahedra(6, (-0.1, -0.05, -0.08), (1.05, 0.97, 1.02), 3)
uncut = meshes.grid(x, hexes, VTK_HEXAHEDRON)
meshes.add_array(uncut.GetPointData(), "f", np.sin(2 * x[:, 0]) + x[:, 1] * x[:, 2])
meshes.add_array(uncut.GetPointData(), "p", 1 + x[:, 0] - 2 * x[:, 2])
meshes.add_array(uncut.GetPointData(), "v", x[:, 1])
meshes.add_array(uncut.GetCellData(), "c", x[hexes].mean(axis=1)[:, 1] ** 2)
first = x[hexes].mean(axis=1)[:, 0] < 0.475
a = meshes.extract(uncut, first)
b = meshes.extract(uncut, ~first)
b.GetPointData().RemoveArray("p")
b.GetCellData().RemoveArray("c")
v = vtk_to_numpy(b.GetPointData().GetArray("v"))
b.GetPointData().RemoveArray("v")
meshes.add_array(b.GetPointData(), "v", np.stack([v, v, v], 1))
source = vtkMultiBlockDataSet()
source.SetBlock(0, a)
source.SetBlock(1, b)
source.SetBlock(2, vtkUnstructuredGrid())  # empty: makes nothing missing

# The reference: the uncut mesh, 'p' NaN where no first-block cell uses a
# point, 'c' NaN on the second block's cells.
holed = vtkUnstructuredGrid()
holed.DeepCopy(uncut)
used = np.zeros(len(x), bool)
used[hexes[first].ravel()] = True
check(not used[hexes[~first]].all(axis=1).any(), "a second-block cell with all its points the first block's")
vtk_to_numpy(holed.GetPointData().GetArray("p"))[~used] = np.nan
vtk_to_numpy(holed.GetCellData().GetArray("c"))[~first] = np.nan
holed.GetPointData().RemoveArray("v")

target = meshes.grid(*meshes.tetrahedra(5, (0.02, 0.03, 0.01), (0.98, 0.99, 0.97), 4), VTK_TETRA)
out, texts = run(target, source)
ref, ref_texts = run(target, holed)
check(not [t for t in texts if "ERROR" in t], "errors: %s" % texts)
for name, kind in (("p", "point"), ("c", "cell")):
    said = [t for t in texts if "Source %s array '%s' is missing on block" % (kind, name) in t]
    check(len(said) == 1, "one warning naming '%s': %s" % (name, texts))
    check(said and "flat index 2" in said[0] and "flat index 3" not in said[0],
          "'%s': the warning names the second block only: %s" % (name, said))
check(not [t for t in texts if "NaN or infinite" in t], "a NaN warning too: %s" % texts)
said = [t for t in texts if "array 'v' is not projected" in t and "3 components" in t and "1 component" in t]
check(len(said) == 1, "one warning refusing 'v': %s" % texts)
check(out.GetPointData().GetArray("v") is None, "'v' projected")
for data, rdata in ((out.GetPointData(), ref.GetPointData()), (out.GetCellData(), ref.GetCellData())):
    for i in range(rdata.GetNumberOfArrays()):
        name = rdata.GetArrayName(i)
        if data.GetArray(name) is None:
            check(False, "%s not in the output" % name)
            continue
        lv = vtk_to_numpy(data.GetArray(name)).astype(float)
        rv = vtk_to_numpy(rdata.GetArray(name)).astype(float)
        finite = ~np.isnan(rv)
        err = float(np.max(np.abs(lv[finite] - rv[finite]), initial=0))
        check(np.array_equal(np.isnan(lv), np.isnan(rv)) and err <= 1e-10 * max(1.0, np.ptp(rv[finite])),
              "%s differs from the holed uncut mesh's projection by %.3g" % (name, err))
mask = out.GetPointData().GetArray("vtkValidPointMask_p")
valid = vtk_to_numpy(mask).astype(bool) if mask is not None else np.zeros(0, bool)
check(valid.any() and not valid.all(), "'p' valid at some points, not all (%d of %d)" % (valid.sum(), len(valid)))
# Deselected, 'v' and 'p' are not projected anyway: no warning on them.
_, texts = run(target, source, disabled=("v", "p"))
check(not [t for t in texts if "'v'" in t or "'p'" in t], "warnings on deselected arrays: %s" % texts)
check(len([t for t in texts if "'c' is missing" in t]) == 1, "the warning on 'c' when 'p' is deselected: %s" % texts)
finish()
