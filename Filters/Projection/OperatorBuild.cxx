// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/OperatorBuild.h"

#include "Projection/Agreement.h"
#include "Projection/Messages.h"
#include "Projection/OperatorCache.h"
#include "Projection/Settings.h"
#include "Projection/SourceSide.h"
#include "Adapter/SimplexMesh.h"
#include "Adapter/SourceLocator.h"
#include "Adapter/Threads.h"

#include "Mesh/CellNeighbors.h"
#include "Search/ParallelSearch.h"

#include <algorithm>

namespace mpvtk
{
const mp::MortarOperator* OperatorSet::First() const
{
  for (const mp::MortarOperator* op : this->Operators)
  {
    if (op)
    {
      return op;
    }
  }
  return nullptr;
}

bool OperatorSet::BuiltAny() const
{
  return std::any_of(std::begin(this->Fresh), std::end(this->Fresh),
    [](const std::unique_ptr<mp::MortarOperator>& op) { return op != nullptr; });
}

namespace
{
/// The options every operator of the leaf shares.
mp::OperatorOptions BaseOptions(const LeafContext& ctx)
{
  mp::OperatorOptions options;
  options.KeepPieces = ctx.Options.OutputIntersections;
  options.Method = ctx.Options.SearchMethod;
  // One range of target cells per thread of the filter's vtkSMPTools scope.
  options.Runner = mpvtk::SMPTaskRunner();
  return options;
}

/// Neighbours and the Source locator, once, before the first operator is built.
class LeafSearch
{
public:
  LeafSearch(LeafContext& ctx, mp::SearchMethod method)
    : Ctx(ctx)
    , Method(method)
  {}
  void Prepare();

private:
  void WarnMisoriented();
  LeafContext& Ctx;
  mp::SearchMethod Method;
  bool Ready = false;
};

void LeafSearch::Prepare()
{
  LeafContext& ctx = this->Ctx;
  SourceSide& source = ctx.Source;
  SimplexMesh& sourceMesh = source.Mesh;
  if (!this->Ready && mp::SearchNeedsNeighbors(this->Method))
  {
    // Neighbours and the seed locator (bins of the boundary cells). (M_tt's
    // pattern builds the target's cells around its points again once the
    // search is done: kept, they would take room during the search.)
    ctx.Target.BuildNeighbors();
    if (!source.SearchReady && !sourceMesh.View().Neighbors)
    {
      sourceMesh.BuildNeighbors(); // (unless the cell reconstruction built them)
    }
    ctx.Stats.Neighbors += ctx.Clock.Lap();
    if (ctx.Target.NonManifoldFaces() || (!source.SearchReady && sourceMesh.NonManifoldFaces()))
    {
      ctx.Say.Warn("Faces shared by more than two cells (" + ctx.Role + ": " +
        std::to_string(ctx.Target.NonManifoldFaces()) +
        ", Source: " + std::to_string(sourceMesh.NonManifoldFaces()) +
        ") are treated as boundaries; results stay correct but the search is slower.");
    }
    this->WarnMisoriented();
    if (!source.SearchReady)
    {
      // A Source without cells has nothing to locate: the kernel's own
      // (empty) locator answers the front's questions then.
      source.Locator.reset(sourceMesh.View().NumberOfCells > 0
          ? static_cast<mp::CandidateLocator*>(new mpvtk::SourceLocator(sourceMesh))
          : new mp::BoxGridLocator(sourceMesh.View()));
      source.SearchReady = true;
      ctx.Stats.Locator += ctx.Clock.Lap();
    }
  }
  if (!this->Ready && ctx.Shape.Trace && !sourceMesh.View().Neighbors)
  {
    // Traces tell the Source's boundary faces by their neighbours, in the
    // brute force too (a surface on the boundary is covered from inside).
    sourceMesh.BuildNeighbors();
    ctx.Stats.Neighbors += ctx.Clock.Lap();
  }
  this->Ready = true;
}

/// Facets meet by oriented normals: says so when a mesh's are not consistent.
void LeafSearch::WarnMisoriented()
{
  LeafContext& ctx = this->Ctx;
  if (ctx.Shape.Trace || !ctx.Target.View().IsSurfaceMesh() ||
    ctx.Options.NormalOrientation == AnyOrientation)
  {
    return;
  }
  const mp::Index target = mp::MisorientedEdges(ctx.Target.View());
  const mp::Index source =
    ctx.Source.SearchReady ? 0 : mp::MisorientedEdges(ctx.Source.Mesh.View());
  if (target > 0 || source > 0)
  {
    ctx.Say.WarnOnce("orientation/" + ctx.Role,
      "Surfaces not consistently oriented (" + ctx.Role + ": " + std::to_string(target) +
        ", Source: " + std::to_string(source) +
        " edges whose two facets are oriented against each other): facets meet only with normals "
        "within MaximumNormalAngle as NormalOrientation says, so facets facing the other way may "
        "meet nothing. Orient the meshes consistently (Generate Surface Normals with Consistency "
        "on), or set NormalOrientation to Any.");
  }
}

const GatheredFields& FieldsOf(const LeafContext& ctx, Transfer t)
{
  return ctx.Source.Fields[SourceAssociation(t)];
}

/// Builds, from one search, every operator of the plan that is not kept.
Verdict BuildMissing(LeafContext& ctx, KeptLeaf& kept, const OperatorPlan& plan,
  LeafAgreement& agreement, LeafSearch& search, OperatorSet& ops)
{
  std::vector<mp::MortarOperator*> making;
  std::vector<mp::OperatorOptions> makingOptions;
  const ProgressShare bar = ctx.Bar;
  for (Transfer t : AllTransfers)
  {
    if (!plan.Used[t])
    {
      continue;
    }
    if (kept.Operator(t))
    {
      ops.Operators[t] = kept.Operator(t);
      continue;
    }
    const GatheredFields& g = FieldsOf(ctx, t);
    mp::OperatorOptions options = BaseOptions(ctx);
    options.TargetSpace = TargetSpaceOf(t);
    options.SourceSpace = SourceSpaceOf(t, ctx.Options.ReconstructsCellData());
    options.Fields = plan.Assembled || g.Components == 0 ? nullptr : g.Functions().data();
    options.FieldComponents = plan.Assembled ? 0 : g.Components;
    options.Progress = [bar](double f) { return bar(0.1 + 0.8 * f); };
    options.DeferTargetMass = true; // M_tt once the Source's arrays are gone
    ops.Fresh[t].reset(new mp::MortarOperator);
    making.push_back(ops.Fresh[t].get());
    makingOptions.push_back(options);
  }
  if (making.empty())
  {
    return Verdict();
  }
  search.Prepare();
  if (!bar(0.1))
  {
    return agreement.End(Verdict::Stop());
  }
  bool ok = false;
  ctx.Bar.Bar->Watch([&]() {
    ok = mp::MortarOperator::BuildTogether(
      making, makingOptions, ctx.Target.View(), ctx.Source.Mesh.View(), ctx.Source.Locator.get());
  });
  if (!ok)
  {
    const std::string& error = making[0]->GetError();
    return agreement.End(
      error == "stopped" ? Verdict::Stop() : Verdict::Fail("Projection failed: " + error));
  }
  for (Transfer t : AllTransfers)
  {
    if (ops.Fresh[t])
    {
      ops.Operators[t] = ops.Fresh[t].get();
      ctx.Stats.Search += ops.Fresh[t]->GetTimings().Search;
      ctx.Stats.Assembly += ops.Fresh[t]->GetTimings().Assembly;
      ++ctx.Stats.OperatorsBuilt;
    }
  }
  ctx.Clock.Lap();
  return Verdict();
}

/// Quadrature points of second-order cells whose inverse map failed, the
/// most any operator built here met (each meets the same pieces' points).
void WarnUnconverged(LeafContext& ctx, const OperatorSet& ops)
{
  vtkIdType counts[2] = { 0, 0 };
  auto count = [&counts](const mp::MortarOperator* op) {
    counts[0] = std::max<vtkIdType>(counts[0], op->GetNumberOfUnconvergedTargetPoints());
    counts[1] = std::max<vtkIdType>(counts[1], op->GetNumberOfUnconvergedSourcePoints());
  };
  for (const std::unique_ptr<mp::MortarOperator>& op : ops.Fresh)
  {
    if (op)
    {
      count(op.get());
    }
  }
  for (const auto& group : ops.GroupFresh)
  {
    count(group.second.get());
  }
  if (counts[0] > 0 || counts[1] > 0)
  {
    ctx.Say.Warn("The inverse map of second-order cells failed at " + std::to_string(counts[0]) +
      " quadrature points of " + ctx.Role + " and " + std::to_string(counts[1]) +
      " of Source (Newton did not converge, or the point lies past a fold of a strongly curved or "
      "inverted cell): their functions were taken at the point's place on the cell's straight "
      "split. Check those cells' mid nodes.");
  }
}

/// The search's counts, and what it found wrong with the meshes.
void ReportSearch(LeafContext& ctx, const OperatorSet& ops)
{
  const mp::MortarOperator* first = ops.First();
  const mp::SearchStatistics& stats = first->GetStatistics();
  ctx.Stats.Intersections += stats.Pieces;
  ctx.Stats.IntersectionTests += stats.IntersectionTests;
  ctx.Stats.LocatorQueries += stats.LocatorQueries;
  ctx.Stats.CoveredMeasure += first->GetCoveredMeasure();
  if (!ops.BuiltAny())
  {
    return;
  }
  const bool trace = ctx.Shape.Trace;
  const int d = ctx.Target.Dimension();
  // Degenerate simplices (the kernel's) and split cells that gave none.
  const vtkIdType flatTarget = stats.DegenerateTargetCells + ctx.Target.FlatCells();
  const vtkIdType flatSource = stats.DegenerateSourceCells + ctx.Source.Mesh.FlatCells();
  if (flatTarget > 0 || flatSource > 0)
  {
    ctx.Say.Warn(std::string("Cells of zero ") +
      (trace       ? "measure (length, area or volume)"
          : d == 1 ? "length"
                   : (d == 2 ? "area" : "volume")) +
      " (" + ctx.Role + ": " + std::to_string(flatTarget) + ", Source: " +
      std::to_string(flatSource) + ") were ignored: they carry no part of the integrals.");
  }
  if (ctx.Target.View().NumberOfCells > 0 && ctx.Source.Mesh.View().NumberOfCells > 0 &&
    first->GetCoveredMeasure() == 0)
  {
    ctx.Say.Warn("Source and " + ctx.Role + " do not overlap: every projected value is invalid." +
      (trace ? " A surface or curve takes values only where it lies inside the Source."
          : ctx.Target.View().IsSurfaceMesh()
          ? " Surfaces meet only within SurfaceReach and with normals within MaximumNormalAngle, "
            "compared as NormalOrientation says: two surfaces facing each other (contact, "
            "fluid-structure) need Opposite, meshes of unknown orientation Any."
          : ""));
  }
  WarnUnconverged(ctx, ops);
  if (first->GetNumberOfOvercoveredCells() > 0)
  {
    const bool composite = ctx.Source.Composite;
    ctx.Say.Warn(std::to_string(first->GetNumberOfOvercoveredCells()) + " " + ctx.Role +
      " cells are covered more than once: Source cells overlap each other " +
      (composite ? "(a composite Source is one mesh of all its blocks: do its blocks overlap?)"
                 : "(folded, inverted among their neighbours, or duplicated)") +
      ". The result is not a projection of one field there." +
      (trace && composite
          ? " A surface or curve lying on the faces between two blocks takes both blocks' cells "
            "there (each block's faces are its boundary): merge the blocks with their points "
            "first (Merge Blocks)."
          : ""));
  }
}

/// The operator of one NaN group for transfer t: kept, or built now.
Verdict GroupOperator(LeafContext& ctx, const KeptLeaf& kept, const OperatorPlan& plan, Transfer t,
  const NaNGroup& group, LeafAgreement& agreement, LeafSearch& search, OperatorSet& ops,
  const mp::MortarOperator*& op)
{
  const GroupKey key(static_cast<int>(t), group.Print);
  op = kept.Group(t, group.Print);
  if (op)
  {
    return Verdict();
  }
  search.Prepare();
  const ProgressShare bar = ctx.Bar;
  mp::OperatorOptions options = BaseOptions(ctx);
  options.TargetSpace = TargetSpaceOf(t);
  options.SourceSpace = SourceSpaceOf(t, ctx.Options.ReconstructsCellData());
  options.KeepPieces = false;
  options.ExcludedSourceCells = group.Excluded.data();
  options.Fields = plan.Assembled ? nullptr : group.Functions().data();
  options.FieldComponents = plan.Assembled ? 0 : group.Components;
  options.Progress = [bar](double) { return bar(0.9); };
  options.DeferTargetMass = true; // (completed with the others)
  std::unique_ptr<mp::MortarOperator> made(new mp::MortarOperator);
  if (!made->Build(ctx.Target.View(), ctx.Source.Mesh.View(), ctx.Source.Locator.get(), options))
  {
    const std::string& error = made->GetError();
    return agreement.End(
      error == "stopped" ? Verdict::Stop() : Verdict::Fail("Projection failed: " + error));
  }
  ctx.Stats.Search += made->GetTimings().Search;
  ctx.Stats.Assembly += made->GetTimings().Assembly;
  ++ctx.Stats.OperatorsBuilt;
  op = made.get();
  ops.Deferred.push_back(made.get());
  ops.GroupFresh.emplace_back(
    key, std::move(made)); // (kept or not at the leaf's end: KeptLeaf::Store)
  return Verdict();
}

/// Each array's operator: its NaN group's, or the transfer's; unused kept groups dropped.
Verdict BuildGroups(LeafContext& ctx, KeptLeaf& kept, const OperatorPlan& plan,
  LeafAgreement& agreement, LeafSearch& search, OperatorSet& ops)
{
  std::vector<GroupKey> used;
  for (Transfer t : AllTransfers)
  {
    const GatheredFields& g = FieldsOf(ctx, t);
    if (!ops.Operators[t] || g.Components == 0)
    {
      continue;
    }
    ops.ByArray[t].assign(g.Arrays.size(), ops.Operators[t]);
    for (const NaNGroup& group : g.Groups)
    {
      used.emplace_back(static_cast<int>(t), group.Print);
      const mp::MortarOperator* op = nullptr;
      const Verdict made = GroupOperator(ctx, kept, plan, t, group, agreement, search, ops, op);
      if (!made.Ok())
      {
        return made;
      }
      for (int a : group.Arrays)
      {
        ops.ByArray[t][a] = op;
      }
    }
  }
  kept.KeepOnlyGroups(used);
  return Verdict();
}
} // namespace

Verdict PlanOperators(
  LeafContext& ctx, KeptLeaf& kept, LeafAgreement& agreement, OperatorPlan& plan)
{
  const Settings& s = ctx.Options;
  plan.Cache =
    kept.LookUp(ctx.Target, ctx.Source.Print, s, ctx.Shape.Trace, ctx.Source.TimeVarying);
  // Kept operators are reused only where every process can keep its own.
  const Verdict elsewhere = agreement.At(LeafAgreement::Build, &plan.Cache.SameGeometry);
  if (!elsewhere.Ok())
  {
    return agreement.End(elsewhere, true);
  }
  kept.Begin(plan.Cache);
  const bool points = ctx.Source.Fields[PointArrays].Any();
  const bool cells = ctx.Source.Fields[CellArrays].Any();
  plan.Used[PointsToPoints] = points && (s.PointDataTarget & ToPointsBit);
  plan.Used[PointsToCells] = points && (s.PointDataTarget & ToCellsBit);
  plan.Used[CellsToCells] = cells && (s.CellDataTarget & ToCellsBit);
  plan.Used[CellsToPoints] = cells && (s.CellDataTarget & ToPointsBit);
  // The operator that gives the mask and coverage when nothing is projected.
  if (std::none_of(std::begin(plan.Used), std::end(plan.Used), [](bool u) { return u; }))
  {
    plan.Used[PointsToPoints] = true;
  }
  // (Labels are weighed by M_ts's rows: Labels.h.)
  const bool labels =
    !ctx.Source.Fields[PointArrays].Labels.empty() || !ctx.Source.Fields[CellArrays].Labels.empty();
  plan.Assembled = s.PreserveBounds || plan.Cache.Assembles() || labels;
  // A signed form's lumped coefficients are clipped to M_ts's rows' bounds
  // on every process (BernsteinForm.h): M_ts kept.
  plan.Assembled = plan.Assembled || (s.Lumped && ctx.Shape.Signed);
  return Verdict();
}

Verdict BuildOperators(LeafContext& ctx, KeptLeaf& kept, const OperatorPlan& plan,
  LeafAgreement& agreement, OperatorSet& ops)
{
  LeafSearch search(ctx, BaseOptions(ctx).Method);
  Verdict built = BuildMissing(ctx, kept, plan, agreement, search, ops);
  if (!built.Ok())
  {
    return built;
  }
  ReportSearch(ctx, ops);
  built = BuildGroups(ctx, kept, plan, agreement, search, ops);
  if (!built.Ok())
  {
    return built;
  }
  for (Transfer t : AllTransfers)
  {
    if (ops.Fresh[t])
    {
      ops.Deferred.push_back(ops.Fresh[t].get());
    }
  }
  return Verdict();
}
} // namespace mpvtk
