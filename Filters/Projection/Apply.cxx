// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Apply.h"
#include "Projection/Messages.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"

#include "Projection/Labels.h"
#include "Projection/OperatorCache.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"
#include "Adapter/SimplexMesh.h"
#include "Transfer/BernsteinForm.h"

#include <algorithm>
#include <vector>

namespace mpvtk
{
namespace
{
/// Why an Apply failed: a stop, or a system it could not solve (the execution then drops the leaf's cache).
Verdict ApplyFailed(const mp::ApplyResult& applied, Transfer t)
{
  if (applied.Stopped)
  {
    return Verdict::Stop();
  }
  return Verdict::Fail(std::string("The projection of ") + TransferName(t) +
    " failed: the mass matrix of the covered target part could not be solved.");
}

/// The NaN groups' arrays: their own operators, their columns of `values`, their systems.
Verdict ApplyGroups(LeafContext& ctx, const OperatorSet& ops, Transfer t,
  const mp::ApplyOptions& apply, const mp::SolverHooks& hook, mp::LargeVector<double>& values,
  std::vector<mp::ProjectedSystem>& systems)
{
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  const double fill = ctx.Options.Fill();
  for (const NaNGroup& group : g.Groups)
  {
    const mp::MortarOperator& op = *ops.ByArray[t][group.Arrays[0]];
    const size_t rows = static_cast<size_t>(op.GetNumberOfTargetFunctions());
    mp::LargeVector<double> own(rows * group.Components);
    mp::ApplyOptions groupApply = apply;
    groupApply.Solve.StartFromX = false;
    const mp::ApplyResult applied =
      op.Apply(group.Functions().data(), group.Components, own.data(), fill, groupApply, hook);
    if (!applied)
    {
      return ApplyFailed(applied, t);
    }
    ctx.Stats.Solve += applied.Seconds;
    int column = 0;
    for (int a : group.Arrays)
    {
      systems[static_cast<size_t>(a)] = applied.System;
      const int nc = g.Arrays[a]->GetNumberOfComponents();
      for (size_t f = 0; f < rows; ++f)
      {
        for (int c = 0; c < nc; ++c)
        {
          values[f * g.Components + g.Offsets[a] + c] = own[f * group.Components + column + c];
        }
      }
      column += nc;
    }
  }
  return Verdict();
}

/**
 * Point data on second-order Input cells without a form (on any process:
 * the choice is the same everywhere, the solves being collective): the
 * consistent mass and no node bounds, each said once. The 8-node
 * quadrilaterals, 20-node hexahedra and 15-node wedges weigh their
 * mid-edge nodes' corners by 7/16 in their form, the other second-order
 * cells by 1/4 (BernsteinForm::EdgeShare): a shared edge would have two
 * rows. (Every other second-order Input is lumped and bounded in its
 * form: MassType::Lumped.)
 */
void SecondOrderSolve(LeafContext& ctx, mp::ApplyOptions& apply)
{
  const std::string cells = ctx.Role +
    " mixes serendipity cells (8-node quadrilaterals, 20-node hexahedra or 15-node wedges) with "
    "other second-order cells, whose forms ";
  if (apply.Mass == mp::MassType::Lumped)
  {
    apply.Mass = mp::MassType::Consistent;
    ctx.Say.WarnOnce("lumped/" + ctx.Role,
      "MassMatrix is Lumped, but " + cells +
        "do not agree on their shared edges: its point data is projected with the consistent "
        "mass.");
  }
  if (apply.Bounded)
  {
    apply.Bounded = false;
    ctx.Say.WarnOnce("bounds/" + ctx.Role,
      "PreserveBounds: " + cells +
        "do not agree on their shared edges: its point data is projected without bounds.");
  }
}

/// One transfer: its fields' solution (warm started when it may), then the NaN groups'.
Verdict ApplyTransfer(LeafContext& ctx, const KeptLeaf& kept, const OperatorPlan& plan,
  const OperatorSet& ops, Transfer t, const mp::SolverHooks& hook, const mp::FringeHalo& halo,
  LeafSolutions& solutions)
{
  mp::LargeVector<double>& values = solutions.Values[t];
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  const mp::MortarOperator& op = *ops.Operators[t];
  const size_t size = static_cast<size_t>(op.GetNumberOfTargetFunctions()) * g.Components;
  mp::ApplyOptions apply;
  apply.Mass = ctx.Options.Lumped ? mp::MassType::Lumped : mp::MassType::Consistent;
  apply.Bounded = ctx.Options.PreserveBounds;
  apply.Signed = ctx.Shape.Signed;
  if (ctx.Shape.SecondOrder && !ctx.Shape.Bernstein && TargetSpaceOf(t) == mp::SpaceType::P1)
  {
    SecondOrderSolve(ctx, apply);
  }
  else if (ctx.Shape.Signed && apply.Mass == mp::MassType::Lumped &&
    TargetSpaceOf(t) == mp::SpaceType::P1)
  {
    apply.Bounded = true; // (a signed form's coefficients, clipped on every process alike)
  }
  apply.Solve.MaxIterations = ctx.Options.MaximumIterations;
  apply.FringeHooks =
    halo.Hooks.Exchange && TargetSpaceOf(t) == mp::SpaceType::P1 ? &halo.Hooks : nullptr;
  if (ctx.Processes.Whole())
  {
    // Progress and a stop inside the solve too (one process: several
    // would have to stop at the same iteration).
    const ProgressShare bar = ctx.Bar;
    apply.Solve.Progress = [bar](double done) { return bar(0.9 + 0.05 * done); };
  }
  const mp::LargeVector<double>* start = ops.Fresh[t] ? nullptr : kept.WarmStart(t, g.Key, size);
  bool warm = start != nullptr;
  ctx.Processes.Agree(Verdict(), &warm); // all processes start alike
  if (warm)
  {
    values.assign(start->begin(), start->end());
    apply.Solve.StartFromX = true;
  }
  else
  {
    values.resize(size);
  }
  const mp::ApplyResult applied =
    op.Apply(g.Functions().data(), g.Components, values.data(), ctx.Options.Fill(), apply, hook);
  if (!applied)
  {
    return ApplyFailed(applied, t);
  }
  ctx.Stats.Solve += applied.Seconds;
  solutions.System[t] = applied.System;
  solutions.ByArray[t].assign(g.Arrays.size(), applied.System);
  if (plan.Cache.Keep)
  {
    solutions.Aside[t] = true;
    solutions.SolvedKey[t] = g.Key;
    solutions.Solved[t].assign(values.begin(), values.end());
  }
  return ApplyGroups(ctx, ops, t, apply, hook, values, solutions.ByArray[t]);
}
/**
 * The fringe of every P1 operator in use aggregated (MortarOperator::
 * AggregateFringe), on every kind of target: volumes, surfaces, curves and
 * traces (on surfaces and curves the stencils are fitted in the tangent
 * coordinates, FringeFrames.h). On several processes first the target's
 * halo (Parts::Halo), so that every process extends as the serial run does.
 * Collective: every process decides alike and calls it for the same
 * operators.
 */
void AggregateFringes(
  LeafContext& ctx, const OperatorSet& ops, const mp::SolverHooks& hooks, mp::FringeHalo& halo)
{
  const mp::MeshView& view = ctx.Target.View();
  const double threshold = ctx.Options.FringeThreshold;
  // (Lumped values are means: nothing to aggregate; a later consistent run
  // aggregates then. Second-order targets without a Bernstein form are
  // solved with the consistent mass whatever the setting: ApplyTransfer.)
  const bool lumped = !ctx.Shape.SecondOrder || ctx.Shape.Bernstein;
  const double used = ctx.Options.Lumped && lumped ? 0.0 : threshold;
  bool anyP1 = false;
  for (Transfer t : AllTransfers)
  {
    anyP1 = anyP1 || (ops.Operators[t] && TargetSpaceOf(t) == mp::SpaceType::P1);
  }
  if (used > 0.0 && anyP1)
  {
    // (Kept operators need it too: their aggregated systems have its rows.)
    const SimplexMesh& target = ctx.Target;
    halo = ctx.Processes.Halo(
      ctx.Shared, view, [&target](mp::Index f) { return target.DataSetPoint(f); });
  }
  for (Transfer t : AllTransfers)
  {
    if (!ops.Operators[t] || TargetSpaceOf(t) != mp::SpaceType::P1)
    {
      continue;
    }
    std::vector<const mp::MortarOperator*> all{ ops.Operators[t] };
    for (const mp::MortarOperator* op : ops.ByArray[t])
    {
      if (std::find(all.begin(), all.end(), op) == all.end())
      {
        all.push_back(op);
      }
    }
    for (const mp::MortarOperator* op : all)
    {
      const double before = op->GetTimings().Assembly;
      const_cast<mp::MortarOperator*>(op)->AggregateFringe(view, used, hooks, &halo);
      ctx.Stats.Assembly += op->GetTimings().Assembly - before;
    }
  }
}
} // namespace

void ShareSystems(
  LeafContext& ctx, const OperatorSet& ops, mp::SolverHooks hooks[2], mp::FringeHalo& halo)
{
  if (ctx.Shape.SecondOrder)
  {
    // Whether every process's second-order Input cells have a Bernstein
    // form (the lumped mass and the bounds of their point data).
    // (and take one edge share: a shared edge's row is the same on both
    // sides).
    const mp::MeshView& view = ctx.Target.View();
    bool bernstein = mp::BernsteinForm::Covers(view);
    const int shares = mp::BernsteinForm::EdgeShares(view);
    bool noQuarter = !(shares & mp::BernsteinForm::QuarterShare);
    bool noSixteenths = !(shares & mp::BernsteinForm::SevenSixteenthsShare);
    ctx.Processes.Agree(Verdict(), &bernstein);
    ctx.Processes.Agree(Verdict(), &noQuarter);
    ctx.Processes.Agree(Verdict(), &noSixteenths);
    ctx.Shape.Bernstein = bernstein && (noQuarter || noSixteenths);
  }
  const SimplexMesh& target = ctx.Target;
  hooks[0] = ctx.Processes.Hooks(ctx.Shared, true,
    static_cast<mp::Index>(ctx.TargetData->GetNumberOfPoints()),
    [&target](mp::Index f) { return target.DataSetPoint(f); });
  hooks[1] = ctx.Processes.Hooks(ctx.Shared, false, 0, nullptr);
  for (Transfer t : AllTransfers)
  {
    if (!ops.Operators[t] || TargetSpaceOf(t) != mp::SpaceType::P1)
    {
      continue;
    }
    const_cast<mp::MortarOperator*>(ops.Operators[t])->ShareValidity(hooks[0]);
    for (const mp::MortarOperator* op : ops.ByArray[t])
    {
      if (op != ops.Operators[t])
      {
        const_cast<mp::MortarOperator*>(op)->ShareValidity(hooks[0]);
      }
    }
  }
  AggregateFringes(ctx, ops, hooks[0], halo);
}

Verdict ApplyOperators(LeafContext& ctx, const KeptLeaf& kept, const OperatorPlan& plan,
  const OperatorSet& ops, const mp::SolverHooks hooks[2], const mp::FringeHalo& halo,
  LeafSolutions& solutions)
{
  for (Transfer t : AllTransfers)
  {
    if (ops.Operators[t])
    {
      solutions.System[t] = ops.Operators[t]->GetAssembledSystem(); // (until applied)
    }
    if (!ops.Operators[t] || ctx.Source.Fields[SourceAssociation(t)].Components == 0)
    {
      continue;
    }
    const mp::SolverHooks& hook = hooks[TargetSpaceOf(t) == mp::SpaceType::P1 ? 0 : 1];
    const Verdict applied = ApplyTransfer(ctx, kept, plan, ops, t, hook, halo, solutions);
    if (!applied.Ok())
    {
      return applied;
    }
  }
  return ApplyLabels(ctx, ops, hooks, solutions);
}
} // namespace mpvtk
