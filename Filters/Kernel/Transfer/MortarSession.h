// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarSession.h
 * @brief MortarOperator::Session: one operator's share of a search (private
 *        to MortarBuild.cxx).
 *
 * The search visits the pieces of every (target, source) pair once;
 * several operators can take them (MortarOperator::BuildTogether). Each
 * takes them through a session of its own: Prepare() sets up, before the
 * search, what its tasks sum into (per target cell what M_tt takes, the
 * marks of target functions shared by tasks, one assembler per task);
 * Finish(), after it, adds the tasks' sums in task order (so any number of
 * operators built together gives each the result of its own Build) and
 * assembles M_ts.
 */
#ifndef MeshProjection_Kernel_MortarSession_h
#define MeshProjection_Kernel_MortarSession_h

#include "Transfer/MortarOperator.h"

#include "Transfer/MassMatrix.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/MortarAssembler.h"
#include "Transfer/StageClock.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

namespace mp
{
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
  UninitializedLargeVector<std::uint64_t>
    Shared; ///< per target function a bit (MortarAssembler::Shared)
  std::vector<Assembler> Assemblers;
  std::vector<MixedBlocks> Blocks;
  std::vector<IntersectionPieces> Pieces;
  std::vector<PartialMasses> Partial; ///< per task: M_tt's blocks of cells covered in part
  // How much of each source cell the pieces cover: per task, summed after.
  std::vector<LargeVector<double>> Met;
  // DP1 sources: each function's covered integral, per task, summed after.
  std::vector<LargeVector<double>> FunctionMet;

  /// `cover`: this session sums how much of each source cell the pieces
  /// cover (the same for every operator of a search: one session does).
  void Prepare(
    MortarOperator& op, const MeshView& target, const MeshView& source, int tasks, bool cover)
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
    // tasks wrote and then read back in a second pass over the cells, shared
    // cache lines between the tasks and took longer); then,
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
        runner.ForRanges(
          words,
          [&](Index begin, Index end) {
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
          },
          Index(1) << 12);
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
    // DP1: each function's covered integral (the integrals of reconstructed cell data).
    constexpr bool functionCover = SourceSpace::Type == SpaceType::DP1;
    this->FunctionMet.resize(static_cast<size_t>(functionCover ? tasks : 0));
    // Each zeroed by its task (the first to touch its pages: see LargeArray.h).
    runner.RunAll(tasks, [&](int k) {
      if (cover)
      {
        this->Met[k].assign(static_cast<size_t>(source.NumberOfCells), 0.0);
      }
      if (functionCover)
      {
        this->FunctionMet[k].assign(static_cast<size_t>(SpaceSize(SpaceType::DP1, source)), 0.0);
      }
    });
    for (int k = 0; k < tasks; ++k)
    {
      Assembler& a = this->Assemblers[k];
      a.SourceCovered = cover ? this->Met[k].data() : nullptr;
      a.SourceFunctionCovered = functionCover ? this->FunctionMet[k].data() : nullptr;
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
        a.FieldCache.Clear();
        continue;
      }
      // Room for the blocks of the range's cells at a generous estimate of
      // columns per cell (the corners of the source cells meeting it): pages
      // of an untouched reservation cost nothing, and the buffers never grow
      // by copying on ordinary meshes.
      const Index rangeCells = RangeBegin(cells, k + 1, tasks) - RangeBegin(cells, k, tasks);
      const Index columnsPerCell =
        SourceSpace::Dofs == 1 ? 8 : (Intersector::Dimension == 2 ? 12 : 40);
      b.Rows.reserve(static_cast<size_t>(rangeCells * TargetSpace::Dofs));
      b.Start.reserve(static_cast<size_t>(rangeCells + 1));
      b.Columns.reserve(static_cast<size_t>(rangeCells * columnsPerCell));
      b.Values.reserve(static_cast<size_t>(rangeCells * columnsPerCell * TargetSpace::Dofs));
    }
    op.Timings.Assembly = SecondsSince(start);
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
      op.Statistics.Pieces += a.Count;
    }
    // (Without Met, another session of the search sums the cover: copied after.)
    if (!this->Met.empty())
    {
      SumTaskArrays(this->Met, runner, op.SourceCovered);
    }
    SumTaskArrays(this->FunctionMet, runner, op.SourceFunctionCovered);
    std::vector<Assembler>().swap(this->Assemblers);
    std::vector<IntersectionPieces>().swap(this->Pieces);
    std::vector<LargeVector<double>>().swap(this->Met);
    std::vector<LargeVector<double>>().swap(this->FunctionMet);
    op.Timings.Search += SecondsSince(start);

    start = std::chrono::steady_clock::now();
    const Index rows = op.TargetMass.Rows;
    if (op.Options.Fields == nullptr)
    {
      AssembleMixedMatrix(
        this->Blocks, rows, SpaceSize(SourceSpace::Type, source), runner, op.MixedMass);
    }
    std::vector<MixedBlocks>().swap(this->Blocks);
    op.Masses.Gather(this->Partial);
    std::vector<PartialMasses>().swap(this->Partial);
    op.Timings.Assembly += SecondsSince(start);
  }
};
} // namespace mp

#endif
