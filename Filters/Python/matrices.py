"""The projection operator in the user's hands: the matrices a
vtkMeshProjectionFilter keeps (CacheOperator on, after an execution), as
scipy.sparse CSR matrices, and Matrix Market files.

GetMatrix reads what the last execution kept and never executes the filter.
The helpers here ask for the matrices explicitly: they turn the filter's
KeepMatrices on and call its Update(), which executes it once more if it
had not kept its operators (a one-off execution sums its right-hand sides
without forming M_ts) and does nothing if it is up to date. KeepMatrices
stays on afterwards.

    from meshprojection import operator_matrices
    M_tt, M_ts, valid = operator_matrices(f)            # point data -> points
    u_t = scipy.sparse.linalg.spsolve(M_tt, M_ts @ u_s)  # = the filter's result on valid rows
                                                         # with FringeThreshold 0 or no fringe
With the fringe's aggregation (FringeThreshold, the default) the filter
solves the projection on the aggregated functions: with P = fringe_extension(f),

    free = P.getnnz(axis=0) > 0                        # columns P uses
    A, b = P.T @ M_tt @ P, P.T @ (M_ts @ u_s)
    u_t = P[:, free] @ spsolve(A[free][:, free], b[free])  # the filter's result on valid rows

With Extrapolation, E = extrapolation_matrix(f) extends the valid values:
the output is E @ u_t on E's nonempty rows (the fill value on the others).
"""
import numpy as np

TRANSFERS = {"points_to_points": 0, "points_to_cells": 1, "cells_to_cells": 2, "cells_to_points": 3}


def _updated(filter_):
    """The VTK filter (a ParaView proxy's client-side object: builtin
    sessions), with KeepMatrices on and up to date."""
    if hasattr(filter_, "GetClientSideObject"):
        filter_ = filter_.GetClientSideObject()
    filter_.SetKeepMatrices(True)
    filter_.Update()
    return filter_


def _csr(filter_, transfer, matrix):
    import scipy.sparse
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIdTypeArray
    starts, columns, values = vtkIdTypeArray(), vtkIdTypeArray(), vtkDoubleArray()
    ncolumns = filter_.GetMatrix(transfer, matrix, starts, columns, values)
    if ncolumns < 0:
        raise RuntimeError("no operator of this transfer is kept: execute the filter with "
                           "CacheOperator on and the transfer in use")
    rows = starts.GetNumberOfTuples() - 1
    return scipy.sparse.csr_matrix(
        (vtk_to_numpy(values).copy(), vtk_to_numpy(columns).copy(), vtk_to_numpy(starts).copy()),
        shape=(rows, ncolumns))


def operator_matrices(filter_, transfer="points_to_points"):
    """(M_tt, M_ts, valid) of a transfer ("points_to_points", "points_to_cells",
    "cells_to_cells", "cells_to_points"): the target mass matrix over the
    covered part (rows of invalid target functions hold 1 on the diagonal),
    the mixed matrix, and the boolean mask of valid target functions (their
    diagonal of the covered mass is positive). Rows and columns are VTK
    point or cell ids. `filter_` is a vtkMeshProjectionFilter, or a ParaView
    proxy of one (its client-side object is used: builtin sessions); its
    KeepMatrices is turned on and it is updated (see above)."""
    filter_ = _updated(filter_)
    t = TRANSFERS[transfer] if isinstance(transfer, str) else int(transfer)
    m_tt = _csr(filter_, t, 0)
    m_ts = _csr(filter_, t, 1)
    # Invalid functions have empty M_ts rows (no piece touches their support).
    valid = np.diff(m_ts.indptr) > 0
    return m_tt, m_ts, valid


def fringe_extension(filter_, transfer="points_to_points"):
    """P, the fringe's extension of a transfer to points (FringeThreshold):
    point functions x point functions, the identity on the free functions
    and the extension weights on the aggregated ones (no nonzero column for
    those); the identity when nothing is aggregated."""
    filter_ = _updated(filter_)
    t = TRANSFERS[transfer] if isinstance(transfer, str) else int(transfer)
    return _csr(filter_, t, 2)


def extrapolation_matrix(filter_, transfer="points_to_points"):
    """E, the extension of a transfer's valid values beyond the Source
    (Extrapolation): target functions x target functions, the identity on
    the valid ones, each extended one's weights over valid ones, empty rows
    for those left the fill value (without Extrapolation: the identity on
    the valid functions). One process's filter."""
    filter_ = _updated(filter_)
    t = TRANSFERS[transfer] if isinstance(transfer, str) else int(transfer)
    return _csr(filter_, t, 3)


def write_matrix_market(filter_, path, transfer="points_to_points", matrix="mixed"):
    """Writes M_ts (matrix="mixed") or M_tt ("target") as a Matrix Market file."""
    filter_ = _updated(filter_)
    t = TRANSFERS[transfer] if isinstance(transfer, str) else int(transfer)
    if not filter_.WriteMatrixMarket(path, t, 1 if matrix == "mixed" else 0):
        raise RuntimeError("could not write " + path)
