// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file QuadratureAssembler.h
 * @brief From pieces to matrices by quadrature: the mortar integrals of
 *        functions that are not affine on a piece (NodalSpace.h).
 *
 * The search hands every (target cell, source cell, piece) to a
 * QuadratureAssembler, as to a MortarAssembler. The piece is cut into
 * simplices (in the plane its convex polygon fanned from its first vertex,
 * in space its own tetrahedra), and on each the rule of degree
 * max(dt + ds, 2 dt) (SimplexQuadrature; dt, ds the two cells' degrees:
 * NodalDegree for a second-order parent, 1 for P1 and DP1, 0 for P0)
 * integrates phi_i psi_j and phi_i phi_k, the two cells' functions
 * evaluated at its points (NodalFunctions). Exact for straight cells, whose
 * functions are polynomials of those degrees; on a curved cell the
 * functions are its true isoparametric ones and the rule's error is that
 * of their polynomial approximation on the piece.
 *
 * Both M_ts and M_tt come from the pieces (on a curved cell the covered
 * part is what the pieces measure), but for an affine cell (straight or
 * linear) covered whole, whose M_tt block the rule on the cell gives
 * exactly, once (ElementMass): the pieces' points are kept per cell until
 * its last piece says which. When a target cell's last piece has come, its
 * blocks go to the task's MixedBlocks, one block per cell when every
 * target cell has as many functions (RowsPerBlock: UniformFunctionCount),
 * else one per target function (RowsPerBlock 1), M_ts's
 * into Blocks and M_tt's into MassBlocks; M_tt is then assembled from
 * these with MixedMatrix.h (AssembleNodalTargetMass). The covered
 * fractions, the source cover, the kept pieces and the counts are those of
 * MortarAssembler.
 *
 * Triangles in the plane, tetrahedra, surfaces and curves: a surface's or
 * curve's piece lies in the target facet's frame, where each quadrature
 * point is taken back to the target facet and to the source facet it is
 * the image of (PiecePlaces), the functions evaluated there. Not the
 * traces (QuadratureSupports).
 */
#ifndef MeshProjection_Kernel_QuadratureAssembler_h
#define MeshProjection_Kernel_QuadratureAssembler_h

#include "Geometry/IntersectionPieces.h"
#include "Geometry/SegmentIntersector.h"
#include "Geometry/SimplexQuadrature.h"
#include "Geometry/SurfaceIntersector.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"
#include "Transfer/MixedMatrix.h"
#include "Transfer/NodalSpace.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace mp
{
/// Whether the quadrature assembler takes intersector I's pieces (not the traces').
template <class I>
constexpr bool QuadratureSupports =
  std::is_same<I, TriangleIntersector>::value || std::is_same<I, TetrahedronIntersector>::value ||
  std::is_same<I, SurfaceIntersector>::value || std::is_same<I, SegmentIntersector>::value;

/**
 * Calls f(corners, measure) for each simplex of `piece` in the
 * intersector's D coordinates (corners: D + 1 pointers to D coordinates;
 * measure signed, as the piece's own): a polygon fanned from its first
 * vertex, a polyhedron's tetrahedra, an interval.
 */
template <class I, class F>
void ForEachPieceSimplex(const typename I::Piece& piece, F&& f)
{
  if constexpr (std::is_same<I, TetrahedronIntersector>::value)
  {
    for (int i = 0; i < piece.NumberOfTetrahedra; ++i)
    {
      const double* corners[4];
      for (int k = 0; k < 4; ++k)
      {
        corners[k] = piece.Points[piece.Corner[i][k]];
      }
      f(corners, piece.Volume[i]);
    }
  }
  else if constexpr (std::is_same<I, SegmentIntersector>::value)
  {
    if (piece.NumberOfVertices == 2)
    {
      const double* corners[2] = { piece.X[0], piece.X[1] };
      f(corners, piece.X[1][0] - piece.X[0][0]);
    }
  }
  else
  {
    const double* o = piece.X[0];
    for (int i = 1; i + 1 < piece.NumberOfVertices; ++i)
    {
      const double* p = piece.X[i];
      const double* q = piece.X[i + 1];
      const double area = 0.5 * ((p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0]));
      const double* corners[3] = { o, p, q };
      f(corners, area);
    }
  }
}

/**
 * Where point x of a piece (in intersector I's D coordinates) lies on the
 * target mesh (`onTarget`) and on the source mesh (`onSource`), in each
 * mesh's SpaceDimension coordinates: the same point for volumes; for
 * surfaces and curves the point of the target facet or segment in space,
 * and the point of the source facet or segment whose image it is (the
 * same barycentric coordinates on the source's projection, Piece::Projected).
 */
template <class I>
void PiecePlaces(const typename I::Cell& t, const typename I::Piece& piece, const MeshView& source,
  const double* x, double* onTarget, double* onSource)
{
  if constexpr (std::is_same<I, SurfaceIntersector>::value)
  {
    const TriangleIntersector::Cell& p = piece.Projected;
    const double u = x[0] - p.X[0][0], v = x[1] - p.X[0][1];
    const double l[3] = { 0.0, p.Inverse[0][0] * u + p.Inverse[0][1] * v,
      p.Inverse[1][0] * u + p.Inverse[1][1] * v };
    for (int a = 0; a < 3; ++a)
    {
      onTarget[a] = t.Origin[a] + x[0] * t.Axis[0][a] + x[1] * t.Axis[1][a];
      onSource[a] = (1.0 - l[1] - l[2]) * source.Point(p.Points[0])[a] +
        l[1] * source.Point(p.Points[1])[a] + l[2] * source.Point(p.Points[2])[a];
    }
  }
  else if constexpr (std::is_same<I, SegmentIntersector>::value)
  {
    const SegmentIntersector::Cell& p = piece.Projected;
    const double l = (x[0] - p.X[0][0]) * p.Inverse[0][0];
    for (int a = 0; a < 3; ++a)
    {
      onTarget[a] = t.Origin[a] + x[0] * t.Axis[a];
      onSource[a] = (1.0 - l) * p.Corner[0][a] + l * p.Corner[1][a];
    }
  }
  else
  {
    for (int a = 0; a < I::Dimension; ++a)
    {
      onTarget[a] = onSource[a] = x[a];
    }
  }
}

/// sum_k b[k] corner[k][0 .. count).
template <int D>
inline std::array<double, 4> Combination(
  const double* b, const double (&corner)[D + 1][4], int count)
{
  std::array<double, 4> c{};
  for (int k = 0; k <= D; ++k)
  {
    for (int a = 0; a < count; ++a)
    {
      c[a] += b[k] * corner[k][a];
    }
  }
  return c;
}

/**
 * Sums one piece's blocks by quadrature: Mts[i][j] += int phi_i psi_j,
 * Mtt[i][k] += int phi_i phi_k (row-major, ft.Count wide; or, with
 * `targetPoints`, the weight and the phi_i of every point appended there
 * for TargetMassFromPoints), and, with `sourceIntegrals`, the integrals of
 * the psi_j; over the piece as the target sees it (a surface's or curve's:
 * on the target facet). The functions ft and fs bound to the piece's cells
 * t and (of `source`) s. The reference the assembled matrices are checked
 * against, and the assembler's own step.
 */
template <class I>
void AddQuadratureBlocks(const typename I::Piece& piece, const typename I::Cell& t,
  const NodalFunctions& ft, const MeshView& source, const NodalFunctions& fs, double* Mts,
  double* Mtt, double* sourceIntegrals, std::vector<double>* targetPoints = nullptr)
{
  constexpr int D = I::Dimension;
  const int nt = ft.Count;
  const int ns = fs.Count;
  const int degree = std::max(ft.Degree + fs.Degree, std::max(2 * ft.Degree, 1));
  const SimplexRule& rule = SimplexQuadrature(D, std::min(degree, MaxSimplexDegree));
  ForEachPieceSimplex<I>(piece, [&](const double* const* corners, double measure) {
    // An affine side's coordinates at the simplex's corners: a point's are
    // then their barycentric combination (no inverse map per point).
    double cornerT[D + 1][4], cornerS[D + 1][4];
    int countT = 0, countS = 0;
    for (int k = 0; k <= D && (ft.IsAffine() || fs.IsAffine()); ++k)
    {
      double onTarget[3], onSource[3];
      PiecePlaces<I>(t, piece, source, corners[k], onTarget, onSource);
      countT = ft.IsAffine() ? ft.Coordinates(onTarget, cornerT[k]) : 0;
      countS = fs.IsAffine() ? fs.Coordinates(onSource, cornerS[k]) : 0;
    }
    for (int q = 0; q < rule.Points; ++q)
    {
      const double* b = &rule.Barycentric[static_cast<size_t>(q) * (D + 1)];
      double phi[MaxNodalFunctions];
      double psi[MaxNodalFunctions];
      if (!ft.IsAffine() || !fs.IsAffine())
      {
        double x[D] = {};
        for (int k = 0; k <= D; ++k)
        {
          for (int a = 0; a < D; ++a)
          {
            x[a] += b[k] * corners[k][a];
          }
        }
        double onTarget[3], onSource[3];
        PiecePlaces<I>(t, piece, source, x, onTarget, onSource);
        if (!ft.IsAffine())
        {
          ft.Values(onTarget, phi);
        }
        if (!fs.IsAffine())
        {
          fs.Values(onSource, psi);
        }
      }
      if (ft.IsAffine())
      {
        ft.ValuesAt(Combination<D>(b, cornerT, countT).data(), phi);
      }
      if (fs.IsAffine())
      {
        fs.ValuesAt(Combination<D>(b, cornerS, countS).data(), psi);
      }
      const double w = rule.Weight[q] * measure;
      for (int i = 0; i < nt; ++i)
      {
        const double wi = w * phi[i];
        for (int j = 0; j < ns; ++j)
        {
          Mts[i * ns + j] += wi * psi[j];
        }
      }
      if (targetPoints)
      {
        targetPoints->push_back(w);
        targetPoints->insert(targetPoints->end(), phi, phi + nt);
      }
      else
      {
        for (int i = 0; i < nt; ++i)
        {
          for (int k = 0; k < nt; ++k)
          {
            Mtt[i * nt + k] += w * phi[i] * phi[k];
          }
        }
      }
      for (int j = 0; sourceIntegrals && j < ns; ++j)
      {
        sourceIntegrals[j] += w * psi[j];
      }
    }
  });
}

/// Mtt[i][k] = sum over `points` (weight, then nt values each) of w phi_i phi_k.
inline void TargetMassFromPoints(const std::vector<double>& points, int nt, double* Mtt)
{
  std::fill(Mtt, Mtt + nt * nt, 0.0);
  for (size_t p = 0; p < points.size(); p += static_cast<size_t>(nt) + 1)
  {
    const double w = points[p];
    const double* phi = &points[p + 1];
    for (int i = 0; i < nt; ++i)
    {
      const double wi = w * phi[i];
      for (int k = i; k < nt; ++k)
      {
        Mtt[i * nt + k] += wi * phi[k];
      }
    }
  }
  for (int i = 0; i < nt; ++i)
  {
    for (int k = 0; k < i; ++k)
    {
      Mtt[i * nt + k] = Mtt[k * nt + i];
    }
  }
}

/**
 * Mtt[i][k] = int phi_i phi_k over kernel cell c of `mesh` whole (of
 * `measure`), f bound to it: the rule of degree 2 f.Degree on the simplex,
 * exact where f is affine (a straight or linear parent).
 */
inline void ElementMass(
  const MeshView& mesh, Index c, double measure, const NodalFunctions& f, double* Mtt)
{
  const int d = mesh.CellDimension;
  const int nt = f.Count;
  const SimplexRule& rule =
    SimplexQuadrature(d, std::min(std::max(2 * f.Degree, 1), MaxSimplexDegree));
  const CellCorners corners = mesh.Cell(c);
  std::fill(Mtt, Mtt + nt * nt, 0.0);
  for (int q = 0; q < rule.Points; ++q)
  {
    const double* b = &rule.Barycentric[static_cast<size_t>(q) * (d + 1)];
    double x[3] = { 0.0, 0.0, 0.0 };
    for (int k = 0; k <= d; ++k)
    {
      for (int a = 0; a < mesh.SpaceDimension; ++a)
      {
        x[a] += b[k] * mesh.Point(corners[k])[a];
      }
    }
    double phi[MaxNodalFunctions];
    f.Values(x, phi);
    const double w = rule.Weight[q] * measure;
    for (int i = 0; i < nt; ++i)
    {
      for (int k = i; k < nt; ++k)
      {
        Mtt[i * nt + k] += w * phi[i] * phi[k];
      }
    }
  }
  for (int i = 0; i < nt; ++i)
  {
    for (int k = 0; k < i; ++k)
    {
      Mtt[i * nt + k] = Mtt[k * nt + i];
    }
  }
}

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
  MixedBlocks* Blocks = nullptr;     ///< this task's M_ts blocks (one per target function)
  MixedBlocks* MassBlocks = nullptr; ///< this task's M_tt blocks (one per target function)
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

  Index Current = -1; ///< the target cell whose pieces are coming
  double CurrentMeasure = 0.0;
  double Covered = 0.0;             ///< its pieces' measure so far
  NodalFunctions T;                 ///< its functions
  NodalFunctions S;                 ///< the current source cell's
  std::vector<Column> BlockColumns; ///< source functions its pieces met
  std::vector<double> BlockValues;  ///< T.Count per column
  std::vector<double> Mtt;          ///< T.Count x T.Count, formed by Flush
  std::vector<double> TargetPoints; ///< its pieces' points: weight, then T.Count values
  std::vector<double> PieceMts;     ///< one piece's, T.Count x S.Count

  void Flush()
  {
    if (this->Current < 0)
    {
      return;
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
    // M_tt's block: the cell's own where that is exact (an affine cell
    // covered whole, as the linear path's element matrix), else the
    // pieces' points'.
    this->Mtt.resize(static_cast<size_t>(nt) * nt);
    if (this->T.IsAffine() &&
      std::fabs(this->Covered - this->CurrentMeasure) <= 1e-12 * this->CurrentMeasure)
    {
      ElementMass(*this->Target, current, this->CurrentMeasure, this->T, this->Mtt.data());
    }
    else
    {
      TargetMassFromPoints(this->TargetPoints, nt, this->Mtt.data());
    }
    this->AppendBlocks(nt);
  }

  /// The current cell's blocks into the task's: one block of all its rows
  /// when the blocks have that many (RowsPerBlock), else one per row.
  void AppendBlocks(int nt)
  {
    MixedBlocks& b = *this->Blocks;
    MixedBlocks& m = *this->MassBlocks;
    const size_t columns = this->BlockColumns.size();
    if (b.RowsPerBlock == nt)
    {
      b.Rows.insert(b.Rows.end(), this->T.Dofs, this->T.Dofs + nt);
      b.Columns.insert(b.Columns.end(), this->BlockColumns.begin(), this->BlockColumns.end());
      b.Values.insert(b.Values.end(), this->BlockValues.begin(), this->BlockValues.end());
      b.Start.push_back(static_cast<Index>(b.Columns.size()));
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
      b.Rows.push_back(this->T.Dofs[i]);
      b.Columns.insert(b.Columns.end(), this->BlockColumns.begin(), this->BlockColumns.end());
      for (size_t slot = 0; slot < columns; ++slot)
      {
        b.Values.push_back(this->BlockValues[slot * nt + i]);
      }
      b.Start.push_back(static_cast<Index>(b.Columns.size()));
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
      this->Flush();
      this->Current = t.Id;
      this->CurrentMeasure = t.Measure;
      this->Covered = 0.0;
      this->T.Bind(*this->Target, this->TargetSpace, t.Id);
      this->BlockColumns.clear();
      this->BlockValues.clear();
      this->TargetPoints.clear();
    }
    if constexpr (QuadratureSupports<Intersector>)
    {
      this->Add(t, s, piece);
    }
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
    this->S.Bind(*this->Source, this->SourceSpace, s.Id);
    const int nt = this->T.Count;
    const int ns = this->S.Count;
    // A piece's measure on the source cell per unit of its own (surfaces, curves).
    const double scale = Intersector::SourceScale(s, piece);
    this->PieceMts.assign(static_cast<size_t>(nt) * ns, 0.0);
    double integrals[MaxNodalFunctions] = {};
    AddQuadratureBlocks<Intersector>(piece, t, this->T, *this->Source, this->S,
      this->PieceMts.data(), nullptr, this->SourceFunctionCovered ? integrals : nullptr,
      &this->TargetPoints);
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
