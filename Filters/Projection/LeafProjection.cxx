// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/LeafProjection.h"

#include "vtkDataSet.h"

#include "Projection/Agreement.h"
#include "Projection/Apply.h"
#include "Projection/Conservation.h"
#include "Projection/Extrapolation.h"
#include "Projection/MassWeighting.h"
#include "Projection/Messages.h"
#include "Projection/OperatorBuild.h"
#include "Projection/OperatorCache.h"
#include "Projection/Outputs.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"
#include "Adapter/SimplexMesh.h"

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace mpvtk
{
namespace
{
/**
 * Test only: whether the environment variable MESHPROJECTION_TEST_FAULT
 * is `stage`@`rank` (docs/testing.md), a fault this process then makes
 * in the leaf: "solve" (its solves reported failed), "local" (an
 * exception in a step of this process alone), "collective" (an exception
 * between the solves' collectives, where the others wait). Unset: never.
 */
bool TestFault(const char* stage, const Parts& parts)
{
  const char* fault = std::getenv("MESHPROJECTION_TEST_FAULT");
  return fault && std::string(fault) == std::string(stage) + "@" + std::to_string(parts.Rank());
}

/// The text of a test fault's failure or exception.
std::string TestFaultText(const char* stage)
{
  return std::string("MESHPROJECTION_TEST_FAULT ") + stage + " (a fault made by a test)";
}

/// Stage 1: the target as the kernel's mesh.
Verdict WrapTarget(const ExecutionShare& run, vtkDataSet* target, const std::string& role,
  SimplexMesh& mesh, Statistics& stats, LeafAgreement& agreement)
{
  mesh.SetOrdering(run.Options.Renumbering);
  mesh.SetCurvedLevel(run.Options.CurvedCellSubdivision);
  const std::string why = mesh.Wrap(target, role.c_str());
  stats.Check += mesh.CheckSeconds();
  stats.Renumber += mesh.OrderSeconds();
  stats.RenumberedMeshes = mesh.Ordered() + run.Source.Mesh.Ordered();
  if (!why.empty())
  {
    return agreement.End(Verdict::Fail(why));
  }
  WarnLeftOut(mesh, role, run.Say);
  stats.Input += run.Clock.Lap();
  return Verdict();
}

/// What the shape means for the user: a Source in a parallel plane, ghost cells, traces.
void WarnShape(LeafContext& ctx)
{
  // The Source's own warnings for the first leaf that gets this far only.
  const bool first = ctx.Say.FirstInRun("shape");
  const SimplexMesh& source = ctx.Source.Mesh;
  if (!ctx.Shape.PlaneWarning.empty() && first)
  {
    ctx.Say.Warn(ctx.Shape.PlaneWarning);
  }
  if (ctx.Target.GhostCells() || (first && source.GhostCells()))
  {
    ctx.Say.Warn("Ghost cells (" + ctx.Role + ": " + std::to_string(ctx.Target.GhostCells()) +
      ", Source: " + std::to_string(source.GhostCells()) + ") are left out of the projection.");
  }
  const bool extensive = ctx.Options.Extensive;
  const bool conserve = ctx.Options.ConserveSourceIntegral;
  if (ctx.Shape.Trace && (extensive || conserve))
  {
    const std::string densities =
      std::string("extensive cell arrays are given as the Source's densities (per unit of its ") +
      (source.Dimension() == 3 ? "volume), " : "area), ");
    ctx.Say.WarnOnce("trace/" + ctx.Role,
      ctx.Role + " lies inside the " + std::to_string(source.Dimension()) +
        "D Source (a trace): " + (extensive ? densities : std::string()) +
        (conserve ? "ConserveSourceIntegral does nothing, " : "") +
        "since a surface or curve holds no part of the Source's integrals.");
  }
}

/**
 * Stage 4: what the solves do not need goes before they need the room. The
 * last leaf's meshes are read again by the outputs only: what those take
 * from them (the Source weights, the target's point cover) is taken now,
 * and the meshes' own arrays (a renumbered copy, neighbours, the Source's
 * locator) go; the target's own after the fringe's aggregation, which
 * reads it (ProjectLeaf). (Not with the intersection pieces, which read
 * both meshes, nor on several processes, whose Source weights are
 * collective.) Then M_tt of the operators built here, on the target alone.
 */
bool PrepareSolves(LeafContext& ctx, const OperatorPlan& plan, OperatorSet& ops,
  SourceWeights& weights, mp::LargeVector<double>& cover)
{
  const bool release =
    ctx.LastReaderOfSource && !ctx.Options.OutputIntersections && ctx.Processes.Whole();
  SourceSide& source = ctx.Source;
  if (release)
  {
    const auto weighing = std::chrono::steady_clock::now();
    for (Transfer t : AllTransfers)
    {
      for (const mp::MortarOperator* op : ops.ByArray[t])
      {
        weights.Weigh(*op);
      }
    }
    // (Counted with the assembly; made later, with the outputs, they count there.)
    ctx.Stats.Assembly +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - weighing).count();
    source.Locator.reset();
    source.Mesh.ReleaseGeometry();
    // The point order and parents too when no operator of this execution
    // will be kept (GetMatrix maps a kept one's columns through them).
    bool keeps = false;
    for (const mp::MortarOperator* op : ops.Deferred)
    {
      keeps = keeps || plan.Cache.Keeps(*op);
    }
    if (!keeps)
    {
      source.Mesh.ReleaseOrder();
    }
  }
  for (mp::MortarOperator* op : ops.Deferred)
  {
    const double before = op->GetTimings().Assembly;
    op->CompleteTargetMass(ctx.Target.View());
    ctx.Stats.Assembly += op->GetTimings().Assembly - before;
  }
  if (release && ctx.Target.OwnsGeometry())
  {
    cover = PointCover(ctx.Target, ops);
    return true; // the target's geometry goes once the fringe is aggregated
  }
  return false;
}
} // namespace

LeafResult ProjectLeaf(const ExecutionShare& run, const LeafJob& job, KeptLeaf& kept)
{
  LeafResult result;
  LeafAgreement agreement(run.Processes);
  // On several processes the dataset first learns the points it shares
  // with others (and gets global point ids).
  const SharedTarget shared = run.Processes.ShareTarget(job.Target);
  vtkDataSet* target = shared.Data;
  SimplexMesh targetMesh;
  ShareCurvedUnrefinable(run.Processes, target, run.Options.CurvedCellSubdivision, targetMesh);
  // The steps of this process alone run through agreement.Local (an
  // exception there is this process's failure, agreed at the next round).
  result.Outcome = agreement.Local("Reading " + job.Role,
    [&]() { return WrapTarget(run, target, job.Role, targetMesh, result.Stats, agreement); });
  if (!result.Outcome.Ok())
  {
    return result;
  }
  LeafContext ctx{ run.Options, run.Processes, run.Say, job.Bar, run.Clock, result.Stats,
    run.Source, targetMesh, target, shared, job.Role, LeafShape(), job.LastReaderOfSource };
  OperatorPlan plan;
  OperatorSet ops;
  // (DecideShape runs its own steps of this process alone through
  // agreement.Local: its collective sums are outside them.)
  result.Outcome = DecideShape(ctx, agreement);
  if (result.Outcome.Ok())
  {
    WarnShape(ctx);
    result.Outcome = agreement.Local("Building the operators", [&]() {
      if (TestFault("local", run.Processes))
      {
        throw std::runtime_error(TestFaultText("local"));
      }
      const Verdict planned = PlanOperators(ctx, kept, agreement, plan);
      return planned.Ok() ? BuildOperators(ctx, kept, plan, agreement, ops) : planned;
    });
  }
  if (!result.Outcome.Ok())
  {
    return result;
  }
  // Every operator of this leaf is built: the target's neighbours go
  // before the solves need their room (the Source's may serve other leaves).
  targetMesh.ReleaseNeighbors();
  run.Clock.Lap();
  SourceWeights weights(run.Source.Mesh, run.Source.Data, run.Processes);
  mp::LargeVector<double> cover;
  bool haveCover = false;
  // The operators' target mass too before the round (this process alone).
  result.Outcome = ctx.Bar(0.9) ? agreement.Local("Assembling the target mass",
                                    [&]() {
                                      haveCover = PrepareSolves(ctx, plan, ops, weights, cover);
                                      return agreement.At(LeafAgreement::Solve);
                                    })
                                : agreement.End(Verdict::Stop());
  if (!result.Outcome.Ok())
  {
    return result;
  }
  mp::SolverHooks hooks[2]; // P1, P0 target functions
  mp::FringeHalo halo;      // several processes: the fringe's ghost layer
  ShareSystems(ctx, ops, hooks, halo);
  // (The extrapolation reads the target's cells after the solves.)
  const bool extrapolate = run.Options.Extrapolation != mp::ExtrapolationMode::None;
  if (haveCover && !extrapolate)
  {
    targetMesh.ReleaseGeometry();
  }
  LeafSolutions solutions;
  if (TestFault("collective", run.Processes))
  {
    throw std::runtime_error(TestFaultText("collective"));
  }
  result.Outcome = ApplyOperators(ctx, kept, plan, ops, hooks, halo, solutions);
  if (result.Outcome.Ok())
  {
    DivideByDensity(ctx, ops, hooks, solutions);
    result.Outcome = ExtrapolateLeaf(ctx, kept, ops, hooks, solutions);
  }
  // After the collective steps that follow the solves, so that the other
  // processes reach the Solved round as this one does.
  if (result.Outcome.Ok() && TestFault("solve", run.Processes))
  {
    result.Outcome =
      Verdict::Fail("The projection failed: the solves failed: " + TestFaultText("solve") + ".");
  }
  result.Outcome =
    result.Outcome.Ok() ? agreement.At(LeafAgreement::Solved) : agreement.End(result.Outcome);
  if (!result.Outcome.Ok())
  {
    return result;
  }
  if (haveCover && extrapolate)
  {
    targetMesh.ReleaseGeometry();
  }
  kept.Store(plan, ops, solutions, targetMesh, run.Source.Mesh);
  // On several processes the outputs are written in step (sums over them):
  // a stop now (after the last agreement) waits for the next leaf's.
  if (!ctx.Bar(0.95) && run.Processes.Whole())
  {
    result.Outcome = Verdict::Stop();
    return result;
  }
  run.Clock.Lap();
  if (!haveCover)
  {
    cover = PointCover(targetMesh, ops);
  }
  WriteLeafOutputs(ctx, job.Output, ops, solutions, weights, cover, hooks[0]);
  if (run.Options.OutputIntersections)
  {
    result.Pieces = LeafPieces(ctx, ops);
  }
  result.Stats.Output += run.Clock.Lap();
  return result;
}
} // namespace mpvtk
