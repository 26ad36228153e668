// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarAssembler.h
 * @brief From pieces to matrices: the paper's MortarInt, for any pair of spaces.
 *
 * The search hands every (target cell, source cell, piece) to a
 * MortarAssembler. From the piece's moments (Geometry) and the two spaces'
 * basis functions on the two cells (Space.h) it adds the local mixed block
 * int phi_i psi_j to the block of the current target cell, and sums the
 * piece's moments about the target cell's first corner. When the cell's
 * last piece has come (the searches deliver the pieces of a target cell one
 * after the other), the cell is marked as covered whole (its target mass
 * block is the element mass matrix, formed once the search is done:
 * MassMatrix.h) or its block from the covered part's moments is kept, and
 * the cell's mixed block is appended to the task's MixedBlocks
 * (MixedMatrix.h). For a single use the assembler can
 * instead sum the right-hand sides M_ts u_s of given fields (Fields): the
 * source field is one affine function on each piece, integrated against
 * the target functions, and M_ts is never formed.
 *
 * With concurrent tasks, target functions whose cells belong to several
 * tasks (Shared) get their right-hand sides collected in DeferredRhs and
 * added after all tasks, in task order.
 */
#ifndef MeshProjection_Kernel_MortarAssembler_h
#define MeshProjection_Kernel_MortarAssembler_h

#include "Geometry/IntersectionPieces.h"
#include "Geometry/SourceSide.h"
#include "Mesh/MeshView.h"
#include "Transfer/CsrMatrix.h"
#include "Transfer/MassMatrix.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/MortarBlocks.h"
#include "Transfer/SourceCellFields.h"
#include "Transfer/Space.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace mp
{
/**
 * The local blocks of one piece, Mts[i][j] = int phi_i psi_j and
 * Mtt[i][k] = int phi_i phi_k over it (added), in the order of the spaces'
 * CellDofs on t and s. Returns the piece's measure (0 when the cells only
 * touch). The reference the assembled matrices are checked against.
 */
template <class Intersector, class TargetSpace, class SourceSpace>
double AddPieceBlocks(const typename Intersector::Piece& piece, const typename Intersector::Cell& t,
  const typename SourceSideOf<Intersector>::type::Cell& s,
  double (&Mts)[TargetSpace::Dofs][SourceSpace::Dofs],
  double (&Mtt)[TargetSpace::Dofs][TargetSpace::Dofs])
{
  constexpr int K = Intersector::Dimension + 1;
  double o[K - 1];
  double M[K][K];
  const double measure = Intersector::Moments(piece, o, M);
  if (!(measure > 0.0))
  {
    return 0.0;
  }
  double lt[TargetSpace::Dofs][K];
  double ls[SourceSpace::Dofs][K];
  TargetSpace::Basis(t, o, lt);
  SourceSpace::Basis(Intersector::SourceCell(s, piece), o, ls);
  AddMixedBlock<TargetSpace::Dofs, SourceSpace::Dofs, K>(lt, ls, M, Mts);
  AddTargetBlock<TargetSpace::Dofs, K>(lt, M, Mtt);
  return measure;
}

/// Whether intersector I's pieces can be claimed by several source cells
/// (I::Tied, I::TieKey: traces of curves along edges of the source).
template <class I, class = void>
struct HasTies : std::false_type
{};
template <class I>
struct HasTies<I, std::void_t<decltype(I::TieKey(std::declval<const typename I::Piece&>()))>>
  : std::true_type
{};

template <class Intersector, class TargetSpace, class SourceSpace>
struct MortarAssembler
{
  using TargetSpaceType = TargetSpace;
  using SourceSpaceType = SourceSpace;
  static constexpr int D = Intersector::Dimension;
  static constexpr int K = D + 1;
  static constexpr int Nt = TargetSpace::Dofs;
  static constexpr int Ns = SourceSpace::Dofs;
  using Cell = typename Intersector::Cell;

  const MeshView* Target = nullptr;
  const MeshView* Source = nullptr;
  /// Per target kernel cell: what M_tt takes from it (CellMasses::State),
  /// written when its last piece has come ...
  float* MassState = nullptr;
  PartialMasses* Partial = nullptr; ///< ... and the blocks of cells covered in part (this task's)
  MixedBlocks* Blocks = nullptr;    ///< this task's mixed blocks
  /// Per target kernel cell: the covered fraction of its measure, written
  /// when its last piece has come (each cell belongs to one task).
  double* CoveredFraction = nullptr;
  double CoveredSum = 0.0; ///< measure of all pieces of this task
  Index Overcovered = 0;   ///< cells whose pieces add up to more than the cell
  IntersectionPieces* Pieces = nullptr;
  Index Count = 0;                ///< pieces of positive measure
  const char* Excluded = nullptr; ///< per source cell: nonzero to leave its pieces out
  /// Per source cell: the measure of its part covered by pieces, on the
  /// source cell (this task's own array, or null).
  double* SourceCovered = nullptr;
  /// DP1 source functions: per function, its integral over the covered
  /// part, on the source cell (this task's own array, or null).
  double* SourceFunctionCovered = nullptr;
  /// Per target function a bit (function f: bit f % 64 of word f / 64), set
  /// when cells of several tasks use it; null for a single task.
  const std::uint64_t* Shared = nullptr;
  /// Right-hand sides instead of blocks: the source fields (source
  /// functions x Components) and their sums (target functions x Components).
  const double* Fields = nullptr;
  int Components = 0;
  double* Rhs = nullptr;
  std::vector<std::pair<Index, double>> DeferredRhs; ///< (position in Rhs, value)
  /// The current cell's pieces' moments times each source field, about its
  /// corner 0 (Components x K): its right-hand sides follow once per cell.
  std::vector<double> CellField;
  /// The source fields per recently met source cell (Clear when Fields change).
  SourceCellFieldCache<SourceSpace> FieldCache;

  Index Current = -1; ///< the target cell whose pieces are coming
  Cell CurrentCell;
  double Moments[K][K];             ///< of its pieces so far, about its corner 0
  std::vector<Column> BlockColumns; ///< source functions its pieces met
  std::vector<double> BlockValues;  ///< Nt per column

  /// Pieces of the current target cell claimed by several source cells
  /// (HasTies): each edge's claim from the lowest source cell id is kept.
  struct Tie
  {
    std::pair<Index, Index> Key;
    typename SourceSideOf<Intersector>::type::Cell Source;
    typename Intersector::Piece Piece;
  };
  std::vector<Tie> Ties;

  void SettleTies()
  {
    if (this->Ties.empty())
    {
      return;
    }
    std::vector<Tie> ties;
    ties.swap(this->Ties);
    std::sort(ties.begin(), ties.end(), [](const Tie& a, const Tie& b) {
      return a.Key != b.Key ? a.Key < b.Key : a.Source.Id < b.Source.Id;
    });
    for (size_t i = 0; i < ties.size(); ++i)
    {
      if (i == 0 || ties[i].Key != ties[i - 1].Key)
      {
        ties[i].Piece.Target = &this->CurrentCell; // the search's own has moved on
        this->Add(this->CurrentCell, ties[i].Source, ties[i].Piece);
      }
    }
  }

  void Flush()
  {
    if (this->Current < 0)
    {
      return;
    }
    if constexpr (HasTies<Intersector>::value)
    {
      this->SettleTies();
    }
    const double covered = this->Moments[0][0];
    const double fraction = covered / this->CurrentCell.Measure;
    this->Overcovered += fraction > 1.0 + 1e-9;
    this->CoveredFraction[this->Current] = std::min(1.0, fraction);
    this->CoveredSum += covered;
    const Index current = this->Current;
    this->Current = -1;
    if (!(covered > 0.0))
    {
      return; // only touching pieces
    }
    Index dofs[Nt];
    TargetSpace::CellDofs(*this->Target, this->CurrentCell, dofs);
    // M_tt's block: formed again from the cell when it is covered whole
    // (MassMatrix.h), else kept.
    const float state = CellMasses::StateOf(*this->Target, current, covered);
    this->MassState[current] = state;
    if (state == CellMasses::Part)
    {
      double mtt[Nt][Nt];
      TargetSpace::MassFromMoments(this->CurrentCell, this->Moments, mtt);
      this->Partial->Add(*this->Target, current, dofs, mtt);
    }
    if (this->Fields)
    {
      // int lt_i u_c over the covered part: the target functions about the
      // corner the moments were summed about, once per cell.
      double lt[Nt][K];
      TargetSpace::Basis(this->CurrentCell, this->CurrentCell.X[0], lt);
      const int nc = this->Components;
      for (int i = 0; i < Nt; ++i)
      {
        const bool shared = this->Shared && ((this->Shared[dofs[i] >> 6] >> (dofs[i] & 63)) & 1);
        for (int c = 0; c < nc; ++c)
        {
          const Index position = dofs[i] * nc + c;
          const double* field = &this->CellField[static_cast<size_t>(c) * K];
          double value = 0.0;
          for (int a = 0; a < K; ++a)
          {
            value += lt[i][a] * field[a];
          }
          if (shared)
          {
            this->DeferredRhs.emplace_back(position, value);
          }
          else
          {
            this->Rhs[position] += value;
          }
        }
      }
      return;
    }
    MixedBlocks& b = *this->Blocks;
    b.Rows.insert(b.Rows.end(), dofs, dofs + Nt);
    b.Columns.insert(b.Columns.end(), this->BlockColumns.begin(), this->BlockColumns.end());
    b.Values.insert(b.Values.end(), this->BlockValues.begin(), this->BlockValues.end());
    b.Start.push_back(static_cast<Index>(b.Columns.size()));
  }

  /// SourceCell: the cell type of the source side (Cell, or a volume's for traces).
  template <class SourceCell>
  void operator()(const Cell& t, const SourceCell& s, const typename Intersector::Piece& piece)
  {
    if (t.Id != this->Current)
    {
      this->Flush();
      this->Current = t.Id;
      this->CurrentCell = t;
      for (auto& row : this->Moments)
      {
        std::fill(row, row + K, 0.0);
      }
      this->BlockColumns.clear();
      this->BlockValues.clear();
      // (Resized only when Components change: assign's call per cell, out
      // of line, cost more than the few zeros it writes.)
      this->CellField.resize(static_cast<size_t>(K) * this->Components);
      std::fill(this->CellField.begin(), this->CellField.end(), 0.0);
    }
    if constexpr (HasTies<Intersector>::value)
    {
      if (Intersector::Tied(piece))
      {
        this->Ties.push_back({ Intersector::TieKey(piece), s, piece });
        return;
      }
    }
    this->Add(t, s, piece);
  }

  /// Adds one piece of the current target cell.
  template <class SourceCell>
  void Add(const Cell& t, const SourceCell& s, const typename Intersector::Piece& piece)
  {
    if (this->Excluded && this->Excluded[s.Id])
    {
      return; // a hole in the source (no data there)
    }
    double o[D];
    double M[K][K];
    const double measure = Intersector::Moments(piece, o, M);
    if (!(measure > 0.0))
    {
      return; // the cells only touch
    }
    double d[D];
    for (int a = 0; a < D; ++a)
    {
      d[a] = o[a] - t.X[0][a];
    }
    // The piece's moments about the target cell's corner 0, summed for the
    // cell's mass block.
    double shifted[K][K];
    ShiftMoments<K>(M, d, shifted);
    for (int a = 0; a < K; ++a)
    {
      for (int b = 0; b < K; ++b)
      {
        this->Moments[a][b] += shifted[a][b];
      }
    }
    // The source cell as the spaces see it on a piece (a surface's source
    // facet: its image in the target's plane).
    const auto& sourceCell = Intersector::SourceCell(s, piece);
    Index dofs[Ns];
    if (this->Fields)
    {
      this->AddFields(t, s, sourceCell, shifted);
      if (this->SourceFunctionCovered)
      {
        double ls[Ns][K];
        SourceSpace::CellDofs(*this->Source, sourceCell, dofs);
        SourceSpace::Basis(sourceCell, t.X[0], ls);
        this->AddFunctionCover(s, piece, ls, shifted[0], dofs);
      }
      this->Finish(t, s, piece, measure);
      return;
    }
    SourceSpace::CellDofs(*this->Source, sourceCell, dofs);
    double lt[Nt][K];
    double ls[Ns][K];
    TargetSpace::Basis(t, o, lt);
    SourceSpace::Basis(sourceCell, o, ls);
    double mts[Nt][Ns] = {};
    AddMixedBlock<Nt, Ns, K>(lt, ls, M, mts);
    this->AddFunctionCover(s, piece, ls, M[0], dofs);
    for (int j = 0; j < Ns; ++j)
    {
      // The block's column of source function dofs[j] (a few per cell).
      const Column c = static_cast<Column>(dofs[j]);
      size_t slot = 0;
      while (slot < this->BlockColumns.size() && this->BlockColumns[slot] != c)
      {
        ++slot;
      }
      if (slot == this->BlockColumns.size())
      {
        this->BlockColumns.push_back(c);
        this->BlockValues.insert(this->BlockValues.end(), Nt, 0.0);
      }
      double* values = &this->BlockValues[slot * Nt];
      for (int i = 0; i < Nt; ++i)
      {
        values[i] += mts[i][j];
      }
    }
    this->Finish(t, s, piece, measure);
  }

  /**
   * Adds the piece's moments `shifted` (about t's corner 0) times the
   * source fields on `cell` (the source cell as the spaces see it on the
   * piece, of search cell `s`), as affine functions about that corner: the
   * target functions come in once per cell (Flush), not once per piece.
   */
  template <class SourceCell, class SpaceCell>
  void AddFields(
    const Cell& t, const SourceCell& s, const SpaceCell& cell, const double (&shifted)[K][K])
  {
    if constexpr (std::is_same<SpaceCell, SourceCell>::value)
    {
      // The search's own prepared cell is the same on all its pieces: its
      // fields come from the cache, formed once while the front meets it.
      if (&cell == &s)
      {
        const int nc = this->Components;
        const double* g = this->FieldCache.Of(*this->Source, cell, this->Fields, nc);
        double d[D];
        for (int a = 0; a < D; ++a)
        {
          d[a] = t.X[0][a] - cell.X[0][a];
        }
        for (int c = 0; c < nc; ++c)
        {
          double f[K];
          SourceCellFieldCache<SourceSpace>::At(g + c * K, d, f);
          double Mf[K];
          MomentTimes<K>(shifted, f, Mf);
          double* field = &this->CellField[static_cast<size_t>(c) * K];
          for (int a = 0; a < K; ++a)
          {
            field[a] += Mf[a];
          }
        }
        return;
      }
    }
    Index dofs[Ns];
    SourceSpace::CellDofs(*this->Source, cell, dofs);
    double ls[Ns][K];
    SourceSpace::Basis(cell, t.X[0], ls);
    const double* u[Ns];
    for (int j = 0; j < Ns; ++j)
    {
      u[j] = this->Fields + dofs[j] * this->Components;
    }
    AddFieldMoments<Ns, K>(ls, shifted, u, this->Components, this->CellField.data());
  }

  /// The piece's integrals of the source functions (ls, about the origin
  /// of the moments whose first row is `m0`), when they are summed.
  template <class SourceCell>
  void AddFunctionCover(const SourceCell& s, const typename Intersector::Piece& piece,
    const double (&ls)[Ns][K], const double (&m0)[K], const Index (&dofs)[Ns])
  {
    if (!this->SourceFunctionCovered)
    {
      return;
    }
    const double scale = Intersector::SourceScale(s, piece);
    for (int j = 0; j < Ns; ++j)
    {
      this->SourceFunctionCovered[dofs[j]] += scale * DotK<K>(ls[j], m0);
    }
  }

  /// Counts a piece of positive `measure`, and keeps it when asked.
  template <class SourceCell>
  void Finish(
    const Cell& t, const SourceCell& s, const typename Intersector::Piece& piece, double measure)
  {
    ++this->Count;
    if (this->SourceCovered)
    {
      this->SourceCovered[s.Id] += measure * Intersector::SourceScale(s, piece);
    }
    if (this->Pieces)
    {
      Intersector::AppendPiece(piece, t.Id, s.Id, *this->Pieces);
    }
  }
};
} // namespace mp

#endif
