// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MatrixExport.h
 * @brief The kept operators' matrices as the user sees them: compressed
 *        sparse rows in the datasets' numbering, and Matrix Market files.
 *
 * Rows are Input's points (P1) or cells (P0); columns Input's (M_tt) or
 * Source's (M_ts) points or cells. A renumbered mesh's kernel points are
 * mapped back to the dataset's points (each row's columns then sorted).
 */
#ifndef MeshProjection_Projection_MatrixExport_h
#define MeshProjection_Projection_MatrixExport_h

#include "Projection/Transfers.h"

#include "vtkType.h"

#include <string>

class vtkDoubleArray;
class vtkIdTypeArray;

namespace mpvtk
{
struct KeptLeaf;

/// M_tt (`matrix` 0), M_ts (1) or the fringe's extension P (2) of `leaf`'s operator of `transfer`; returns the number of columns
/// (-1 for P on several processes whose stencils reach the halo).
vtkIdType ExportMatrix(const KeptLeaf& leaf, Transfer transfer, int matrix,
  vtkIdTypeArray* rowStart, vtkIdTypeArray* columns, vtkDoubleArray* values);

/// Writes compressed rows as a Matrix Market coordinate file; an error text, or empty.
std::string WriteMatrixMarketFile(const std::string& fileName, const std::string& title,
  vtkIdType columnCount, vtkIdTypeArray* rowStart, vtkIdTypeArray* columns, vtkDoubleArray* values);
} // namespace mpvtk

#endif
