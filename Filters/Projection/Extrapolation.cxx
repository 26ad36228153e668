// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Extrapolation.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"

#include "Projection/Messages.h"
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
 * The valid values of array `a` kept within the range of the Source values
 * (those this process gathered: on one process the field's range), so that
 * the extension, bounded by the valid values, is too. (The fringe's values
 * are extrapolations from well-covered points and may pass the Source's
 * extremes where the field goes on growing beyond it; so may the L2
 * projection next to an extreme on the Source's boundary.)
 */
void ClipToSource(const GatheredFields& g, size_t a, const mp::MortarOperator& op, mp::LargeVector<double>& values)
{
  const std::vector<char>& valid = op.GetValid();
  const int nc = g.Arrays[a]->GetNumberOfComponents();
  const size_t width = static_cast<size_t>(g.Components);
  const size_t sources = width > 0 ? g.Values.size() / width : 0;
  for (int k = 0; k < nc; ++k)
  {
    const size_t column = static_cast<size_t>(g.Offsets[a] + k);
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (size_t j = 0; j < sources; ++j)
    {
      const double v = g.Values[j * width + column];
      low = v < low ? v : low; // (NaN compares false: left out)
      high = v > high ? v : high;
    }
    for (size_t f = 0; f < valid.size() && low <= high; ++f)
    {
      if (valid[f])
      {
        double& v = values[f * width + column];
        v = std::min(high, std::max(low, v));
      }
    }
  }
}

/// One transfer: its arrays extended one by one (each with its own operator's validity).
Verdict ExtrapolateTransfer(LeafContext& ctx, const OperatorSet& ops, Transfer t,
  const mp::SolverHooks& hook, LeafSolutions& solutions)
{
  const mp::MeshView& view = ctx.Target.View();
  const bool points = TargetSpaceOf(t) == mp::SpaceType::P1;
  mp::FunctionGraph graph;
  const mp::MortarOperator* graphOf = nullptr;
  const GatheredFields& g = ctx.Source.Fields[SourceAssociation(t)];
  const auto mode = static_cast<mp::ExtrapolationMode>(ctx.Options.Extrapolation);
  mp::LargeVector<double>& values = solutions.Values[t];
  double left = 0.0;
  for (size_t a = 0; a < g.Arrays.size(); ++a)
  {
    const mp::MortarOperator& op = *ops.ByArray[t][a];
    ClipToSource(g, a, op, values);
    std::vector<char> extrapolated;
    if (graph.Size() == 0 || &op != graphOf)
    {
      // Rows for the functions this operator leaves invalid.
      std::vector<char> want(op.GetValid().size());
      for (size_t f = 0; f < want.size(); ++f)
      {
        want[f] = !op.GetValid()[f];
      }
      graph = points ? mp::PointGraph(view, want) : mp::CellGraph(view, want);
      graphOf = &op;
    }
    const mp::Index unreached = mp::Extrapolate(graph, op.GetValid(), values.data(), g.Components,
      g.Offsets[a], g.Arrays[a]->GetNumberOfComponents(), mode, hook, extrapolated);
    left = std::max(left, static_cast<double>(unreached));
    if (&op == ops.Operators[t])
    {
      solutions.Extrapolated[t].swap(extrapolated);
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

Verdict ExtrapolateLeaf(LeafContext& ctx, const OperatorSet& ops, const mp::SolverHooks hooks[2],
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
    const Verdict done = ExtrapolateTransfer(ctx, ops, t, points ? hooks[0] : mp::SolverHooks(), solutions);
    if (!done.Ok())
    {
      return done;
    }
  }
  return Verdict();
}
} // namespace mpvtk
