// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file QuadratureAssembler.h
 * @brief From pieces to matrices by quadrature: the mortar integrals of
 *        functions that are not affine on a piece (NodalSpace.h).
 *
 * The search hands every (target cell, source cell, piece) to a
 * QuadratureAssembler, as to a MortarAssembler, which integrates the two
 * cells' functions over the piece by quadrature (PieceQuadrature.h) with
 * the rule of degree max(dt + ds, 2 dt) (dt, ds the two cells' degrees:
 * NodalDegree for a second-order parent, 1 for P1 and DP1, 0 for P0), at
 * most 6 (MaxPieceDegree): exact for straight simplices, whose functions
 * are polynomials of those degrees; on a curved cell the functions are its true isoparametric ones
 * and the rule's error is that of their polynomial approximation on the
 * piece. Where the source functions lie in the target cell's span
 * (InTargetBasis), the pieces' target mass blocks are summed per source
 * parent (Deferred) and turned into mixed blocks once per parent when the
 * target cell is done.
 *
 * Both M_ts and M_tt come from the pieces (on a curved cell the covered
 * part is what the pieces measure), but for an affine cell (straight or
 * linear) of degree at most 3 covered whole, whose M_tt block the rule on
 * the cell gives exactly, once (ElementMass): the pieces' points are kept per cell until
 * its last piece says which. When a target cell's last piece has come, its
 * blocks go to the task's MixedBlocks, one block per cell when every
 * target cell has as many functions (RowsPerBlock: UniformFunctionCount),
 * else one per target function (RowsPerBlock 1), M_ts's into Blocks and
 * M_tt's into MassBlocks; M_tt is then assembled from these
 * (NodalMass.h). The covered fractions, the source cover, the kept pieces
 * and the counts are those of MortarAssembler.
 *
 * Triangles in the plane, tetrahedra, surfaces, curves and traces: a
 * surface's or curve's piece lies in the target facet's frame, where each
 * quadrature point is taken back to the target facet and to the source
 * facet it is the image of, or for a trace to the point in the source
 * volume (PiecePlaces), the functions evaluated there.
 */
#ifndef MeshProjection_Kernel_QuadratureAssembler_h
#define MeshProjection_Kernel_QuadratureAssembler_h

#include "Geometry/IntersectionPieces.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/MortarAssembler.h"
#include "Transfer/NodalSpace.h"
#include "Transfer/PieceQuadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace mp
{
template <class Intersector>
struct QuadratureAssembler
{
  using Cell = typename Intersector::Cell;
  using Piece = typename Intersector::Piece;
  static constexpr int D = Intersector::Dimension;

  const MeshView* Target = nullptr;
  const MeshView* Source = nullptr;
  SpaceType TargetSpace = SpaceType::P1;
  SpaceType SourceSpace = SpaceType::P1;
  MixedBlocks* Blocks = nullptr;     ///< this task's M_ts blocks (see the file comment)
  MixedBlocks* MassBlocks = nullptr; ///< this task's M_tt blocks
  /// Per target kernel cell: the covered fraction of its measure, written
  /// when its last piece has come (each cell belongs to one task).
  double* CoveredFraction = nullptr;
  double CoveredSum = 0.0; ///< measure of all pieces of this task
  Index Overcovered = 0;   ///< cells whose pieces add up to more than the cell
  IntersectionPieces* Pieces = nullptr;
  Index Count = 0;                         ///< pieces of positive measure
  const char* Excluded = nullptr;          ///< per source cell: nonzero to leave its pieces out
  double* SourceCovered = nullptr;         ///< per source cell (this task's, or null)
  double* SourceFunctionCovered = nullptr; ///< DP1: per source function (this task's, or null)
  /// A single use: the source fields (source functions x Components), whose
  /// right-hand sides are summed instead of M_ts's blocks (null: M_ts).
  const double* Fields = nullptr;
  int Components = 0;
  std::vector<Index> RhsRows;    ///< Fields: the blocks' rows (T.Count per block) ...
  std::vector<double> RhsValues; ///< ... and their right-hand sides (Components per row)
  std::vector<double> BlockRhs;  ///< the open blocks' (T.Count x Components)

  Index Current = -1; ///< the target cell whose pieces are coming
  double CurrentMeasure = 0.0;
  double Covered = 0.0;             ///< its pieces' measure so far
  NodalFunctions T;                 ///< its functions
  NodalFunctions S;                 ///< the current source cell's
  std::vector<Column> BlockColumns; ///< source functions the open blocks' pieces met
  std::vector<double> BlockValues;  ///< T.Count per column
  bool Open = false;                ///< blocks of cells with T's functions are open
  std::vector<double> Mtt;          ///< their M_tt block (T.Count x T.Count)
  std::vector<double> TargetPoints; ///< its pieces' points: weight, then T.Count values ...
  std::vector<double> MttSum;       ///< ... or their blocks (InTargetBasis)
  /// The current cell's pieces' target mass blocks per source parent
  /// (InTargetBasis): their mixed blocks follow once per parent (CloseCell).
  /// With Fields, the open blocks' sums per source parent (their values
  /// at the target's nodes are the same on all the blocks' cells), settled
  /// when the blocks are appended.
  struct Deferred
  {
    Index Key = -1;  ///< NodalFunctions::Key of the source functions
    Index Cell = -1; ///< a source cell they live on
    std::vector<double> G;
    // With Fields, G is not formed: the source functions at the target's
    // nodes (Psi, T.Count x S.Count) and their dofs, the fields there (U,
    // T.Count x Components), and the pieces' integrals of the target functions.
    std::vector<double> Psi;
    std::vector<Index> Dofs;
    std::vector<double> U;
    std::vector<double> Integral;
  };
  std::vector<Deferred> Pending;
  size_t PendingCount = 0;
  std::vector<double> PieceMts; ///< one piece's, T.Count x S.Count

  /// The last cell done, and its open blocks appended.
  void Flush()
  {
    this->CloseCell();
    this->AppendBlocks();
  }

  /// Pieces of the current target cell claimed by several source cells
  /// (HasTies: a curve along an edge of a volume): each edge's claim from
  /// the lowest source cell id is kept, as MortarAssembler keeps it.
  struct Tie
  {
    std::pair<Index, Index> Key;
    typename SourceSideOf<Intersector>::type::Cell Source;
    Piece Part;
  };
  std::vector<Tie> Ties;
  Cell CurrentCell; ///< (ties are settled after the search's own has moved on)

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
        ties[i].Part.Target = &this->CurrentCell;
        this->Add(this->CurrentCell, ties[i].Source, ties[i].Part);
      }
    }
  }

  /**
   * The current cell done: its covered fraction, and its M_tt block added
   * to the open one: the cell's own where that is exact (an affine cell
   * covered whole, as the linear path's element matrix), else its pieces'.
   * Its mixed blocks stay open while the next cells have the same
   * functions (the simplices of one second-order parent, met one after
   * the other: one block for them all).
   */
  void CloseCell()
  {
    if (this->Current < 0)
    {
      return;
    }
    if constexpr (HasTies<Intersector>::value)
    {
      this->SettleTies();
    }
    const double fraction = this->Covered / this->CurrentMeasure;
    this->Overcovered += fraction > 1.0 + 1e-9;
    this->CoveredFraction[this->Current] = std::min(1.0, fraction);
    this->CoveredSum += this->Covered;
    const Index current = this->Current;
    this->Current = -1;
    if (!(this->Covered > 0.0))
    {
      return; // only touching pieces
    }
    const int nt = this->T.Count;
    if (!this->Fields)
    {
      this->SettlePending(); // (with Fields, once per block: AppendBlocks)
    }
    if (!this->Open)
    {
      this->Mtt.assign(static_cast<size_t>(nt) * nt, 0.0);
      this->Open = true;
    }
    // (Only where the pieces' rule is exact for M_tt too: else M_tt comes
    // from the pieces' points, as M_ts, and a field of the target's space
    // is still reproduced.)
    if (this->T.IsAffine() && 2 * this->T.Degree <= MaxPieceDegree &&
      std::fabs(this->Covered - this->CurrentMeasure) <= 1e-12 * this->CurrentMeasure)
    {
      this->MttSum.resize(static_cast<size_t>(nt) * nt);
      ElementMass(*this->Target, current, this->CurrentMeasure, this->T, this->MttSum.data());
    }
    else
    {
      TargetMassFromPoints(this->TargetPoints, nt, this->MttSum.data());
    }
    for (size_t e = 0; e < this->Mtt.size(); ++e)
    {
      this->Mtt[e] += this->MttSum[e];
    }
  }

  /// The deferred sources' mixed blocks (and their mass blocks into MttSum).
  void SettlePending()
  {
    const int nt = this->T.Count;
    for (size_t k = 0; k < this->PendingCount; ++k)
    {
      Deferred& d = this->Pending[k];
      if (this->Fields)
      {
        this->SettleIntegrals(d);
        continue;
      }
      MirrorUpper(nt, d.G.data()); // (AddPieceTargetMass summed the upper triangle)
      this->S.Bind(*this->Source, this->SourceSpace, d.Cell);
      this->PieceMts.assign(static_cast<size_t>(nt) * this->S.Count, 0.0);
      double integrals[MaxNodalFunctions] = {};
      SourceInTargetBasis(*this->Target, this->T, this->S, d.G.data(), this->PieceMts.data(),
        this->SourceFunctionCovered ? integrals : nullptr);
      this->MergeColumns(integrals, 1.0);
      for (size_t e = 0; e < d.G.size(); ++e)
      {
        this->MttSum[e] += d.G[e];
      }
    }
    this->PendingCount = 0;
  }

  /// The pending sums of the source functions of Key `key`, or null.
  Deferred* FindPending(Index key)
  {
    for (size_t k = 0; k < this->PendingCount; ++k)
    {
      if (this->Pending[k].Key == key)
      {
        return &this->Pending[k];
      }
    }
    return nullptr;
  }

  /// With Fields: the source functions' integrals over a deferred source's
  /// pieces (sum_m int phi_m psi_j(X_m)) into their cover.
  void SettleIntegrals(const Deferred& d)
  {
    if (!this->SourceFunctionCovered)
    {
      return;
    }
    const int nt = this->T.Count;
    const int ns = static_cast<int>(d.Dofs.size());
    for (int j = 0; j < ns; ++j)
    {
      double integral = 0.0;
      for (int m = 0; m < nt; ++m)
      {
        integral += d.Integral[m] * d.Psi[static_cast<size_t>(m) * ns + j];
      }
      this->SourceFunctionCovered[d.Dofs[j]] += integral;
    }
  }

  /// The pending sums of the source functions bound in S: when new, a zero
  /// target mass block, or with Fields their values at the target's nodes.
  Deferred& PendingFor(Index cell)
  {
    const Index key = this->S.Key();
    if (Deferred* known = this->FindPending(key))
    {
      return *known;
    }
    if (this->PendingCount == this->Pending.size())
    {
      this->Pending.emplace_back();
    }
    Deferred& d = this->Pending[this->PendingCount++];
    d.Key = key;
    d.Cell = cell;
    const size_t nt = static_cast<size_t>(this->T.Count);
    if (!this->Fields)
    {
      d.G.assign(nt * nt, 0.0);
      return d;
    }
    d.Psi.resize(nt * this->S.Count);
    d.Dofs.assign(this->S.Dofs, this->S.Dofs + this->S.Count);
    d.U.resize(nt * this->Components);
    d.Integral.assign(nt, 0.0);
    SourceAtTargetNodes(
      *this->Target, this->T, this->S, this->Fields, this->Components, d.Psi.data(), d.U.data());
    return d;
  }

  /// With Fields: PieceMts (T.Count x S.Count, the functions bound in S)
  /// times the fields into the open blocks' right-hand sides, and
  /// `integrals` times `scale` to the source functions' cover.
  void AddToRhs(const double* integrals, double scale)
  {
    const int nt = this->T.Count;
    const int ns = this->S.Count;
    const int nc = this->Components;
    for (int i = 0; i < nt; ++i)
    {
      for (int c = 0; c < nc; ++c)
      {
        double value = 0.0;
        for (int j = 0; j < ns; ++j)
        {
          value += this->PieceMts[static_cast<size_t>(i) * ns + j] *
            this->Fields[this->S.Dofs[j] * nc + c];
        }
        this->BlockRhs[static_cast<size_t>(i) * nc + c] += value;
      }
    }
    for (int j = 0; this->SourceFunctionCovered && j < ns; ++j)
    {
      this->SourceFunctionCovered[this->S.Dofs[j]] += scale * integrals[j];
    }
  }

  /// Adds PieceMts (T.Count x S.Count, the functions bound in S) to the
  /// block's columns, and `integrals` times `scale` to the source functions' cover.
  void MergeColumns(const double* integrals, double scale)
  {
    const int nt = this->T.Count;
    const int ns = this->S.Count;
    for (int j = 0; j < ns; ++j)
    {
      const Column c = static_cast<Column>(this->S.Dofs[j]);
      size_t slot = 0;
      while (slot < this->BlockColumns.size() && this->BlockColumns[slot] != c)
      {
        ++slot;
      }
      if (slot == this->BlockColumns.size())
      {
        this->BlockColumns.push_back(c);
        this->BlockValues.insert(this->BlockValues.end(), nt, 0.0);
      }
      double* values = &this->BlockValues[slot * nt];
      for (int i = 0; i < nt; ++i)
      {
        values[i] += this->PieceMts[static_cast<size_t>(i) * ns + j];
      }
      if (this->SourceFunctionCovered)
      {
        this->SourceFunctionCovered[this->S.Dofs[j]] += scale * integrals[j];
      }
    }
  }

  /// The open blocks into the task's: one block of all their rows when the
  /// blocks have that many (RowsPerBlock), else one per row.
  void AppendBlocks()
  {
    if (this->Fields)
    {
      this->SettlePending();
    }
    if (!this->Open)
    {
      return;
    }
    this->Open = false;
    const int nt = this->T.Count;
    MixedBlocks& b = *this->Blocks;
    MixedBlocks& m = *this->MassBlocks;
    const size_t columns = this->BlockColumns.size();
    const bool mixed = this->Fields == nullptr;
    if (!mixed)
    {
      this->RhsRows.insert(this->RhsRows.end(), this->T.Dofs, this->T.Dofs + nt);
      this->RhsValues.insert(this->RhsValues.end(), this->BlockRhs.begin(), this->BlockRhs.end());
    }
    if (b.RowsPerBlock == nt)
    {
      if (mixed)
      {
        b.Rows.insert(b.Rows.end(), this->T.Dofs, this->T.Dofs + nt);
        b.Columns.insert(b.Columns.end(), this->BlockColumns.begin(), this->BlockColumns.end());
        b.Values.insert(b.Values.end(), this->BlockValues.begin(), this->BlockValues.end());
        b.Start.push_back(static_cast<Index>(b.Columns.size()));
      }
      m.Rows.insert(m.Rows.end(), this->T.Dofs, this->T.Dofs + nt);
      for (int k = 0; k < nt; ++k)
      {
        m.Columns.push_back(static_cast<Column>(this->T.Dofs[k]));
      }
      m.Values.insert(m.Values.end(), this->Mtt.begin(), this->Mtt.end()); // (symmetric)
      m.Start.push_back(static_cast<Index>(m.Columns.size()));
      return;
    }
    for (int i = 0; i < nt; ++i)
    {
      if (mixed)
      {
        b.Rows.push_back(this->T.Dofs[i]);
        b.Columns.insert(b.Columns.end(), this->BlockColumns.begin(), this->BlockColumns.end());
        for (size_t slot = 0; slot < columns; ++slot)
        {
          b.Values.push_back(this->BlockValues[slot * nt + i]);
        }
        b.Start.push_back(static_cast<Index>(b.Columns.size()));
      }
      m.Rows.push_back(this->T.Dofs[i]);
      for (int k = 0; k < nt; ++k)
      {
        m.Columns.push_back(static_cast<Column>(this->T.Dofs[k]));
        m.Values.push_back(this->Mtt[static_cast<size_t>(i) * nt + k]);
      }
      m.Start.push_back(static_cast<Index>(m.Columns.size()));
    }
  }

  template <class SourceCell>
  void operator()(const Cell& t, const SourceCell& s, const Piece& piece)
  {
    if (t.Id != this->Current)
    {
      this->CloseCell();
      if (this->T.Key() != NodalFunctions::KeyOf(*this->Target, this->TargetSpace, t.Id))
      {
        this->AppendBlocks();
      }
      this->Current = t.Id;
      this->CurrentCell = t;
      this->CurrentMeasure = t.Measure;
      this->Covered = 0.0;
      this->T.Bind(*this->Target, this->TargetSpace, t.Id);
      if (!this->Open)
      {
        this->BlockColumns.clear();
        this->BlockValues.clear();
        this->BlockRhs.assign(static_cast<size_t>(this->T.Count) * this->Components, 0.0);
      }
      this->TargetPoints.clear();
      this->MttSum.assign(static_cast<size_t>(this->T.Count) * this->T.Count, 0.0);
      if (!this->Fields)
      {
        this->PendingCount = 0;
      }
    }
    if constexpr (QuadratureSupports<Intersector>)
    {
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
  }

  /**
   * Adds a piece whose source functions lie in the target's span
   * (InTargetBasis) to their pending sums; false, S bound to s, when they
   * do not. With Fields, a source parent met before in the open blocks
   * passed already (its functions' own conditions), and S is not bound.
   */
  template <class SourceCell>
  bool AddInTargetBasis(const Cell& t, const SourceCell& s, const Piece& piece)
  {
    constexpr bool volume = std::is_same<Intersector, TriangleIntersector>::value ||
      std::is_same<Intersector, TetrahedronIntersector>::value;
    Deferred* d = nullptr;
    if (this->Fields && ComparableMeasures(t.Measure, s.Measure))
    {
      d = this->FindPending(NodalFunctions::KeyOf(*this->Source, this->SourceSpace, s.Id));
    }
    if (!d)
    {
      this->S.Bind(*this->Source, this->SourceSpace, s.Id);
      if (!InTargetBasis(volume, this->T, this->S, t.Measure, s.Measure))
      {
        return false;
      }
      d = &this->PendingFor(s.Id);
    }
    if (this->Fields)
    {
      AddPieceRhs<Intersector>(piece, this->T, d->U.data(), this->Components, this->BlockRhs.data(),
        d->Integral.data(), this->TargetPoints);
    }
    else
    {
      AddPieceTargetMass<Intersector>(piece, this->T, d->G.data());
    }
    return true;
  }

  /// Adds one piece of the current target cell.
  template <class SourceCell>
  void Add(const Cell& t, const SourceCell& s, const Piece& piece)
  {
    if (this->Excluded && this->Excluded[s.Id])
    {
      return; // a hole in the source (no data there)
    }
    double o[D];
    double M[D + 1][D + 1];
    const double measure = Intersector::Moments(piece, o, M);
    if (!(measure > 0.0))
    {
      return; // the cells only touch
    }
    this->Covered += measure;
    // A piece's measure on the source cell per unit of its own (surfaces, curves).
    const double scale = Intersector::SourceScale(s, piece);
    if (!this->AddInTargetBasis(t, s, piece))
    {
      this->PieceMts.assign(static_cast<size_t>(this->T.Count) * this->S.Count, 0.0);
      double integrals[MaxNodalFunctions] = {};
      AddByPoints<Intersector>(piece, t, this->T, *this->Source, this->S, this->PieceMts.data(),
        nullptr, this->SourceFunctionCovered ? integrals : nullptr, &this->TargetPoints);
      if (this->Fields)
      {
        this->AddToRhs(integrals, scale);
      }
      else
      {
        this->MergeColumns(integrals, scale);
      }
    }
    ++this->Count;
    if (this->SourceCovered)
    {
      this->SourceCovered[s.Id] += measure * scale;
    }
    if (this->Pieces)
    {
      Intersector::AppendPiece(piece, t.Id, s.Id, *this->Pieces);
    }
  }
};

} // namespace mp

#endif
