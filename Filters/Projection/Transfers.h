// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Transfers.h
 * @brief The four transfers and what each means: the space of the Source
 *        functions it reads (P1 point arrays or P0 cell arrays), the space
 *        of the target functions it writes, and the order in which their
 *        arrays are written.
 *
 * The values are those of vtkMeshProjectionFilter::Transfers (GetMatrix's
 * argument), as the filter's .cxx asserts: Projection does not include the
 * public header.
 */
#ifndef MeshProjection_Projection_Transfers_h
#define MeshProjection_Projection_Transfers_h

#include "Transfer/Space.h"

namespace mpvtk
{
/// Source association to target association; the index of a leaf's operators.
enum Transfer : int
{
  PointsToPoints = 0,
  PointsToCells = 1,
  CellsToCells = 2,
  CellsToPoints = 3
};
constexpr int NumberOfTransfers = 4;
constexpr Transfer AllTransfers[NumberOfTransfers] = { PointsToPoints, PointsToCells, CellsToCells,
  CellsToPoints };
/**
 * The order the outputs are written in: each association's own transfer
 * first (points to points, cells to cells), so that an array going to the
 * other association is the one renamed when the names clash.
 */
constexpr Transfer OutputOrder[NumberOfTransfers] = { PointsToPoints, CellsToCells, PointsToCells,
  CellsToPoints };

/// Which Source fields a transfer reads: 0 point arrays (P1), 1 cell arrays (P0) (SourceFields.h's Association).
inline int SourceAssociation(Transfer t)
{
  return t == PointsToPoints || t == PointsToCells ? 0 : 1;
}
inline bool ToPoints(Transfer t)
{
  return t == PointsToPoints || t == CellsToPoints;
}
/// The space of the Source functions transfer t reads: cell arrays are DP1 when reconstructed
/// (Settings::ReconstructsCellData).
inline mp::SpaceType SourceSpaceOf(Transfer t, bool reconstructed)
{
  return SourceAssociation(t) == 0 ? mp::SpaceType::P1
                                   : (reconstructed ? mp::SpaceType::DP1 : mp::SpaceType::P0);
}
inline mp::SpaceType TargetSpaceOf(Transfer t)
{
  return ToPoints(t) ? mp::SpaceType::P1 : mp::SpaceType::P0;
}
/// A transfer to the association its Source arrays come from (the one whose integrals are reported).
inline bool IsOwnAssociation(Transfer t)
{
  return ToPoints(t) == (SourceAssociation(t) == 0);
}
inline const char* TransferName(Transfer t)
{
  static const char* names[] = { "points to points", "points to cells", "cells to cells",
    "cells to points" };
  return names[t];
}
} // namespace mpvtk

#endif
