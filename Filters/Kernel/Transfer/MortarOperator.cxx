// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/MortarOperator.h"

#include "Geometry/Measures.h"

#include "Geometry/Intersectors.h"
#include "Search/ParallelSearch.h"
#include "Transfer/MassMatrix.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/MortarAssembler.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <limits>

namespace mp
{
namespace
{
double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// How many of ids[0..n) lie outside [0, bound), counted in `runner`'s tasks.
template <class Id>
Index CountOutside(const Id* ids, Index n, Index bound, const TaskRunner& runner)
{
  return runner.ForRanges(n, [=](Index begin, Index end) {
    Index outside = 0;
    for (Index i = begin; i < end; ++i)
    {
      // (A negative id is a huge unsigned one.)
      outside += static_cast<std::uint64_t>(ids[i]) >= static_cast<std::uint64_t>(bound);
    }
    return outside;
  }, Index(1) << 16);
}

std::string CheckIds(const MeshView& mesh, const char* name, const TaskRunner& runner)
{
  const Index uses = mesh.NumberOfCells * mesh.CornersPerCell();
  if ((mesh.Connectivity32 ? CountOutside(mesh.Connectivity32, uses, mesh.NumberOfPoints, runner)
                           : CountOutside(mesh.Connectivity, uses, mesh.NumberOfPoints, runner)) > 0)
  {
    return std::string(name) + ": a cell refers to a point that does not exist";
  }
  if (mesh.Parent && CountOutside(mesh.Parent, mesh.NumberOfCells, mesh.NumberOfParents, runner) > 0)
  {
    return std::string(name) + ": a cell's parent does not exist";
  }
  return std::string();
}
} // namespace

MortarOperator::MortarOperator() = default;
MortarOperator::~MortarOperator() = default;

bool MortarOperator::Build(const MeshView& target, const MeshView& source,
  CandidateLocator* locator, const OperatorOptions& options)
{
  return BuildTogether({ this }, { options }, target, source, locator);
}

bool MortarOperator::Check(
  const MeshView& target, const MeshView& source, CandidateLocator* locator)
{
  const OperatorOptions& options = this->Options;
  for (const auto& mesh : { std::make_pair(&target, "Input (target)"), std::make_pair(&source, "Source") })
  {
    const MeshView& m = *mesh.first;
    if (!(((m.CellDimension == 2 || m.CellDimension == 3) && m.IsVolumeMesh()) ||
          m.IsSurfaceMesh() || m.IsCurveMesh()))
    {
      this->Error = std::string(mesh.second) +
        ": only segments of curves (in the plane or in space), triangles in the plane (2D), "
        "triangles of surfaces in 3D and tetrahedra in space (3D) have a geometry";
      return false;
    }
    this->Error = CheckSearchMesh(m, mesh.second, options.Method);
    if (this->Error.empty())
    {
      this->Error = CheckIds(m, mesh.second, options.Runner);
    }
    if (!this->Error.empty())
    {
      return false;
    }
  }
  if (SearchNeedsNeighbors(options.Method) && !locator)
  {
    this->Error = "the advancing front needs a locator over the source cells";
    return false;
  }
  const bool trace = IsTracePair(target, source);
  if (target.CellDimension == 2 && source.CellDimension == 2 &&
    target.SpaceDimension != source.SpaceDimension)
  {
    this->Error = "Input and Source are triangles seen in different spaces (" +
      std::to_string(target.SpaceDimension) + "D and " + std::to_string(source.SpaceDimension) +
      "D): a surface in 3D is matched with a surface in 3D";
    return false;
  }
  if (target.CellDimension != source.CellDimension && !trace)
  {
    this->Error = "Input and Source have different dimensions (" +
      std::to_string(target.CellDimension) + "D and " + std::to_string(source.CellDimension) +
      "D); of different dimensions, only a surface in tetrahedra or a curve in triangles (in "
      "their plane) or tetrahedra (a trace) can be projected";
    return false;
  }
  const Index rows = SpaceSize(options.TargetSpace, target);
  const Index columns = SpaceSize(options.SourceSpace, source);
  this->SourceFunctions = columns;
  if (options.FieldComponents < 0 || (options.FieldComponents > 0 && !options.Fields))
  {
    this->Error = "fields to project: a pointer and a number of components are needed";
    return false;
  }
  if (std::max(rows, columns) > std::numeric_limits<Column>::max())
  {
    this->Error = "a space of " + std::to_string(std::max(rows, columns)) +
      " functions; at most 2^31 - 1 are supported";
    return false;
  }
  return true;
}

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

void MortarOperator::CompleteTargetMass(const MeshView& target)
{
  if (!this->MassPending)
  {
    return;
  }
  this->MassPending = false;
  auto start = std::chrono::steady_clock::now();
  const TaskRunner& runner = this->Options.Runner;
  // The point cover (the largest covered fraction around each point) is
  // made with M_tt, from the parents' fractions: each cell's through its
  // parent (an array of fractions per kernel cell kept beside them for it
  // was 8 MiB more at the peak for a target of 10^6 cells).
  if (target.Parent)
  {
    // Split or renumbered cells: the covered fraction of each original cell
    // (here rather than right after the search: with DeferTargetMass the
    // Source's arrays are gone by now, and the two arrays of fractions take
    // no room from the search's).
    this->CoveredFraction = ParentFractions(target, this->CoveredFraction, runner);
  }
  CellValues coverFrom;
  if (this->CoveredFraction.size() >= static_cast<size_t>(target.Parents()))
  {
    coverFrom.Values = this->CoveredFraction.data();
    coverFrom.ByParent = target.Parent != nullptr;
  }
  AssembleTargetMass(this->Options.TargetSpace, target, &this->Masses, runner, this->TargetMass,
    coverFrom, &this->PointCover);
  this->Masses = CellMasses();
  // A function is valid when its support meets the source: its diagonal
  // entry of the covered mass matrix is positive. An invalid function's
  // whole row is zero (no piece touches its support); a 1 on the diagonal
  // decouples it.
  const Index rows = this->TargetMass.Rows;
  CsrMatrix& mass = this->TargetMass;
  this->Valid.resize(static_cast<size_t>(rows));
  this->RowSums.resize(static_cast<size_t>(rows));
  this->NumberOfValid += runner.ForRanges(rows, [&](Index begin, Index end) {
    Index valid = 0;
    for (Index i = begin; i < end; ++i)
    {
      double& diagonal = mass.Values[mass.Find(i, i)];
      const bool isValid = diagonal > 0.0;
      double sum = 0.0;
      if (isValid)
      {
        ++valid;
        for (Index p = mass.RowStart[i]; p < mass.RowStart[i + 1]; ++p)
        {
          sum += mass.Values[p];
        }
      }
      else
      {
        diagonal = 1.0;
      }
      this->Valid[i] = isValid ? 1 : 0;
      this->RowSums[i] = sum;
    }
    return valid;
  }, 16384);
  // (Its lumped start reads the valid rows' sums just made: an invalid
  // row's decoupling 1 is left out, but its right-hand side is 0.)
  this->Solver.reset(new BlockCG(this->TargetMass, runner, this->RowSums.data()));
  this->Timings.Assembly += Seconds(start);
}

/**
 * One operator's share of a search: what M_tt takes from each target cell
 * (assembled after the search), the marks of its target functions shared
 * by tasks, one assembler per task with its blocks,
 * pieces and source cover, and what follows the search. Several sessions
 * take the pieces of one search (MortarOperator::BuildTogether), each
 * summing them in the order a search of its own would.
 */
template <class Intersector, class TargetSpace, class SourceSpace>
struct MortarOperator::Session
{
  using Assembler = MortarAssembler<Intersector, TargetSpace, SourceSpace>;
  MortarOperator* Op = nullptr;
  UninitializedLargeVector<std::uint64_t> Shared; ///< per target function a bit (MortarAssembler::Shared)
  std::vector<Assembler> Assemblers;
  std::vector<MixedBlocks> Blocks;
  std::vector<IntersectionPieces> Pieces;
  std::vector<PartialMasses> Partial; ///< per task: M_tt's blocks of cells covered in part
  // How much of each source cell the pieces cover: per task, summed after.
  std::vector<LargeVector<double>> Met;

  /// `cover`: this session sums how much of each source cell the pieces
  /// cover (the same for every operator of a search: one session does).
  void Prepare(MortarOperator& op, const MeshView& target, const MeshView& source, int tasks, bool cover)
  {
    auto start = std::chrono::steady_clock::now();
    this->Op = &op;
    const TaskRunner& runner = op.Options.Runner;
    // M_tt comes after the search (MassMatrix.h): per target cell what it
    // takes, written by the tasks (each cell's state by the task of the
    // cell; zeros first, each task the first to touch its pages).
    const Index rows = SpaceSize(TargetSpace::Type, target);
    op.TargetMass = CsrMatrix();
    op.TargetMass.Rows = op.TargetMass.Columns = rows;
    const Index cells = target.NumberOfCells;
    op.Masses.Dofs = TargetSpace::Dofs;
    op.Masses.State.resize(static_cast<size_t>(cells));
    runner.Fill(op.Masses.State.data(), cells, CellMasses::None, Index(1) << 16);
    this->Partial.resize(static_cast<size_t>(tasks));
    // Target functions on cells of more than one task: their right-hand
    // sides are summed after the tasks (MortarAssembler::Shared; fields
    // given at Build only). Each task sets a bit per function of its cells
    // in a set of its own (an eighth of a byte per function, mostly in its
    // core's cache: no memory shared; 16-bit marks in one array, which the
    // tasks wrote and then read back in a second pass over the cells, took
    // 4.1 ms on two threads for a target of 10^6 cells, the sets 2.2); then,
    // word by word and task after task, a function met again is shared. In
    // batches of 64 tasks, so that the sets never take more room than 8
    // bytes a function.
    const bool single = op.Options.Fields != nullptr;
    if (tasks > 1 && single)
    {
      using Word = std::uint64_t;
      const Index words = rows / 64 + 1;
      UninitializedLargeVector<Word> seen(static_cast<size_t>(words));
      UninitializedLargeVector<Word>& shared = this->Shared;
      shared.resize(static_cast<size_t>(words));
      runner.Fill(seen.data(), words, Word(0), Index(1) << 12);
      runner.Fill(shared.data(), words, Word(0), Index(1) << 12);
      constexpr int Batch = 64;
      std::vector<UninitializedLargeVector<Word>> bits(static_cast<size_t>(std::min(tasks, Batch)));
      for (int batch = 0; batch < tasks; batch += Batch)
      {
        const int count = std::min(Batch, tasks - batch);
        runner.RunAll(count, [&](int i) {
          UninitializedLargeVector<Word>& mine = bits[i];
          mine.resize(static_cast<size_t>(words));
          std::fill(mine.begin(), mine.end(), Word(0));
          Word* set = mine.data();
          const int k = batch + i;
          for (Index c = RangeBegin(cells, k, tasks); c < RangeBegin(cells, k + 1, tasks); ++c)
          {
            Index dofs[TargetSpace::Dofs];
            TargetSpace::MeshCellDofs(target, c, dofs);
            for (Index f : dofs)
            {
              set[f >> 6] |= Word(1) << (f & 63);
            }
          }
        });
        runner.ForRanges(words, [&](Index begin, Index end) {
          for (Index w = begin; w < end; ++w)
          {
            Word before = seen[w];
            Word twice = shared[w];
            for (int i = 0; i < count; ++i)
            {
              twice |= before & bits[i][w];
              before |= bits[i][w];
            }
            seen[w] = before;
            shared[w] = twice;
          }
          return 0;
        }, Index(1) << 12);
      }
    }
    if (single)
    {
      // Zeros written by the tasks (each the first to touch its pages).
      const Index size = rows * op.Options.FieldComponents;
      op.Rhs.resize(static_cast<size_t>(size));
      runner.Fill(op.Rhs.data(), size, 0.0, Index(1) << 16);
    }
    this->Assemblers.resize(static_cast<size_t>(tasks));
    this->Blocks.resize(static_cast<size_t>(tasks));
    this->Pieces.resize(static_cast<size_t>(tasks > 1 ? tasks : 0));
    this->Met.resize(static_cast<size_t>(cover ? tasks : 0));
    // Each zeroed by its task (the first to touch its pages: see LargeArray.h).
    if (cover)
    {
      runner.RunAll(tasks, [&](int k) { this->Met[k].assign(static_cast<size_t>(source.NumberOfCells), 0.0); });
    }
    for (int k = 0; k < tasks; ++k)
    {
      Assembler& a = this->Assemblers[k];
      a.SourceCovered = cover ? this->Met[k].data() : nullptr;
      a.Target = &target;
      a.Source = &source;
      a.MassState = op.Masses.State.data();
      a.Partial = &this->Partial[k];
      a.Shared = tasks > 1 && single ? this->Shared.data() : nullptr;
      a.CoveredFraction = op.CoveredFraction.data();
      a.Excluded = op.Options.ExcludedSourceCells;
      if (op.Options.KeepPieces)
      {
        a.Pieces = tasks > 1 ? &this->Pieces[k] : &op.Pieces;
      }
      MixedBlocks& b = this->Blocks[k];
      b.RowsPerBlock = TargetSpace::Dofs;
      a.Blocks = &b;
      if (single)
      {
        // Right-hand sides only: no blocks.
        a.Fields = op.Options.Fields;
        a.Components = op.Options.FieldComponents;
        a.Rhs = op.Rhs.data();
        continue;
      }
      // Room for the blocks of the range's cells at a generous estimate of
      // columns per cell (the corners of the source cells meeting it): pages
      // of an untouched reservation cost nothing, and the buffers never grow
      // by copying on ordinary meshes.
      const Index rangeCells = RangeBegin(cells, k + 1, tasks) - RangeBegin(cells, k, tasks);
      const Index columnsPerCell = SourceSpace::Dofs == 1 ? 8 : (Intersector::Dimension == 2 ? 12 : 40);
      b.Rows.reserve(static_cast<size_t>(rangeCells * TargetSpace::Dofs));
      b.Start.reserve(static_cast<size_t>(rangeCells + 1));
      b.Columns.reserve(static_cast<size_t>(rangeCells * columnsPerCell));
      b.Values.reserve(static_cast<size_t>(rangeCells * columnsPerCell * TargetSpace::Dofs));
    }
    op.Timings.Assembly = Seconds(start);
  }

  /// After the search: the tasks' sums merged, M_ts, the valid functions.
  void Finish(const MeshView& source)
  {
    MortarOperator& op = *this->Op;
    auto start = std::chrono::steady_clock::now();
    const TaskRunner& runner = op.Options.Runner;
    const int tasks = static_cast<int>(this->Assemblers.size());
    for (Assembler& a : this->Assemblers)
    {
      a.Flush();
    }
    // The tasks' contributions, in task order (deterministic).
    for (int k = 0; k < tasks; ++k)
    {
      Assembler& a = this->Assemblers[k];
      for (const auto& entry : a.DeferredRhs)
      {
        op.Rhs[entry.first] += entry.second;
      }
      if (tasks > 1)
      {
        op.Pieces.Append(this->Pieces[k]);
      }
      op.CoveredMeasure += a.CoveredSum;
      op.OvercoveredCells += a.Overcovered;
      // (Without Met, another session of the search sums the cover: copied after.)
      if (!this->Met.empty() && k == 0)
      {
        op.SourceCovered.swap(this->Met[0]);
      }
      else if (!this->Met.empty())
      {
        const double* met = this->Met[k].data();
        double* covered = op.SourceCovered.data();
        runner.ForRanges(static_cast<Index>(op.SourceCovered.size()), [=](Index begin, Index end) {
          for (Index c = begin; c < end; ++c)
          {
            covered[c] += met[c];
          }
          return 0;
        }, Index(1) << 16);
      }
      op.Statistics.Pieces += a.Count;
    }
    std::vector<Assembler>().swap(this->Assemblers);
    std::vector<IntersectionPieces>().swap(this->Pieces);
    std::vector<LargeVector<double>>().swap(this->Met);
    op.Timings.Search += Seconds(start);

    start = std::chrono::steady_clock::now();
    const Index rows = op.TargetMass.Rows;
    if (op.Options.Fields == nullptr)
    {
      AssembleMixedMatrix(this->Blocks, rows, SpaceSize(SourceSpace::Type, source), runner, op.MixedMass);
    }
    std::vector<MixedBlocks>().swap(this->Blocks);
    op.Masses.Gather(this->Partial);
    std::vector<PartialMasses>().swap(this->Partial);
    op.Timings.Assembly += Seconds(start);
  }
};

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
    // dispatch per piece: 1% of a 3D run).
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
  const double seconds = Seconds(start);
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

void MortarOperator::ShareValidity(const SolverHooks& hooks)
{
  if (!hooks.Exchange)
  {
    return;
  }
  const Index n = this->TargetMass.Rows;
  std::vector<double> diagonal(static_cast<size_t>(n), 0.0);
  for (Index i = 0; i < n; ++i)
  {
    diagonal[i] = this->Valid[i] ? this->TargetMass.Values[this->TargetMass.Find(i, i)] : 0.0;
  }
  hooks.Exchange(diagonal.data(), 1);
  this->NumberOfValid = 0;
  for (Index i = 0; i < n; ++i)
  {
    if (!this->Valid[i] && diagonal[i] > 0.0)
    {
      // Covered in another part only: this part's row is empty (the 1 that
      // decoupled it goes), the other parts complete it.
      this->Valid[i] = 1;
      this->TargetMass.Values[this->TargetMass.Find(i, i)] = 0.0;
    }
    this->NumberOfValid += this->Valid[i];
  }
}

bool MortarOperator::Apply(const double* sourceValues, int components, double* targetValues,
  double fill, const SolveOptions& solve, const SolverHooks& hooks) const
{
  ApplyOptions options;
  options.Solve = solve;
  return this->Apply(sourceValues, components, targetValues, fill, options, hooks);
}

void MortarOperator::ReleaseMatrices()
{
  this->Solver.reset();
  for (CsrMatrix* m : { &this->TargetMass, &this->MixedMass })
  {
    CsrMatrix empty;
    empty.Rows = m->Rows;
    empty.Columns = m->Columns;
    *m = std::move(empty);
  }
  UninitializedLargeVector<double>().swap(this->Rhs);
}

size_t MortarOperator::MemoryBytes() const
{
  auto csr = [](const CsrMatrix& m) {
    return m.RowStart.capacity() * sizeof(Index) + m.ColumnIndex.capacity() * sizeof(Column) +
      m.Values.capacity() * sizeof(double);
  };
  return csr(this->TargetMass) + csr(this->MixedMass) + this->Rhs.capacity() * sizeof(double) +
    this->Valid.capacity() + this->RowSums.capacity() * sizeof(double) +
    this->CoveredFraction.capacity() * sizeof(double) + this->PointCover.capacity() * sizeof(double) +
    this->Pieces.MemoryBytes();
}

namespace
{
/**
 * Clip and assured sum on column `k` of x (rows x c): each valid value into
 * [low_i, high_i], then the difference to `total` (sum of w_i x_i wanted)
 * spread in proportion to w_i times the room left. On a distributed system
 * the sums are over the rows each part counts, summed over the parts (`w`,
 * `low`, `high` and x complete in shared rows, so every part clips them
 * alike).
 */
void ClipAndAssuredSum(double* x, int c, int k, const std::vector<double>& w,
  const std::vector<char>& valid, const std::vector<double>& low, const std::vector<double>& high,
  double total, const SolverHooks& hooks)
{
  const Index n = static_cast<Index>(w.size());
  const char* counted = hooks.Counted;
  double clipped = 0.0;
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      double& v = x[i * c + k];
      v = std::min(high[i], std::max(low[i], v));
      clipped += !counted || counted[i] ? w[i] * v : 0.0;
    }
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&clipped, 1);
  }
  const double missing = total - clipped;
  double room = 0.0;
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i] && (!counted || counted[i]))
    {
      room += w[i] * (missing > 0 ? high[i] - x[i * c + k] : x[i * c + k] - low[i]);
    }
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&room, 1);
  }
  if (!(room > 0.0) || missing == 0.0)
  {
    return; // nothing to give back, or no room (then the sum was already at a bound)
  }
  const double scale = missing / room;
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      double& v = x[i * c + k];
      v += scale * (missing > 0 ? high[i] - v : v - low[i]);
    }
  }
}
} // namespace

bool MortarOperator::Apply(const double* sourceValues, int components, double* targetValues,
  double fill, const ApplyOptions& options, const SolverHooks& hooks) const
{
  const SolveOptions& solve = options.Solve;
  const auto start = std::chrono::steady_clock::now();
  const Index n = this->TargetMass.Rows;
  // A part without rows of a distributed system still takes part in its sums.
  if (!this->Solver || components <= 0 || (n == 0 && !hooks.Reduce && !hooks.Exchange))
  {
    this->Timings.Solve = Seconds(start);
    return this->Solver != nullptr || components <= 0;
  }
  // The right-hand sides: summed during the search for the build's fields,
  // else M_ts u_s (completed across parts by the Exchange hook).
  LargeVector<double> product;
  const double* rhs = this->Rhs.data();
  if (this->Options.Fields)
  {
    if (sourceValues != this->Options.Fields || components != this->Options.FieldComponents)
    {
      return false; // built for other fields: M_ts was not stored
    }
    if (hooks.Exchange)
    {
      product.assign(this->Rhs.begin(), this->Rhs.end());
    }
  }
  else
  {
    product.resize(static_cast<size_t>(n) * components);
    this->Options.Runner.ForRanges(n, [&](Index begin, Index end) {
      this->MixedMass.MultiplyRows(sourceValues, product.data(), components, begin, end);
      return 0.0;
    });
  }
  if (hooks.Exchange)
  {
    hooks.Exchange(product.data(), components);
  }
  if (!product.empty())
  {
    rhs = product.data();
  }
  if (solve.StartFromX)
  {
    // Invalid functions hold the fill value of a previous Apply (NaN, say):
    // their rows and columns of M_tt are zero but for the diagonal, yet
    // 0 * NaN would spread it through the products. Their solution is 0.
    for (Index i = 0; i < n; ++i)
    {
      if (!this->Valid[i])
      {
        std::fill(targetValues + i * components, targetValues + (i + 1) * components, 0.0);
      }
    }
  }
  bool ok = true;
  if (options.Mass == MassType::Lumped)
  {
    // Row sums of M_tt completed across parts like the right-hand sides.
    std::vector<double> sums(this->RowSums);
    if (hooks.Exchange)
    {
      hooks.Exchange(sums.data(), 1);
    }
    for (Index i = 0; i < n; ++i)
    {
      for (int k = 0; k < components; ++k)
      {
        targetValues[i * components + k] = sums[i] > 0.0 ? rhs[i * components + k] / sums[i] : 0.0;
      }
    }
  }
  else
  {
    ok = this->Solver->Solve(rhs, targetValues, components, solve, hooks);
  }
  if (ok && options.Bounded && options.Mass == MassType::Consistent)
  {
    if (!this->HasMixedMass() || (hooks.Exchange && !hooks.ExchangeMinimum))
    {
      return false; // local bounds need M_ts's rows (and, shared, their parts' extremes)
    }
    // Each row's bounds: the Source values of its columns (a shared row's
    // columns are spread over the parts: their extremes, completed). The
    // weights: M_tt's row sums, completed like the right-hand sides.
    std::vector<double> weights(this->RowSums);
    if (hooks.Exchange)
    {
      hooks.Exchange(weights.data(), 1);
    }
    std::vector<double> low(static_cast<size_t>(n)), high(static_cast<size_t>(n));
    std::vector<double> extremes(hooks.ExchangeMinimum ? 2 * static_cast<size_t>(n) : 0);
    for (int k = 0; k < components; ++k)
    {
      double total = 0.0;
      for (Index i = 0; i < n; ++i)
      {
        double lo = std::numeric_limits<double>::infinity();
        double hi = -lo;
        for (Index p = this->MixedMass.RowStart[i]; p < this->MixedMass.RowStart[i + 1]; ++p)
        {
          const double u = sourceValues[static_cast<Index>(this->MixedMass.ColumnIndex[p]) * components + k];
          lo = std::min(lo, u);
          hi = std::max(hi, u);
        }
        low[i] = lo;
        high[i] = hi;
        if (this->Valid[i] && (!hooks.Counted || hooks.Counted[i]))
        {
          total += rhs[i * components + k]; // sum_i (M_ts u_s)_i = int u_s over the covered part
        }
      }
      if (hooks.Reduce)
      {
        hooks.Reduce(&total, 1);
      }
      if (hooks.ExchangeMinimum)
      {
        // The largest as the smallest of the negated values.
        for (Index i = 0; i < n; ++i)
        {
          extremes[2 * i] = low[i];
          extremes[2 * i + 1] = -high[i];
        }
        hooks.ExchangeMinimum(extremes.data(), 2);
        for (Index i = 0; i < n; ++i)
        {
          low[i] = extremes[2 * i];
          high[i] = -extremes[2 * i + 1];
        }
      }
      ClipAndAssuredSum(targetValues, components, k, weights, this->Valid, low, high, total, hooks);
    }
  }
  for (Index i = 0; i < n; ++i)
  {
    if (!this->Valid[i])
    {
      std::fill(targetValues + i * components, targetValues + (i + 1) * components, fill);
    }
  }
  this->Timings.Solve = Seconds(start);
  return ok;
}

} // namespace mp
