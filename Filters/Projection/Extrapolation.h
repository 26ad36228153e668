// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Extrapolation.h
 * @brief Beyond the Source (Extrapolation): each projected array's values
 *        extended from its valid functions over Input's point graph (point
 *        data) or cell graph (cell data), after the solves and before the
 *        outputs (the integrals stay those of the covered part).
 *
 * On several processes the point graph is one over all processes (shared
 * points completed by the hooks); the cell graph and the nearest values are
 * each process's own.
 */
#ifndef MeshProjection_Projection_Extrapolation_h
#define MeshProjection_Projection_Extrapolation_h

#include "Projection/Apply.h"
#include "Projection/Leaf.h"

namespace mpvtk
{
/**
 * Extends every transfer's arrays (Settings::Extrapolation); a failure is a
 * stop or an error. The transfer's own operator takes the extension `kept`
 * has for the same mode and valid functions (ExtensionKey), else one built
 * here into `solutions`, which the cache keeps with the operator at the
 * leaf's end (later steps, GetMatrix EXTRAPOLATION).
 */
Verdict ExtrapolateLeaf(LeafContext& ctx, const KeptLeaf& kept, const OperatorSet& ops,
  const mp::SolverHooks hooks[2], LeafSolutions& solutions);
} // namespace mpvtk

#endif
