// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalSession.h
 * @brief MortarOperator::NodalSession: one operator's share of a search
 *        when a side's point data lives in the cells' own space (private
 *        to MortarBuild.cxx).
 *
 * The counterpart of MortarSession.h for an operator whose target or
 * source space is P1 on a mesh with second-order cells (NodalSpace.h):
 * Prepare() sets up one QuadratureAssembler per task, Finish() adds the
 * tasks' sums in task order and assembles M_ts, and keeps M_tt's blocks
 * for CompleteTargetMass (NodalMass.h). With OperatorOptions::Fields
 * (a single use), each task sums its target blocks' right-hand sides
 * instead of M_ts's blocks (QuadratureAssembler::Fields), added into the
 * operator's in task order after the search: M_ts is never formed.
 */
#ifndef MeshProjection_Kernel_NodalSession_h
#define MeshProjection_Kernel_NodalSession_h

#include "Transfer/MortarOperator.h"

#include "Mesh/Tasks.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/QuadratureAssembler.h"
#include "Transfer/StageClock.h"

#include <algorithm>
#include <chrono>
#include <vector>

namespace mp
{
/// Whether an operator with `options` on these meshes takes the nodal path.
inline bool UsesNodalSpace(
  const OperatorOptions& options, const MeshView& target, const MeshView& source)
{
  return HasNodalSpace(options.TargetSpace, target) || HasNodalSpace(options.SourceSpace, source);
}

template <class Intersector>
struct MortarOperator::NodalSession
{
  using Assembler = QuadratureAssembler<Intersector>;
  MortarOperator* Op = nullptr;
  std::vector<Assembler> Assemblers;
  std::vector<MixedBlocks> Blocks;
  std::vector<MixedBlocks> MassBlocks;
  std::vector<IntersectionPieces> Pieces;
  std::vector<LargeVector<double>> Met;         ///< per task: the source cells' cover
  std::vector<LargeVector<double>> FunctionMet; ///< per task: DP1 functions' cover

  /// `cover`: this session sums how much of each source cell the pieces cover.
  void Prepare(
    MortarOperator& op, const MeshView& target, const MeshView& source, int tasks, bool cover)
  {
    auto start = std::chrono::steady_clock::now();
    this->Op = &op;
    const Index rows = SpaceSize(op.Options.TargetSpace, target);
    op.TargetMass = CsrMatrix();
    op.TargetMass.Rows = op.TargetMass.Columns = rows;
    op.NodalPath = true;
    op.NodalTarget = HasNodalSpace(op.Options.TargetSpace, target);
    // Each source function's integral over the covered part: DP1's, and the
    // cells' own functions' (their integrals are not a share of the cells'
    // measures, as P1's are: a quadratic corner's is zero or less).
    const bool functionCover =
      op.Options.SourceSpace == SpaceType::DP1 || HasNodalSpace(op.Options.SourceSpace, source);
    this->Assemblers.resize(static_cast<size_t>(tasks));
    this->Blocks.resize(static_cast<size_t>(tasks));
    this->MassBlocks.resize(static_cast<size_t>(tasks));
    this->Pieces.resize(static_cast<size_t>(tasks > 1 ? tasks : 0));
    this->Met.resize(static_cast<size_t>(cover ? tasks : 0));
    this->FunctionMet.resize(static_cast<size_t>(functionCover ? tasks : 0));
    const int rowsPerBlock = std::max(1, UniformFunctionCount(target, op.Options.TargetSpace));
    for (int k = 0; k < tasks; ++k)
    {
      this->Blocks[k].RowsPerBlock = this->MassBlocks[k].RowsPerBlock = rowsPerBlock;
      if (cover)
      {
        this->Met[k].assign(static_cast<size_t>(source.NumberOfCells), 0.0);
      }
      if (functionCover)
      {
        this->FunctionMet[k].assign(
          static_cast<size_t>(SpaceSize(op.Options.SourceSpace, source)), 0.0);
      }
      Assembler& a = this->Assemblers[k];
      a.Target = &target;
      a.Source = &source;
      a.TargetSpace = op.Options.TargetSpace;
      a.SourceSpace = op.Options.SourceSpace;
      a.Blocks = &this->Blocks[k];
      a.MassBlocks = &this->MassBlocks[k];
      a.CoveredFraction = op.CoveredFraction.data();
      a.Excluded = op.Options.ExcludedSourceCells;
      a.SourceCovered = cover ? this->Met[k].data() : nullptr;
      a.SourceFunctionCovered = functionCover ? this->FunctionMet[k].data() : nullptr;
      a.Fields = op.Options.Fields;
      a.Components = op.Options.Fields ? op.Options.FieldComponents : 0;
      if (op.Options.KeepPieces)
      {
        a.Pieces = tasks > 1 ? &this->Pieces[k] : &op.Pieces;
      }
      this->Reserve(target,
        RangeBegin(target.NumberOfCells, k + 1, tasks) - RangeBegin(target.NumberOfCells, k, tasks),
        k);
    }
    op.Timings.Assembly = SecondsSince(start);
  }

  /**
   * Room for task k's blocks of `cells` target kernel cells at a generous
   * estimate per cell (the columns of the source functions meeting its
   * parent): pages of an untouched reservation cost nothing (LargeArray.h),
   * and the buffers never grow by copying (which touches every page
   * again) on ordinary meshes.
   */
  void Reserve(const MeshView& target, Index cells, int k)
  {
    const size_t n = static_cast<size_t>(cells);
    const size_t corners = static_cast<size_t>(target.CornersPerCell());
    const size_t columns = target.CellDimension == 3 ? 40 : 16;
    const size_t values = target.CellDimension == 3 ? 160 : 60;
    if (this->Op->Options.Fields)
    {
      Assembler& a = this->Assemblers[k];
      a.RhsRows.reserve(n * corners);
      a.RhsValues.reserve(n * corners * static_cast<size_t>(a.Components));
    }
    else
    {
      MixedBlocks& b = this->Blocks[k];
      b.Rows.reserve(n * corners);
      b.Start.reserve(n + 1);
      b.Columns.reserve(n * columns);
      b.Values.reserve(n * values);
    }
    MixedBlocks& m = this->MassBlocks[k];
    m.Rows.reserve(n * corners);
    m.Start.reserve(n + 1);
    m.Columns.reserve(n * corners);
    m.Values.reserve(n * corners * corners);
  }

  /// With Fields: the tasks' right-hand sides into the operator's, in task order.
  void SumRhs(Index rows)
  {
    MortarOperator& op = *this->Op;
    const size_t nc = static_cast<size_t>(op.Options.FieldComponents);
    op.Rhs.resize(static_cast<size_t>(rows) * nc);
    std::fill(op.Rhs.begin(), op.Rhs.end(), 0.0);
    for (Assembler& a : this->Assemblers)
    {
      for (size_t r = 0; r < a.RhsRows.size(); ++r)
      {
        double* b = &op.Rhs[static_cast<size_t>(a.RhsRows[r]) * nc];
        for (size_t c = 0; c < nc; ++c)
        {
          b[c] += a.RhsValues[r * nc + c];
        }
      }
      std::vector<Index>().swap(a.RhsRows);
      std::vector<double>().swap(a.RhsValues);
    }
  }

  /// After the search: the tasks' sums merged, M_ts (or the right-hand sides), M_tt's blocks kept.
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
    const Index rows = op.TargetMass.Rows;
    if (op.Options.Fields)
    {
      this->SumRhs(rows);
    }
    for (int k = 0; k < tasks; ++k)
    {
      const Assembler& a = this->Assemblers[k];
      if (tasks > 1)
      {
        op.Pieces.Append(this->Pieces[k]);
      }
      op.CoveredMeasure += a.CoveredSum;
      op.OvercoveredCells += a.Overcovered;
      op.UnconvergedPoints[0] += a.T.Unconverged;
      op.UnconvergedPoints[1] += a.S.Unconverged;
      op.Statistics.Pieces += a.Count;
    }
    if (!this->Met.empty())
    {
      SumTaskArrays(this->Met, runner, op.SourceCovered);
    }
    SumTaskArrays(this->FunctionMet, runner, op.SourceFunctionCovered);
    std::vector<Assembler>().swap(this->Assemblers);
    std::vector<IntersectionPieces>().swap(this->Pieces);
    op.Timings.Search += SecondsSince(start);

    start = std::chrono::steady_clock::now();
    if (!op.Options.Fields)
    {
      AssembleMixedMatrix(
        this->Blocks, rows, SpaceSize(op.Options.SourceSpace, source), runner, op.MixedMass);
    }
    op.NodalMassBlocks.swap(this->MassBlocks);
    op.Timings.Assembly += SecondsSince(start);
  }
};
} // namespace mp

#endif
