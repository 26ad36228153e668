// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalMass.h
 * @brief M_tt of the cells' own space (NodalSpace.h), and what the fringe
 *        reads of it, after a search by quadrature (QuadratureAssembler.h).
 *
 * The quadrature assembler leaves M_tt as blocks, one per covered target
 * cell or one per function of such a cell (MixedBlocks). Their sum in
 * compressed rows is M_tt over the covered part; every row also holds its
 * diagonal (0 where no piece met the function), which the operator turns
 * into the 1 of an invalid function as for the linear path.
 *
 * The fringe (FringeAggregation.h) asks how much of each function's
 * support is covered. For P1 that is int_covered phi_i / int phi_i; a
 * quadratic corner function's integral is zero (triangles) or negative
 * (tetrahedra), so the cells' own space measures the support by its cells
 * instead: the covered measure of the simplices a function lives on over
 * their measure (NodalSupportCover).
 */
#ifndef MeshProjection_Kernel_NodalMass_h
#define MeshProjection_Kernel_NodalMass_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"
#include "Transfer/CsrMatrix.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/Space.h"

#include <vector>

namespace mp
{
/**
 * M_tt for `space` on `mesh` from the tasks' blocks (emptied), with every
 * row's diagonal in its pattern. With `cover` and `parentFraction` (per
 * parent of `mesh`): per point the largest fraction of the parents whose
 * functions use it (0 for a point no cell uses).
 */
void AssembleNodalTargetMass(std::vector<MixedBlocks>& blocks, const MeshView& mesh,
  SpaceType space, const TaskRunner& runner, CsrMatrix& matrix,
  const double* parentFraction = nullptr, LargeVector<double>* cover = nullptr);

/**
 * Per point function of `mesh` (NodalSpace.h): the measure of the
 * simplices it lives on (`whole`) and their covered measure (`covered`,
 * each simplex's measure times its parent's `parentFraction`).
 */
void NodalSupportCover(const MeshView& mesh, const double* parentFraction,
  std::vector<double>& covered, LargeVector<double>& whole);
} // namespace mp

#endif
