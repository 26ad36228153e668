"""The plugin under `mpiexec -n N pvbatch --mpi` (not symmetric: the script
runs on process 0 and drives the others, as a user's pvbatch script does).

The sample meshes are read, spread over the processes with Redistribute
DataSet, projected with the MeshProjection proxy, and fetched back to
process 0: the values at every point (matched by coordinates) equal the
serial filter's (1e-10 of each field's range), the masks too, the field
data integrals are the serial totals, and every process held a part of
Input (ProcessIds).

The pieces are written by every process (SaveData, a .pvtu in inline
binary) and read back whole on process 0.

Usage: mpiexec -n N pvbatch --mpi TestMeshProjectionPvbatch.py <plugin> N <temporary directory>
"""
import os
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import LoadPlugin, RedistributeDataSet, SaveData, XMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

import mpsupport.testing
from mpsupport.testing import DATA, check

plugin, processes, temp = sys.argv[1], int(sys.argv[2]), sys.argv[3]
os.makedirs(temp, exist_ok=True)
LoadPlugin(plugin, ns=globals())
check(servermanager.ActiveConnection.GetNumberOfDataPartitions() == processes,
      "pvbatch runs on %d processes" % processes)

for dim, (tname, sname) in (("2D", ("lshape_target.vtu", "lshape_source.vtu")),
                            ("3D", ("lshape3d_target.vtu", "lshape3d_source.vtu"))):
    target = RedistributeDataSet(Input=XMLUnstructuredGridReader(FileName=[os.path.join(DATA, tname)]))
    source = RedistributeDataSet(Input=XMLUnstructuredGridReader(FileName=[os.path.join(DATA, sname)]))
    projection = MeshProjection(Input=target, Source=source)  # noqa: F821
    # Every process writes its piece; process 0 reads them all.
    path = os.path.join(temp, "projected%s.pvtu" % dim)
    SaveData(path, proxy=projection, DataMode="Binary")
    from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader
    pieces = vtkXMLPUnstructuredGridReader()
    pieces.SetFileName(path)
    pieces.UpdateInformation()
    check(pieces.GetNumberOfPieces() == processes, "%s: %d pieces written" % (dim, pieces.GetNumberOfPieces()))
    pieces.Update()
    fetched = pieces.GetOutput()
    for k in range(pieces.GetNumberOfPieces()):
        one = vtkXMLPUnstructuredGridReader()
        one.SetFileName(path)
        one.UpdatePiece(k, pieces.GetNumberOfPieces(), 0)
        check(one.GetOutput().GetNumberOfCells() > 0, "%s: process %d held a part of Input" % (dim, k))
    # The serial filter on the whole meshes, here on process 0.
    import meshprojection
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    readers = []
    for name in (tname, sname):
        r = vtkXMLUnstructuredGridReader()
        r.SetFileName(os.path.join(DATA, name))
        r.Update()
        readers.append(r)
    serial = meshprojection.vtkMeshProjectionFilter()
    serial.SetInputData(readers[0].GetOutput())
    serial.SetSourceData(readers[1].GetOutput())
    serial.Update()
    whole = serial.GetOutput()

    index = {tuple(x): i for i, x in enumerate(vtk_to_numpy(whole.GetPoints().GetData()))}
    x = vtk_to_numpy(fetched.GetPoints().GetData())
    at = np.array([index.get(tuple(p), -1) for p in x])
    check(np.all(at >= 0), "%s: every point written is a point of Input" % dim)
    check(len(set(at)) == whole.GetNumberOfPoints(), "%s: the pieces hold every point of Input" % dim)
    mask = vtk_to_numpy(fetched.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
    smask = vtk_to_numpy(whole.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
    check(np.array_equal(mask, smask[at]), "%s: valid masks are the serial ones" % dim)
    source_pd = readers[1].GetOutput().GetPointData()
    compared = 0
    for a in range(source_pd.GetNumberOfArrays()):
        name = source_pd.GetArrayName(a)
        u = vtk_to_numpy(fetched.GetPointData().GetArray(name))
        w = vtk_to_numpy(whole.GetPointData().GetArray(name))[at]
        scale = float(np.ptp(vtk_to_numpy(source_pd.GetArray(a)))) or 1.0
        err = float(np.max(np.abs(u[mask] - w[mask]))) / scale
        check(err <= 1e-10, "%s: %s differs from serial by %.3g of its range" % (dim, name, err))
        compared += 1
        for prefix in ("SourceIntegral_", "TargetIntegral_"):
            pi = fetched.GetFieldData().GetArray(prefix + name)
            si = whole.GetFieldData().GetArray(prefix + name)
            check(pi is not None and si is not None and
                  abs(pi.GetComponent(0, 0) - si.GetComponent(0, 0)) <= 1e-10 * abs(si.GetComponent(0, 0)),
                  "%s: %s%s is the serial total" % (dim, prefix, name))
    check(compared > 0, "%s: arrays compared" % dim)
    print("%s: %d points from %d processes compared" % (dim, len(x), processes))
# The script ends normally on success (pvbatch then finalizes every process).
if mpsupport.testing.failures:
    print("%d check(s) failed" % len(mpsupport.testing.failures), file=sys.stderr)
    sys.exit(1)
print("all checks passed")
