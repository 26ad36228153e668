// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file OperatorBuild.h
 * @brief The operators of one leaf: which transfers run, which kept
 *        operators serve again, and the search that builds the others.
 *
 * Every operator to build comes from one search over the leaf's meshes
 * (each intersection piece goes to every operator's sums: point and cell
 * data cost one search, not two), started once the neighbours and the
 * Source locator exist (made by the first leaf that searches). NaN groups
 * have operators of their own, each from a search with the group's Source
 * cells left out, kept like the others while the meshes and the cells left
 * out are the same. M_tt is completed later (CompleteTargetMass), once the
 * Source's arrays that the search needed are gone.
 */
#ifndef MeshProjection_Projection_OperatorBuild_h
#define MeshProjection_Projection_OperatorBuild_h

#include "Projection/Leaf.h"

namespace mpvtk
{
class LeafAgreement;
struct KeptLeaf;

/**
 * Which transfers run and how: the cache looked up (KeptLeaf::LookUp; takes
 * part in the Build round: kept operators serve only where every process
 * can keep its own), then begun (KeptLeaf::Begin: cleared when the meshes
 * changed).
 */
Verdict PlanOperators(
  LeafContext& ctx, KeptLeaf& kept, LeafAgreement& agreement, OperatorPlan& plan);

/**
 * The operators of the plan: kept ones, and the others built by one
 * search, then the NaN groups' operators. Adds to the leaf's statistics
 * and warns of degenerate cells, no overlap and overlapping Source cells.
 */
Verdict BuildOperators(LeafContext& ctx, KeptLeaf& kept, const OperatorPlan& plan,
  LeafAgreement& agreement, OperatorSet& ops);
} // namespace mpvtk

#endif
