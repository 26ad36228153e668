// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MatrixExport.h
 * @brief The kept operators' matrices as the user sees them: compressed
 *        sparse rows in the datasets' numbering, and Matrix Market files.
 *
 * Rows are Input's points (P1) or cells (P0); columns Input's (M_tt, P, E)
 * or Source's (M_ts) points or cells. A renumbered mesh's kernel points are
 * mapped back to the dataset's points (each row's columns then sorted).
 */
#ifndef MeshProjection_Projection_MatrixExport_h
#define MeshProjection_Projection_MatrixExport_h

#include "Projection/Transfers.h"

#include "vtkType.h"

#include <string>

class vtkDoubleArray;
class vtkIdTypeArray;

namespace mp
{
class MortarOperator;
}

namespace mpvtk
{
struct KeptLeaf;

/// The matrices of a kept operator (vtkMeshProjectionFilter::Matrices).
enum class Exported
{
  TargetMass,      ///< M_tt
  MixedMass,       ///< M_ts
  FringeExtension, ///< P (the identity where nothing is aggregated, P0 targets too)
  Extrapolation ///< E over the valid functions (their identity, empty invalid rows, without Extrapolation)
};

/**
 * Whether `op`'s fringe extension reaches its halo (on several processes: a
 * row of this process's functions with a column of a ghost point), which
 * this process's numbering cannot write.
 */
bool FringeReachesHalo(const mp::MortarOperator& op);

/// `matrix` of `leaf`'s operator of `transfer`; returns the number of columns.
vtkIdType ExportMatrix(const KeptLeaf& leaf, Transfer transfer, Exported matrix,
  vtkIdTypeArray* rowStart, vtkIdTypeArray* columns, vtkDoubleArray* values);

/// Writes compressed rows as a Matrix Market coordinate file; an error text, or empty.
std::string WriteMatrixMarketFile(const std::string& fileName, const std::string& title,
  vtkIdType columnCount, vtkIdTypeArray* rowStart, vtkIdTypeArray* columns, vtkDoubleArray* values);
} // namespace mpvtk

#endif
