// SPDX-License-Identifier: BSD-3-Clause
// MortarOperator (MortarOperator.h), the build: the operators' options
// checked and reset, then one search whose pieces go to every operator's
// session (MortarSession.h), each summing them as its own Build would.
#include "Transfer/MortarOperator.h"

#include "Geometry/Intersectors.h"
#include "Search/ParallelSearch.h"
#include "Transfer/MortarSession.h"
#include "Transfer/NodalSession.h"
#include "Transfer/StageClock.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace mp
{
bool MortarOperator::BuildTogether(const std::vector<MortarOperator*>& operators,
  const std::vector<OperatorOptions>& options, const MeshView& target, const MeshView& source,
  CandidateLocator* locator)
{
  if (operators.empty() || options.size() != operators.size())
  {
    return false;
  }
  bool ok = true;
  unsigned pairs = 0; // the pairs of spaces taken
  for (size_t i = 0; i < operators.size(); ++i)
  {
    MortarOperator& op = *operators[i];
    op.Options = options[i];
    op.Options.Runner.Tasks = std::max(1, options[i].Runner.Tasks);
    op.TargetMass = CsrMatrix();
    op.Masses = CellMasses();
    op.MassPending = false;
    op.MixedMass = CsrMatrix();
    UninitializedLargeVector<double>().swap(op.Rhs);
    op.Solver.reset();
    op.Statistics = SearchStatistics();
    op.Timings = OperatorTimings();
    op.Pieces = IntersectionPieces();
    op.Error.clear();
    op.Valid.clear();
    op.NumberOfValid = 0;
    op.CoveredFraction.assign(static_cast<size_t>(target.NumberOfCells), 0.0);
    op.SourceCovered.clear();
    op.SourceFunctionCovered.clear();
    op.CoveredMeasure = 0;
    op.OvercoveredCells = 0;
    op.UnconvergedPoints[0] = op.UnconvergedPoints[1] = 0;
    op.SourceFunctions = 0;
    op.NodalPath = false;
    op.NodalTarget = false;
    op.Bernstein = BernsteinForm();
    op.NodalMassBlocks.clear();
    op.Pieces.Dimension = target.CellDimension;
    const unsigned pair = 1u << (3 * (op.Options.TargetSpace == SpaceType::P1 ? 1 : 0) +
                            static_cast<int>(op.Options.SourceSpace));
    if (pairs & pair)
    {
      op.Error = "operators built together need pairs of spaces of their own";
      ok = false;
    }
    pairs |= pair;
    if (i > 0 &&
      (op.Options.Method != options[0].Method ||
        op.Options.ExcludedSourceCells != options[0].ExcludedSourceCells))
    {
      op.Error = "operators built together share their search: the same method and excluded cells";
      ok = false;
    }
    ok = ok && op.Check(target, source, locator);
  }
  if (!ok)
  {
    // Every operator says why (the first reason found).
    std::string why;
    for (MortarOperator* op : operators)
    {
      why = why.empty() ? op->Error : why;
    }
    for (MortarOperator* op : operators)
    {
      op->Error = why;
    }
    return false;
  }
  WithIntersectorOf(target, source, [&](auto* tag) {
    AssembleTogether<std::remove_pointer_t<decltype(tag)>>(operators, target, source, locator);
  });
  bool built = true;
  for (MortarOperator* op : operators)
  {
    if (!op->Error.empty())
    {
      op->TargetMass = CsrMatrix();
      op->Masses = CellMasses();
      op->MixedMass = CsrMatrix();
      op->Valid.clear();
      built = false;
      continue;
    }
    op->MassPending = true;
    if (!op->Options.DeferTargetMass)
    {
      op->CompleteTargetMass(target);
    }
  }
  return built;
}

namespace
{
/**
 * The visitor of one search that several operators share: each piece to
 * each session's assembler of the task (at most one per pair of spaces;
 * the others null).
 */
template <class... A>
struct SharedVisitor
{
  std::tuple<A*...> Each;
  template <class Cell, class SourceCell, class Piece>
  void operator()(const Cell& t, const SourceCell& s, const Piece& piece)
  {
    std::apply([&](auto*... assembler) { ((assembler ? (*assembler)(t, s, piece) : void()), ...); },
      this->Each);
  }
};

/**
 * SharedVisitor's pieces also to the tasks' assemblers of the operators in
 * the cells' own space (NodalSession.h), after the others.
 */
template <class Q, class... A>
struct SharedVisitorWithNodal
{
  SharedVisitor<A...> Linear;
  std::vector<Q*> Nodal;
  template <class Cell, class SourceCell, class Piece>
  void operator()(const Cell& t, const SourceCell& s, const Piece& piece)
  {
    this->Linear(t, s, piece);
    for (Q* q : this->Nodal)
    {
      (*q)(t, s, piece);
    }
  }
};

/// The session of one pair of spaces, made when an operator asks for it.
template <class S>
struct SessionSlot
{
  using Assembler = typename S::Assembler;
  std::unique_ptr<S> Session;
  Assembler* AssemblerOf(int task) const
  {
    return this->Session ? &this->Session->Assemblers[task] : nullptr;
  }
};
} // namespace

template <class Intersector>
void MortarOperator::AssembleTogether(const std::vector<MortarOperator*>& operators,
  const MeshView& target, const MeshView& source, CandidateLocator* locator)
{
  constexpr int D = Intersector::Dimension;
  using SourceP1 = typename SourceP1Of<Intersector>::type;
  using SourceDP1 = DiscontinuousP1Space<SourceP1>;
  using P1 = P1Space<D>;
  using P0 = P0Space<D>;
  // The sessions by pair of spaces, target <- source: P1 <- P1, P1 <- P0,
  // P1 <- DP1, P0 <- P1, P0 <- P0, P0 <- DP1.
  std::tuple<SessionSlot<Session<Intersector, P1, SourceP1>>,
    SessionSlot<Session<Intersector, P1, P0>>, SessionSlot<Session<Intersector, P1, SourceDP1>>,
    SessionSlot<Session<Intersector, P0, SourceP1>>, SessionSlot<Session<Intersector, P0, P0>>,
    SessionSlot<Session<Intersector, P0, SourceDP1>>>
    slots;
  // Calls f on each session made.
  auto forEachSession = [&](auto&& f) {
    std::apply([&](auto&... slot) { ((slot.Session ? f(*slot.Session) : void()), ...); }, slots);
  };
  MortarOperator& lead = *operators[0];
  const TaskRunner& runner = lead.Options.Runner;
  // The target cells in ranges, one per task, each with its own front,
  // locator and sums.
  const int tasks = runner.TasksFor(target.NumberOfCells, 64);
  // The cover of the source cells is the same for every operator (the
  // same pieces, the same excluded cells): the lead's session sums it
  // (per-task arrays of source cells: once, not per operator).
  // Operators whose point data lives in the cells' own space take the
  // quadrature path (NodalSession.h); the others' sessions are untouched.
  using Nodal = NodalSession<Intersector>;
  std::vector<std::unique_ptr<Nodal>> nodal;
  for (MortarOperator* op : operators)
  {
    const bool cover = op == &lead;
    if (UsesNodalSpace(op->Options, target, source))
    {
      nodal.emplace_back(new Nodal);
      nodal.back()->Prepare(*op, target, source, tasks, cover);
      continue;
    }
    std::apply(
      [&](auto&... slot) {
        auto make = [&](auto& s) {
          using S = typename std::remove_reference_t<decltype(s)>::element_type;
          using Target = typename S::Assembler::TargetSpaceType;
          using Source = typename S::Assembler::SourceSpaceType;
          if (op->Options.TargetSpace == Target::Type && op->Options.SourceSpace == Source::Type)
          {
            s.reset(new S);
            s->Prepare(*op, target, source, tasks, cover);
          }
        };
        (make(slot.Session), ...);
      },
      slots);
  }
  auto start = std::chrono::steady_clock::now();
  SearchStatistics statistics;
  auto search = [&](auto& visitors) {
    return SearchInRanges<Intersector>(lead.Options.Method, target, source, locator, runner,
      visitors, statistics, lead.Options.Progress);
  };
  bool done = false;
  if (!nodal.empty())
  {
    auto visitorsOf = [&](auto&... slot) {
      using Visitor = SharedVisitorWithNodal<typename Nodal::Assembler,
        typename std::remove_reference_t<decltype(slot)>::Assembler...>;
      std::vector<Visitor> visitors(static_cast<size_t>(tasks));
      for (int k = 0; k < tasks; ++k)
      {
        visitors[k].Linear.Each = std::make_tuple(slot.AssemblerOf(k)...);
        for (auto& session : nodal)
        {
          visitors[k].Nodal.push_back(&session->Assemblers[k]);
        }
      }
      return visitors;
    };
    auto visitors = std::apply(visitorsOf, slots);
    done = search(visitors);
  }
  else if (operators.size() == 1)
  {
    // One operator: its assemblers visit the pieces themselves (no
    // dispatch per piece, which costs a little on every piece).
    forEachSession([&](auto& session) { done = search(session.Assemblers); });
  }
  else
  {
    auto visitorsOf = [&](auto&... slot) {
      using Visitor = SharedVisitor<typename std::remove_reference_t<decltype(slot)>::Assembler...>;
      std::vector<Visitor> visitors(static_cast<size_t>(tasks));
      for (int k = 0; k < tasks; ++k)
      {
        visitors[k].Each = std::make_tuple(slot.AssemblerOf(k)...);
      }
      return visitors;
    };
    auto visitors = std::apply(visitorsOf, slots);
    done = search(visitors);
  }
  const double seconds = SecondsSince(start);
  for (MortarOperator* op : operators)
  {
    op->Statistics = statistics;
    op->Timings.Search = op == &lead ? seconds : 0.0; // the search once, on the first
    if (!done)
    {
      op->Error = "stopped";
    }
  }
  if (!done)
  {
    return;
  }
  forEachSession([&](auto& session) { session.Finish(source); });
  for (auto& session : nodal)
  {
    session->Finish(source);
  }
  for (MortarOperator* op : operators)
  {
    if (op != &lead)
    {
      op->SourceCovered = lead.SourceCovered;
    }
  }
}
} // namespace mp
