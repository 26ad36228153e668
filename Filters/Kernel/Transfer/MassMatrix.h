// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MassMatrix.h
 * @brief The pattern of the target mass matrix M_tt of a space.
 *
 * P1: the point graph of the mesh (every pair of points sharing a cell, and
 * every point with itself), built from the cells around each point in
 * concurrent tasks over point ranges. P0: the diagonal. The values are
 * zeros, summed by the assembler (MortarAssembler.h).
 */
#ifndef MeshProjection_Kernel_MassMatrix_h
#define MeshProjection_Kernel_MassMatrix_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"
#include "Transfer/CsrMatrix.h"
#include "Transfer/Space.h"

namespace mp
{
/// The CSR pattern of M_tt for `space` on `mesh`, with zero values.
void MassPattern(SpaceType space, const MeshView& mesh, const TaskRunner& runner, CsrMatrix& matrix);
} // namespace mp

#endif
