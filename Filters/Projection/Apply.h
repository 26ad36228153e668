// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Apply.h
 * @brief Applying one leaf's operators: M_ts u_s, then M_tt (consistent,
 *        from the previous step's solution when the same arrays meet the
 *        same operator) or its row sums (lumped), with bounds when asked;
 *        each Apply's system kept with its values (LeafSolutions).
 *
 * On several processes the systems are one global system each: the rows
 * shared with other processes are completed in every product (the hooks),
 * and a function valid on any process is valid on all.
 */
#ifndef MeshProjection_Projection_Apply_h
#define MeshProjection_Projection_Apply_h

#include "Projection/Leaf.h"

#include "Mesh/LargeArray.h"
#include "Transfer/BlockCG.h"
#include "Transfer/Extrapolation.h"
#include "Transfer/MortarOperator.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mpvtk
{
struct KeptLeaf;

/**
 * One label array's result on one transfer's target functions (Labels.h:
 * ApplyLabels): per target function the index of the label that wins
 * there (-1: none; empty when no label is anywhere) and, when asked for
 * (LabelFractions, at most MaximumLabelFractions labels), the fractions,
 * target functions x labels.
 */
struct LabelSolution
{
  std::vector<int> Winner;
  mp::LargeVector<double> Fractions;
};

/// The solutions of one leaf: per transfer, target functions x the fields' components.
struct LeafSolutions
{
  mp::LargeVector<double> Values[NumberOfTransfers];
  /**
   * Per transfer in use: the system its own operator's values were solved
   * in (mp::ApplyResult::System; M_tt's when nothing was applied), which
   * the masks, extrapolation and outputs read.
   */
  mp::ProjectedSystem System[NumberOfTransfers];
  /// Per transfer and Source array: the system of its operator's Apply (its NaN group's, or System[t]).
  std::vector<mp::ProjectedSystem> ByArray[NumberOfTransfers];
  /// Per transfer: the functions whose values were extrapolated (its operator's; Extrapolation).
  std::vector<char> Extrapolated[NumberOfTransfers];
  /// With CachePlan::Keep, per transfer: its operator's solution (before
  /// the NaN groups' columns and the extrapolation) and its fields' key,
  /// the next execution's start (KeptLeaf::Store).
  mp::LargeVector<double> Solved[NumberOfTransfers];
  std::string SolvedKey[NumberOfTransfers];
  bool Aside[NumberOfTransfers] = {}; ///< Solved and SolvedKey set
  /// Per transfer: the key of the extension its operator's arrays took
  /// (ExtensionKey; 0: none) and, when built here (Built), the extension.
  std::uint64_t ExtensionKey[NumberOfTransfers] = {};
  bool Built[NumberOfTransfers] = {};
  mp::Extension Extension[NumberOfTransfers];
  /**
   * Mass weighting (MassWeighting.h), per transfer: the weighted arrays'
   * projected products rho q (target functions x their components, in
   * GatheredFields::Mass.Weighted's order), before the division; and per
   * weighted array, the functions valid in its system that the density
   * guard left undivided (empty: none).
   */
  mp::LargeVector<double> Products[NumberOfTransfers];
  std::vector<std::vector<char>> Guarded[NumberOfTransfers];
  /// Per transfer and label array of its association (GatheredFields::Labels): the
  /// winning labels and the fractions (Labels.h: LabelSolution).
  std::vector<LabelSolution> Labels[NumberOfTransfers];
};

/// The solver's hooks of P1 (0) and P0 (1) target functions; P1 operators
/// share their validity, then aggregate their fringe (FringeThreshold; on
/// several processes with the target's `halo`, made here). First decides,
/// alike everywhere, whether second-order Input cells have a Bernstein
/// form (LeafShape::Bernstein).
void ShareSystems(
  LeafContext& ctx, const OperatorSet& ops, mp::SolverHooks hooks[2], mp::FringeHalo& halo);

/**
 * Applies every operator in use to its fields (and NaN groups' operators to
 * theirs), warm started from the kept solution where `kept` has one for the
 * same fields; with plan.Cache.Keep each solution is put aside to be kept;
 * then the label arrays (Labels.h: ApplyLabels).
 */
Verdict ApplyOperators(LeafContext& ctx, const KeptLeaf& kept, const OperatorPlan& plan,
  const OperatorSet& ops, const mp::SolverHooks hooks[2], const mp::FringeHalo& halo,
  LeafSolutions& solutions);
} // namespace mpvtk

#endif
