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
 * The extension over the target's point or cell graph into the functions
 * not `valid`, built, reading the functions with reads[f] (`valid`'s
 * when null; a subset: the others are neither read nor extended).
 */
mp::Extension BuildExtension(LeafContext& ctx, const std::vector<char>& valid, bool points,
  const mp::SolverHooks& hook, const std::vector<char>* reads = nullptr)
{
  const mp::ExtrapolationMode mode = ctx.Options.Extrapolation;
  // Rows for the functions this operator leaves invalid.
  std::vector<char> want(valid.size());
  for (size_t f = 0; f < want.size(); ++f)
  {
    want[f] = !valid[f];
  }
  const mp::MeshView& view = ctx.Target.View();
  const mp::FunctionGraph graph = points ? mp::PointGraph(view, want) : mp::CellGraph(view, want);
  return mp::ExtendOver(graph, reads ? *reads : valid, mode, hook);
}

/**
 * Whether array a of transfer t is a mass-weighted one that the density
 * guard left undivided somewhere (on any process: collective when the
 * association is weighted), and then in `reads` its valid functions less
 * those: their values are no values of q (MassWeighting.h), so its
 * extension reads the divided ones only and stays within their range.
 */
bool NarrowedReads(LeafContext& ctx, const GatheredFields& g, int a, Transfer t,
  const std::vector<char>& valid, const LeafSolutions& solutions, std::vector<char>& reads)
{
  const int w = g.Mass.Active() ? g.Mass.WeightedIndex(a) : -1;
  if (w < 0)
  {
    return false;
  }
  const std::vector<char>& guarded = solutions.Guarded[t][static_cast<size_t>(w)];
  double any = guarded.empty() ? 0.0 : 1.0;
  ctx.Processes.Sum(&any, 1);
  if (any == 0.0)
  {
    return false;
  }
  reads = valid;
  for (size_t f = 0; f < guarded.size(); ++f)
  {
    reads[f] = reads[f] && !guarded[f];
  }
  return true;
}

/**
 * The extension of transfer t's own operator: the kept one where the cache
 * has one for the same mode and valid functions (those of an aggregated
 * solve drop the fringe's least covered ones, a lumped one's do not), else
 * built into `solutions` (the cache keeps it at the leaf's end). Whether to
 * reuse is agreed: the build is collective.
 */
const mp::Extension& OwnExtension(LeafContext& ctx, const KeptLeaf& kept, Transfer t,
  const std::vector<char>& valid, const mp::SolverHooks& hook, LeafSolutions& solutions)
{
  const std::uint64_t key = ExtensionKey(ctx.Options.Extrapolation, valid);
  const mp::Extension* found = kept.Extension(t, key);
  bool reuse = found != nullptr;
  ctx.Processes.Agree(Verdict(), &reuse);
  solutions.ExtensionKey[t] = key;
  if (reuse)
  {
    return *found;
  }
  solutions.Extension[t] = BuildExtension(ctx, valid, TargetSpaceOf(t) == mp::SpaceType::P1, hook);
  solutions.Built[t] = true;
  return solutions.Extension[t];
}

/// One transfer: its arrays extended one by one (each with its own operator's validity).
Verdict ExtrapolateTransfer(LeafContext& ctx, const KeptLeaf& kept, const OperatorSet& ops,
  Transfer t, const mp::SolverHooks& hook, LeafSolutions& solutions)
{
  const bool points = TargetSpaceOf(t) == mp::SpaceType::P1;
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  mp::LargeVector<double>& values = solutions.Values[t];
  double left = 0.0;
  const mp::MortarOperator* builtFor = nullptr;
  const mp::Extension* own = nullptr;
  mp::Extension group;
  const mp::Extension* ext = nullptr;
  std::vector<char> reads;
  for (size_t a = 0; a < g.Arrays.size(); ++a)
  {
    const mp::MortarOperator& op = *ops.ByArray[t][a];
    const std::vector<char>& valid = *solutions.ByArray[t][a].Valid;
    if (NarrowedReads(ctx, g, static_cast<int>(a), t, valid, solutions, reads))
    {
      // A mass-weighted array with guarded functions: an extension of its own.
      group = BuildExtension(ctx, valid, points, hook, &reads);
      ext = &group;
      builtFor = nullptr;
      left = std::max(left, static_cast<double>(ext->Unreached));
    }
    else if (&op != builtFor)
    {
      // The transfer's own operator's extension may be kept (GetMatrix, later steps); a NaN group's is its own.
      if (&op == ops.Operators[t])
      {
        own = own ? own : &OwnExtension(ctx, kept, t, valid, hook, solutions);
        ext = own;
      }
      else
      {
        group = BuildExtension(ctx, valid, points, hook);
        ext = &group;
      }
      builtFor = &op;
      left = std::max(left, static_cast<double>(ext->Unreached));
    }
    mp::ApplyExtension(
      *ext, values.data(), g.Components, g.Offsets[a], g.Arrays[a]->GetNumberOfComponents(), hook);
    if (&op == ops.Operators[t] && (ext == own || solutions.Extrapolated[t].empty()))
    {
      solutions.Extrapolated[t] = ext->Extended;
    }
  }
  if (left > 0.0 && ctx.Processes.Rank() == 0)
  {
    ctx.Say.WarnOnce("extrapolation/" + ctx.Role + (points ? "/points" : "/cells"),
      std::to_string(static_cast<long long>(left)) + " " + ctx.Role +
        (points ? " points" : " cells") + " are connected to no " + (points ? "point" : "cell") +
        " the Source reaches: Extrapolation leaves them the fill value.");
  }
  return Verdict();
}
} // namespace

Verdict ExtrapolateLeaf(LeafContext& ctx, const KeptLeaf& kept, const OperatorSet& ops,
  const mp::SolverHooks hooks[2], LeafSolutions& solutions)
{
  if (ctx.Options.Extrapolation == mp::ExtrapolationMode::None)
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
    const Verdict done =
      ExtrapolateTransfer(ctx, kept, ops, t, points ? hooks[0] : mp::SolverHooks(), solutions);
    if (!done.Ok())
    {
      return done;
    }
  }
  return Verdict();
}
} // namespace mpvtk
