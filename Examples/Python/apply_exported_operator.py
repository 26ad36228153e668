"""Apply Mesh Projection's operator yourself: export M_tt and M_ts as scipy
matrices, project another field with numpy, and compare with the filter.

    pvpython apply_exported_operator.py --plugin /path/to/MeshProjection.so

The operator is built once by the filter (from the geometry alone); any field
on the Source's points then projects as u_t = M_tt^-1 (M_ts u_s) on the valid
target points, which is what the filter computes.
"""
import argparse
import os
import sys

import numpy as np
import scipy.sparse.linalg
from paraview.simple import LoadPlugin, OpenDataFile, PythonCalculator, servermanager
from vtkmodules.util.numpy_support import vtk_to_numpy

import meshprojection

DATA = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "Data")
parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--plugin", required=True, help="path of MeshProjection.so")
args = parser.parse_args()
LoadPlugin(args.plugin, ns=globals())

source = OpenDataFile(os.path.join(DATA, "lshape_source.vtu"))
target = OpenDataFile(os.path.join(DATA, "lshape_target.vtu"))
# A field the filter also projects, for the comparison.
source_xy = PythonCalculator(Input=source, Expression="sin(3 * inputs[0].Points[:, 0]) * inputs[0].Points[:, 1]",
                             ArrayName="Other")
source_xy.UpdatePipeline()
projection = MeshProjection(Input=target, Source=source_xy)  # noqa: F821
projection.UpdatePipeline()

# The operator of point data -> points, as scipy CSR matrices.
M_tt, M_ts, valid = meshprojection.operator_matrices(projection, "points_to_points")
print("M_tt %s, %d nonzeros; M_ts %s, %d nonzeros; %d valid target points"
      % (M_tt.shape, M_tt.nnz, M_ts.shape, M_ts.nnz, valid.sum()))

src = servermanager.Fetch(source_xy)
x = vtk_to_numpy(src.GetPoints().GetData())
u_s = np.sin(3 * x[:, 0]) * x[:, 1]
u_t = scipy.sparse.linalg.spsolve(M_tt.tocsc(), M_ts @ u_s)

out = projection.GetClientSideObject().GetOutputDataObject(0)
filtered = vtk_to_numpy(out.GetPointData().GetArray("Other"))
error = np.max(np.abs(u_t[valid] - filtered[valid]))
print("max |numpy - filter| on valid points: %.3g" % error)
meshprojection.write_matrix_market(projection, os.path.join(os.getcwd(), "M_ts.mtx"))
print("wrote M_ts.mtx")
sys.exit(0 if error < 1e-12 else 1)
