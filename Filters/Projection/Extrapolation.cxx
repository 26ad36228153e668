// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Extrapolation.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"

#include "Projection/Messages.h"
#include "Projection/OperatorCache.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"
#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"

#include "Transfer/Extrapolation.h"

#include <algorithm>
#include <limits>
#include <string>

namespace mpvtk
{
namespace
{
/**
 * The extension over `op`'s invalid functions: the kept one where it is
 * this operator's (a reused operator, the same mode, the same valid
 * functions: those of an aggregated solve drop the fringe's least covered
 * ones, a lumped one's do not), else built. Whether to reuse is agreed:
 * the build is collective.
 */
const mp::Extension& ExtensionOf(LeafContext& ctx, const mp::MortarOperator& op,
  const std::vector<char>& valid, bool points, const mp::SolverHooks& hook, KeptOperator* kept,
  mp::Extension& own)
{
  const auto mode = static_cast<mp::ExtrapolationMode>(ctx.Options.Extrapolation);
  mp::Extension& ext = kept ? kept->Extension : own;
  if (kept)
  {
    bool reuse = kept->Operator.get() == &op && kept->ExtensionFor == &op && ext.Mode == mode &&
      ext.Valid == valid;
    ctx.Processes.Agree(Verdict(), &reuse);
    if (reuse)
    {
      return ext;
    }
  }
  // Rows for the functions this operator leaves invalid.
  std::vector<char> want(valid.size());
  for (size_t f = 0; f < want.size(); ++f)
  {
    want[f] = !valid[f];
  }
  const mp::MeshView& view = ctx.Target.View();
  const mp::FunctionGraph graph = points ? mp::PointGraph(view, want) : mp::CellGraph(view, want);
  ext = mp::ExtendOver(graph, valid, mode, hook);
  if (kept)
  {
    kept->ExtensionFor = &op;
  }
  return ext;
}

/// One transfer: its arrays extended one by one (each with its own operator's validity).
Verdict ExtrapolateTransfer(LeafContext& ctx, KeptLeaf& kept, const OperatorSet& ops, Transfer t,
  const mp::SolverHooks& hook, LeafSolutions& solutions)
{
  const bool points = TargetSpaceOf(t) == mp::SpaceType::P1;
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  mp::LargeVector<double>& values = solutions.Values[t];
  double left = 0.0;
  const mp::MortarOperator* builtFor = nullptr;
  mp::Extension own;
  const mp::Extension* ext = nullptr;
  for (size_t a = 0; a < g.Arrays.size(); ++a)
  {
    const mp::MortarOperator& op = *ops.ByArray[t][a];
    if (&op != builtFor)
    {
      // The transfer's own operator keeps its extension (GetMatrix, later steps).
      const bool main = &op == ops.Operators[t] && ctx.Options.CacheOperator;
      ext = &ExtensionOf(ctx, op, *solutions.ByArray[t][a].Valid, points, hook,
        main ? &kept.Operators[t] : nullptr, own);
      builtFor = &op;
      left = std::max(left, static_cast<double>(ext->Unreached));
    }
    mp::ApplyExtension(*ext, values.data(), g.Components, g.Offsets[a],
      g.Arrays[a]->GetNumberOfComponents(), hook);
    if (&op == ops.Operators[t])
    {
      solutions.Extrapolated[t] = ext->Extended;
    }
  }
  if (left > 0.0 && ctx.Processes.Rank() == 0)
  {
    ctx.Say.WarnOnce("extrapolation/" + ctx.Role + (points ? "/points" : "/cells"),
      std::to_string(static_cast<long long>(left)) + " " + ctx.Role + (points ? " points" : " cells") +
        " are connected to no " + (points ? "point" : "cell") +
        " the Source reaches: Extrapolation leaves them the fill value.");
  }
  return Verdict();
}
} // namespace

Verdict ExtrapolateLeaf(LeafContext& ctx, KeptLeaf& kept, const OperatorSet& ops, const mp::SolverHooks hooks[2],
  LeafSolutions& solutions)
{
  if (ctx.Options.Extrapolation == 0)
  {
    return Verdict();
  }
  for (Transfer t : AllTransfers)
  {
    if (!ops.Operators[t] || ctx.Source.Fields[SourceAssociation(t)].Components == 0)
    {
      continue;
    }
    const bool points = TargetSpaceOf(t) == mp::SpaceType::P1;
    // Cells are not shared between processes: each extends over its own.
    const Verdict done = ExtrapolateTransfer(ctx, kept, ops, t, points ? hooks[0] : mp::SolverHooks(), solutions);
    if (!done.Ok())
    {
      return done;
    }
  }
  return Verdict();
}
} // namespace mpvtk
