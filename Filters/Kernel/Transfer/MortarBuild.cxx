// SPDX-License-Identifier: BSD-3-Clause
// MortarOperator (MortarOperator.h), the build: the operators' options
// checked and reset, then one search whose pieces go to every operator's
// session (MortarSession.h), each summing them as its own Build would.
#include "Transfer/MortarOperator.h"

#include "Geometry/Intersectors.h"
#include "Search/ParallelSearch.h"
#include "Transfer/MortarSession.h"
#include "Transfer/StageClock.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
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
    op.CoveredMeasure = 0;
    op.OvercoveredCells = 0;
    op.SourceFunctions = 0;
    op.Pieces.Dimension = target.CellDimension;
    const unsigned pair = 1u << ((op.Options.TargetSpace == SpaceType::P1 ? 2 : 0) +
      (op.Options.SourceSpace == SpaceType::P1 ? 1 : 0));
    if (pairs & pair)
    {
      op.Error = "operators built together need pairs of spaces of their own";
      ok = false;
    }
    pairs |= pair;
    if (i > 0 && (op.Options.Method != options[0].Method ||
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
template <class A, class B, class C, class E>
struct SharedVisitor
{
  A* First = nullptr;
  B* Second = nullptr;
  C* Third = nullptr;
  E* Fourth = nullptr;
  template <class Cell, class SourceCell, class Piece>
  void operator()(const Cell& t, const SourceCell& s, const Piece& piece)
  {
    if (this->First)
    {
      (*this->First)(t, s, piece);
    }
    if (this->Second)
    {
      (*this->Second)(t, s, piece);
    }
    if (this->Third)
    {
      (*this->Third)(t, s, piece);
    }
    if (this->Fourth)
    {
      (*this->Fourth)(t, s, piece);
    }
  }
};
} // namespace

template <class Intersector>
void MortarOperator::AssembleTogether(const std::vector<MortarOperator*>& operators,
  const MeshView& target, const MeshView& source, CandidateLocator* locator)
{
  constexpr int D = Intersector::Dimension;
  using SourceP1 = typename SourceP1Of<Intersector>::type;
  using P1 = P1Space<D>;
  using P0 = P0Space<D>;
  // The sessions by pair of spaces: P1 <- P1, P1 <- P0, P0 <- P1, P0 <- P0.
  std::unique_ptr<Session<Intersector, P1, SourceP1>> s11;
  std::unique_ptr<Session<Intersector, P1, P0>> s10;
  std::unique_ptr<Session<Intersector, P0, SourceP1>> s01;
  std::unique_ptr<Session<Intersector, P0, P0>> s00;
  MortarOperator& lead = *operators[0];
  const TaskRunner& runner = lead.Options.Runner;
  // The target cells in ranges, one per task, each with its own front,
  // locator and sums.
  const int tasks = runner.TasksFor(target.NumberOfCells, 64);
  // The cover of the source cells is the same for every operator (the
  // same pieces, the same excluded cells): the lead's session sums it
  // (per-task arrays of source cells: once, not per operator).
  for (MortarOperator* op : operators)
  {
    const bool p1t = op->Options.TargetSpace == SpaceType::P1;
    const bool p1s = op->Options.SourceSpace == SpaceType::P1;
    const bool cover = op == &lead;
    if (p1t && p1s)
    {
      s11.reset(new Session<Intersector, P1, SourceP1>);
      s11->Prepare(*op, target, source, tasks, cover);
    }
    else if (p1t)
    {
      s10.reset(new Session<Intersector, P1, P0>);
      s10->Prepare(*op, target, source, tasks, cover);
    }
    else if (p1s)
    {
      s01.reset(new Session<Intersector, P0, SourceP1>);
      s01->Prepare(*op, target, source, tasks, cover);
    }
    else
    {
      s00.reset(new Session<Intersector, P0, P0>);
      s00->Prepare(*op, target, source, tasks, cover);
    }
  }
  // Calls f on each session made.
  auto forEachSession = [&](auto&& f) {
    if (s11)
    {
      f(*s11);
    }
    if (s10)
    {
      f(*s10);
    }
    if (s01)
    {
      f(*s01);
    }
    if (s00)
    {
      f(*s00);
    }
  };
  auto start = std::chrono::steady_clock::now();
  SearchStatistics statistics;
  auto search = [&](auto& visitors) {
    return SearchInRanges<Intersector>(lead.Options.Method, target, source, locator, runner,
      visitors, statistics, lead.Options.Progress);
  };
  bool done = false;
  if (operators.size() == 1)
  {
    // One operator: its assemblers visit the pieces themselves (no
    // dispatch per piece, which costs a little on every piece).
    forEachSession([&](auto& session) { done = search(session.Assemblers); });
  }
  else
  {
    using Visitor = SharedVisitor<typename Session<Intersector, P1, SourceP1>::Assembler,
      typename Session<Intersector, P1, P0>::Assembler,
      typename Session<Intersector, P0, SourceP1>::Assembler,
      typename Session<Intersector, P0, P0>::Assembler>;
    std::vector<Visitor> visitors(static_cast<size_t>(tasks));
    for (int k = 0; k < tasks; ++k)
    {
      visitors[k].First = s11 ? &s11->Assemblers[k] : nullptr;
      visitors[k].Second = s10 ? &s10->Assemblers[k] : nullptr;
      visitors[k].Third = s01 ? &s01->Assemblers[k] : nullptr;
      visitors[k].Fourth = s00 ? &s00->Assemblers[k] : nullptr;
    }
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
  for (MortarOperator* op : operators)
  {
    if (op != &lead)
    {
      op->SourceCovered = lead.SourceCovered;
    }
  }
}
} // namespace mp
