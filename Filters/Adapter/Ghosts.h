// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Ghosts.h
 * @brief Which cells of a dataset the projection leaves out as ghosts: the
 *        one rule, for the wraps and for the gathering on several processes.
 *
 * A cell flagged DUPLICATECELL (owned by another process) or HIDDENCELL
 * (blanked) is not part of the mesh; other ghost flags (REFINEDCELL,
 * EXTERIORCELL, ...) describe cells that still are.
 */
#ifndef MeshProjection_Adapter_Ghosts_h
#define MeshProjection_Adapter_Ghosts_h

#include "vtkDataSetAttributes.h"
#include "vtkType.h"
#include "vtkUnsignedCharArray.h"

namespace mpvtk
{
/// The ghost flags that leave a cell out.
constexpr unsigned char LeftOutGhostFlags =
  vtkDataSetAttributes::DUPLICATECELL | vtkDataSetAttributes::HIDDENCELL;

/// Whether cell c is left out (`ghosts` may be null: no ghost cells).
inline bool IsLeftOutGhost(vtkUnsignedCharArray* ghosts, vtkIdType c)
{
  return ghosts && (ghosts->GetValue(c) & LeftOutGhostFlags) != 0;
}
} // namespace mpvtk

#endif
