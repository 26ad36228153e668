// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PieceQuadrature.h
 * @brief One intersection piece's integrals of the cells' own functions
 *        (NodalSpace.h) by quadrature, for QuadratureAssembler.h.
 *
 * A piece is cut into simplices (ForEachPieceSimplex: the polygon fanned
 * from its first vertex, the polyhedron's tetrahedra, the interval), each
 * integrated with a rule of SimplexQuadrature.h at whose points the two
 * cells' functions are evaluated (on surfaces and curves at the points of
 * the two facets the piece's point stands for: PiecePlaces). An affine
 * side (a straight or linear cell) is read from its coordinates at each
 * simplex's corners, combined per point, with no inverse map per point.
 *
 * AddByPoints evaluates both sides at every point. Where the source
 * functions lie in the target cell's span (InTargetBasis: both affine, the
 * target's space complete to the source's degree) their mixed block is the
 * target mass block times their values at the target's nodes
 * (AddPieceTargetMass, SourceInTargetBasis): only the target side is
 * evaluated at the points, and the product can be taken once per source
 * parent. Both are exact on straight cells. ElementMass gives a whole
 * affine cell's mass block by the rule on the cell.
 */
#ifndef MeshProjection_Kernel_PieceQuadrature_h
#define MeshProjection_Kernel_PieceQuadrature_h

#include "Geometry/SegmentIntersector.h"
#include "Geometry/SimplexQuadrature.h"
#include "Geometry/SurfaceIntersector.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TraceIntersector.h"
#include "Geometry/TriangleIntersector.h"
#include "Transfer/NodalSpace.h"

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

namespace mp
{
/// Whether intersector I's pieces are intervals of a target segment's axis.
template <class I>
constexpr bool OnSegments = std::is_same<I, SegmentIntersector>::value ||
  std::is_same<I, CurveTraceIntersector<TriangleIntersector>>::value ||
  std::is_same<I, CurveTraceIntersector<TetrahedronIntersector>>::value;

/// Whether the quadrature assembler takes intersector I's pieces (all).
template <class I>
constexpr bool QuadratureSupports =
  std::is_same<I, TriangleIntersector>::value || std::is_same<I, TetrahedronIntersector>::value ||
  std::is_same<I, SurfaceIntersector>::value || std::is_same<I, SegmentIntersector>::value ||
  std::is_same<I, SurfaceTraceIntersector>::value || OnSegments<I>;

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
  else if constexpr (OnSegments<I>)
  {
    if (piece.NumberOfVertices == 2)
    {
      const double* corners[2] = { piece.X[0], piece.X[1] };
      f(corners, piece.X[1][0] - piece.X[0][0]);
    }
  }
  else if constexpr (std::is_same<I, SurfaceTraceIntersector>::value)
  {
    for (int p = 0; p < piece.NumberOfParts; ++p)
    {
      ForEachPieceSimplex<TriangleIntersector>(piece.Parts[p], f);
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
 * same barycentric coordinates on the source's projection, Piece::Projected);
 * for traces the target's point in space on both (it lies in the source).
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
  else if constexpr (std::is_same<I, SurfaceTraceIntersector>::value)
  {
    for (int a = 0; a < 3; ++a) // (a trace lies in the source volume: the same point)
    {
      onTarget[a] = onSource[a] = t.Origin[a] + x[0] * t.Axis[0][a] + x[1] * t.Axis[1][a];
    }
  }
  else if constexpr (OnSegments<I>)
  {
    for (int a = 0; a < 3; ++a)
    {
      onTarget[a] = onSource[a] = t.Origin[a] + x[0] * t.Axis[a];
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
 * The highest degree of the pieces' rules. Products of the tensor-product
 * and pyramid cells' functions reach degree 8 to 12 (a 27-node hexahedron
 * by itself), whose rules take 125 to 343 points per tetrahedron of a piece;
 * capped at 6 (24 points), M_ts and M_tt are inexact for them alone but
 * come from the same points, so every field of the target's space (a
 * quadratic on straight cells) is still reproduced, and each function's
 * own integral (degree <= 6) is still exact.
 */
constexpr int MaxPieceDegree = 6;

/**
 * Sums one piece's blocks by quadrature, both sides' functions at every
 * point: Mts[i][j] += int phi_i psi_j, Mtt[i][k] += int phi_i phi_k
 * (row-major, ft.Count wide; or, with `targetPoints`, the weight and the
 * phi_i of every point appended there for TargetMassFromPoints), and, with
 * `sourceIntegrals`, the integrals of the psi_j; over the piece as the
 * target sees it (a surface's or curve's: on the target facet). The
 * functions ft and fs bound to the piece's cells t and (of `source`) s.
 * The reference the assembled matrices are checked against.
 */
template <class I>
void AddByPoints(const typename I::Piece& piece, const typename I::Cell& t,
  const NodalFunctions& ft, const MeshView& source, const NodalFunctions& fs, double* Mts,
  double* Mtt, double* sourceIntegrals, std::vector<double>* targetPoints)
{
  constexpr int D = I::Dimension;
  const int nt = ft.Count;
  const int ns = fs.Count;
  const int degree = std::max(ft.Degree + fs.Degree, std::max(2 * ft.Degree, 1));
  const SimplexRule& rule = SimplexQuadrature(D, std::min(degree, MaxPieceDegree));
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

/// G[i][k] += w phi_i phi_k for k >= i (the upper triangle), N functions
/// (N > 0: known at compile time, so the loops unroll; 0: n of them).
template <int N>
inline void AddUpperProduct(double w, const double* phi, int n, double* G)
{
  const int nt = N > 0 ? N : n;
  for (int i = 0; i < nt; ++i)
  {
    const double wi = w * phi[i];
    for (int k = i; k < nt; ++k)
    {
      G[i * nt + k] += wi * phi[k];
    }
  }
}

/**
 * Adds the piece's target mass block G[i][k] += int phi_i phi_k (ft affine,
 * row-major; the upper triangle k >= i only, the rest left as it is), by
 * the rule of degree 2 ft.Degree (exact). With SourceInTargetBasis it
 * gives the piece's mixed block too.
 */
template <class I>
void AddPieceTargetMass(const typename I::Piece& piece, const NodalFunctions& ft, double* G)
{
  constexpr int D = I::Dimension;
  const int nt = ft.Count;
  const SimplexRule& rule = SimplexQuadrature(D, std::max(2 * ft.Degree, 1));
  ForEachPieceSimplex<I>(piece, [&](const double* const* corners, double measure) {
    double corner[D + 1][4];
    int count = 0;
    for (int k = 0; k <= D; ++k)
    {
      count = ft.Coordinates(corners[k], corner[k]);
    }
    for (int q = 0; q < rule.Points; ++q)
    {
      const double* b = &rule.Barycentric[static_cast<size_t>(q) * (D + 1)];
      double phi[MaxNodalFunctions];
      ft.ValuesAt(Combination<D>(b, corner, count).data(), phi);
      const double w = rule.Weight[q] * measure;
      switch (nt) // (the usual counts: tetrahedra's and triangles' P2 and P1)
      {
        case 10:
          AddUpperProduct<10>(w, phi, nt, G);
          break;
        case 6:
          AddUpperProduct<6>(w, phi, nt, G);
          break;
        case 4:
          AddUpperProduct<4>(w, phi, nt, G);
          break;
        default:
          AddUpperProduct<0>(w, phi, nt, G);
      }
    }
  });
}

/// One point's share of AddPieceRhs: integral[m] += w phi_m, and
/// rhs[i][c] += w u_c phi_i with u_c = sum_m phi_m U[m][c], N functions
/// (N > 0: known at compile time, so the loops unroll; 0: n of them).
template <int N>
inline void AddPointRhs(double w, const double* phi, int n, const double* U, int components,
  double* rhs, double* integral)
{
  const int nt = N > 0 ? N : n;
  for (int m = 0; m < nt; ++m)
  {
    integral[m] += w * phi[m];
  }
  for (int c = 0; c < components; ++c)
  {
    double u = 0.0;
    for (int m = 0; m < nt; ++m)
    {
      u += phi[m] * U[m * components + c];
    }
    const double wu = w * u;
    for (int i = 0; i < nt; ++i)
    {
      rhs[i * components + c] += wu * phi[i];
    }
  }
}

/**
 * The right-hand sides of one piece where the source fields lie in the
 * target cell's span (InTargetBasis), for a single use (fields given):
 * rhs[i][c] += int phi_i u_c with u_c = sum_m phi_m U[m][c] (U: the
 * fields' values at the target's nodes, nt x components), and
 * integral[m] += int phi_m (which gives the source functions' integrals,
 * SourceInTargetBasis's column sums); each point's weight and phi_i
 * appended to `targetPoints` for TargetMassFromPoints. The rule of degree
 * 2 ft.Degree (exact on straight cells), ft affine; M_ts and the target
 * mass block are never formed.
 */
template <class I>
void AddPieceRhs(const typename I::Piece& piece, const NodalFunctions& ft, const double* U,
  int components, double* rhs, double* integral, std::vector<double>& targetPoints)
{
  constexpr int D = I::Dimension;
  const int nt = ft.Count;
  const SimplexRule& rule = SimplexQuadrature(D, std::max(2 * ft.Degree, 1));
  ForEachPieceSimplex<I>(piece, [&](const double* const* corners, double measure) {
    double corner[D + 1][4];
    int count = 0;
    for (int k = 0; k <= D; ++k)
    {
      count = ft.Coordinates(corners[k], corner[k]);
    }
    // (The points' room taken once per simplex, their values written in place.)
    const size_t stride = static_cast<size_t>(nt) + 1;
    const size_t first = targetPoints.size();
    targetPoints.resize(first + stride * rule.Points);
    for (int q = 0; q < rule.Points; ++q)
    {
      const double* b = &rule.Barycentric[static_cast<size_t>(q) * (D + 1)];
      double* point = &targetPoints[first + stride * q];
      double* phi = point + 1;
      ft.ValuesAt(Combination<D>(b, corner, count).data(), phi);
      const double w = rule.Weight[q] * measure;
      point[0] = w;
      switch (nt) // (the usual counts: tetrahedra's and triangles' P2 and P1)
      {
        case 10:
          AddPointRhs<10>(w, phi, nt, U, components, rhs, integral);
          break;
        case 6:
          AddPointRhs<6>(w, phi, nt, U, components, rhs, integral);
          break;
        case 4:
          AddPointRhs<4>(w, phi, nt, U, components, rhs, integral);
          break;
        default:
          AddPointRhs<0>(w, phi, nt, U, components, rhs, integral);
      }
    }
  });
}

/// Copies the upper triangle of the n x n matrix G onto its lower one.
inline void MirrorUpper(int n, double* G)
{
  for (int i = 0; i < n; ++i)
  {
    for (int k = 0; k < i; ++k)
    {
      G[i * n + k] = G[k * n + i];
    }
  }
}

/// InTargetBasis's condition on the two cells' measures.
inline bool ComparableMeasures(double targetMeasure, double sourceMeasure)
{
  return 100.0 * sourceMeasure >= targetMeasure;
}

/**
 * Whether source functions fs lie in the span of target functions ft, so
 * that SourceInTargetBasis gives their mixed block from the target mass
 * block: both cells affine (straight or linear), the target's point
 * functions a complete polynomial space (P1, or a straight simplex
 * parent's P2) of at least the source's degree, on triangles in the plane
 * or tetrahedra (`volume`); and the source cell not far smaller than the
 * target (its functions are read at the target's nodes, whose distance
 * would amplify their rounding).
 */
inline bool InTargetBasis(bool volume, const NodalFunctions& ft, const NodalFunctions& fs,
  double targetMeasure, double sourceMeasure)
{
  return volume && ft.Space == SpaceType::P1 && ft.IsAffine() && fs.IsAffine() &&
    fs.Degree <= ft.Degree && ft.Degree <= 2 && ComparableMeasures(targetMeasure, sourceMeasure);
}

/**
 * Mts[i][j] += int phi_i psi_j from G[i][m] = int phi_i phi_m over the same
 * part (InTargetBasis: psi_j = sum_m psi_j(X_m) phi_m over the target's
 * nodes X_m, points of `target`), and, with `sourceIntegrals`, the
 * integrals of the psi_j (the phi_i sum to 1: Mts's column sums).
 */
inline void SourceInTargetBasis(const MeshView& target, const NodalFunctions& ft,
  const NodalFunctions& fs, const double* G, double* Mts, double* sourceIntegrals)
{
  const int nt = ft.Count;
  const int ns = fs.Count;
  double psi[MaxNodalFunctions * MaxNodalFunctions]; // row m: the psi_j at node m
  for (int m = 0; m < nt; ++m)
  {
    fs.Values(target.Point(ft.Dofs[m]), psi + m * ns);
  }
  for (int i = 0; i < nt; ++i)
  {
    for (int m = 0; m < nt; ++m)
    {
      const double g = G[i * nt + m];
      for (int j = 0; j < ns; ++j)
      {
        const double v = g * psi[m * ns + j];
        Mts[i * ns + j] += v;
        if (sourceIntegrals)
        {
          sourceIntegrals[j] += v;
        }
      }
    }
  }
}

/**
 * The values psi_j(X_m) of source functions fs at the target's nodes X_m
 * (points of `target`; row m, fs.Count wide), and from them the source
 * fields `fields` (source functions x components) there:
 * U[m][c] = sum_j psi_j(X_m) u_j,c (InTargetBasis: the fields in the
 * target's basis).
 */
inline void SourceAtTargetNodes(const MeshView& target, const NodalFunctions& ft,
  const NodalFunctions& fs, const double* fields, int components, double* psi, double* U)
{
  const int nt = ft.Count;
  const int ns = fs.Count;
  for (int m = 0; m < nt; ++m)
  {
    fs.Values(target.Point(ft.Dofs[m]), psi + m * ns);
    for (int c = 0; c < components; ++c)
    {
      double u = 0.0;
      for (int j = 0; j < ns; ++j)
      {
        u += psi[m * ns + j] * fields[fs.Dofs[j] * components + c];
      }
      U[m * components + c] = u;
    }
  }
}

/// Mtt[i][k] += the sum over `points` (weight, then nt values each) of w
/// phi_i phi_k (Mtt symmetric).
inline void TargetMassFromPoints(const std::vector<double>& points, int nt, double* Mtt)
{
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

} // namespace mp

#endif
