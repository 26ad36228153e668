// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Space.h
 * @brief The function spaces a field lives in: P1 on points, P0 on cells,
 *        and DP1, linear on each cell (a reconstruction of cell data).
 *
 * A space says, for a cell (as the intersectors prepare it), which global
 * functions live on it (`CellDofs`), what they are on the cell as affine
 * functions of x - o (`Basis`, rows: constant, then gradient), and the
 * block of its mass matrix over a covered part with the given moments
 * (`MassFromMoments`). The assembler (MortarAssembler.h) needs nothing else,
 * so any pair of spaces gives the mixed and target mass matrices: P1 -> P1
 * (point data), P0 -> P0 (cell data), P0 -> P1 and P1 -> P0.
 *
 *  - P1: the continuous piecewise linear functions, one per point (the
 *    barycentric coordinates on each simplex).
 *  - P0: the piecewise constant functions, one per cell: per original cell
 *    when the mesh's simplices have parents (MeshView::Parent), so that a
 *    split quad or hexahedron keeps one value.
 *  - DP1: the discontinuous piecewise linear functions, one per corner of
 *    each simplex (function c (d + 1) + k: corner k of simplex c, in the
 *    mesh's corner order). A source space only: it carries a cell field
 *    reconstructed as a linear function on each cell
 *    (LinearReconstruction.h), given by its values at the corners.
 *
 * Adding a space (e.g. P1 on split cells with a tied centre point) means a
 * struct of this shape here and a case in MortarOperator's dispatch.
 */
#ifndef MeshProjection_Kernel_Space_h
#define MeshProjection_Kernel_Space_h

#include "Geometry/SourceSide.h"
#include "Mesh/MeshView.h"
#include "Transfer/MortarBlocks.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace mp
{
enum class SpaceType
{
  P1 = 0, ///< on points (point data)
  P0 = 1, ///< on cells (cell data)
  DP1 = 2 ///< on the corners of each simplex (reconstructed cell data; source only)
};

/// How many functions the space has on `mesh`.
inline Index SpaceSize(SpaceType type, const MeshView& mesh)
{
  switch (type)
  {
    case SpaceType::P1:
      return mesh.NumberOfPoints;
    case SpaceType::P0:
      return mesh.Parents();
    default:
      return mesh.NumberOfCells * mesh.CornersPerCell();
  }
}

template <int D>
struct P1Space
{
  static constexpr SpaceType Type = SpaceType::P1;
  static constexpr int Dofs = D + 1;
  static constexpr int K = D + 1;

  /// The functions on mesh cell c, from the mesh alone (any order).
  static void MeshCellDofs(const MeshView& mesh, Index c, Index (&dofs)[Dofs])
  {
    const CellCorners ids = mesh.Cell(c);
    for (int k = 0; k < Dofs; ++k)
    {
      dofs[k] = ids[k];
    }
  }
  /// The functions on a prepared cell, in the order of Basis().
  template <class Cell>
  static void CellDofs(const MeshView&, const Cell& c, Index (&dofs)[Dofs])
  {
    std::copy(c.Points, c.Points + Dofs, dofs);
  }
  /// The barycentric coordinates of `c` as affine functions of x - o.
  template <class Cell>
  static void Basis(const Cell& c, const double* o, double (&l)[Dofs][K])
  {
    double shift[D];
    for (int a = 0; a < D; ++a)
    {
      shift[a] = o[a] - c.X[0][a];
    }
    for (int r = 0; r < D; ++r)
    {
      double constant = 0.0;
      for (int a = 0; a < D; ++a)
      {
        constant += c.Inverse[r][a] * shift[a];
        l[r + 1][a + 1] = c.Inverse[r][a];
      }
      l[r + 1][0] = constant;
    }
    for (int k = 0; k < K; ++k)
    {
      double sum = 0.0;
      for (int r = 1; r < Dofs; ++r)
      {
        sum += l[r][k];
      }
      l[0][k] = (k == 0 ? 1.0 : 0.0) - sum;
    }
  }
  /**
   * The mass block of `c` over its covered part, from that part's moments
   * about the corner c.X[0]. A cell covered whole (moments[0][0] equals its
   * measure within 1e-12) gets the exact element mass matrix,
   * measure (1 + delta_ik) d! / (d + 2)!, free of any cancellation.
   */
  template <class Cell>
  static void MassFromMoments(const Cell& c, const double (&moments)[K][K], double (&m)[Dofs][Dofs])
  {
    const double covered = moments[0][0];
    if (std::fabs(covered - c.Measure) <= 1e-12 * c.Measure)
    {
      const double unit = covered / ((D + 1) * (D + 2)); // d! / (d + 2)! = 1 / ((d + 1)(d + 2))
      for (int i = 0; i < Dofs; ++i)
      {
        for (int k = 0; k < Dofs; ++k)
        {
          m[i][k] = unit * (i == k ? 2.0 : 1.0);
        }
      }
      return;
    }
    double l[Dofs][K];
    Basis(c, c.X[0], l);
    for (auto& row : m)
    {
      std::fill(row, row + Dofs, 0.0);
    }
    AddTargetBlock<Dofs, K>(l, moments, m);
  }
};

template <int D>
struct P0Space
{
  static constexpr SpaceType Type = SpaceType::P0;
  static constexpr int Dofs = 1;
  static constexpr int K = D + 1;

  static void MeshCellDofs(const MeshView& mesh, Index c, Index (&dofs)[Dofs])
  {
    dofs[0] = mesh.ParentOf(c);
  }
  template <class Cell>
  static void CellDofs(const MeshView& mesh, const Cell& c, Index (&dofs)[Dofs])
  {
    dofs[0] = mesh.ParentOf(c.Id);
  }
  /// The constant 1.
  template <class Cell>
  static void Basis(const Cell&, const double*, double (&l)[Dofs][K])
  {
    std::fill(l[0], l[0] + K, 0.0);
    l[0][0] = 1.0;
  }
  /// The covered measure.
  template <class Cell>
  static void MassFromMoments(const Cell&, const double (&moments)[K][K], double (&m)[Dofs][Dofs])
  {
    m[0][0] = moments[0][0];
  }
};
/**
 * P1 of a source cell seen on a lower-dimensional target (traces,
 * Geometry/TraceIntersector.h): its N functions are given on the piece
 * (AffineCell) as affine functions of the target frame's D coordinates.
 * Only a source space: it has no mass matrix of its own.
 */
template <int N, int D>
struct RestrictedP1Space
{
  static constexpr SpaceType Type = SpaceType::P1;
  static constexpr int Dofs = N;
  static constexpr int K = D + 1;

  template <class Cell>
  static void CellDofs(const MeshView&, const Cell& c, Index (&dofs)[Dofs])
  {
    std::copy(c.Points, c.Points + Dofs, dofs);
  }
  template <class Cell>
  static void Basis(const Cell& c, const double* o, double (&l)[Dofs][K])
  {
    for (int j = 0; j < Dofs; ++j)
    {
      double value = c.Affine[j][0];
      for (int a = 0; a < D; ++a)
      {
        value += c.Affine[j][a + 1] * o[a];
        l[j][a + 1] = c.Affine[j][a + 1];
      }
      l[j][0] = value;
    }
  }
};

/**
 * DP1 on the cells of `P1` (a P1 space as the pieces see the source:
 * SourceP1Of): the same functions on each cell, but each cell's own, so
 * that a field may jump between cells. The prepared cells may order their
 * corners otherwise than the mesh (e.g. counterclockwise): each function
 * is named by its corner's place in the mesh's cell.
 */
template <class P1>
struct DiscontinuousP1Space
{
  static constexpr SpaceType Type = SpaceType::DP1;
  static constexpr int Dofs = P1::Dofs;
  static constexpr int K = P1::K;

  template <class Cell>
  static void CellDofs(const MeshView& mesh, const Cell& c, Index (&dofs)[Dofs])
  {
    const CellCorners corners = mesh.Cell(c.Id);
    const Index first = c.Id * Dofs;
    for (int k = 0; k < Dofs; ++k)
    {
      int place = 0;
      while (place + 1 < Dofs && corners[place] != c.Points[k])
      {
        ++place;
      }
      assert(corners[place] == c.Points[k] && "a prepared cell's corners are the mesh cell's");
      dofs[k] = first + place;
    }
  }
  template <class Cell>
  static void Basis(const Cell& c, const double* o, double (&l)[Dofs][K])
  {
    P1::Basis(c, o, l);
  }
};

/// The P1 space of the source as intersector I's pieces see it: P1Space,
/// or RestrictedP1Space for a trace (a volume source).
template <class I, bool Trace = IsTrace<I>>
struct SourceP1Of
{
  using type = P1Space<I::Dimension>;
};

template <class I>
struct SourceP1Of<I, true>
{
  using type = RestrictedP1Space<SourceSideOf<I>::type::Corners, I::Dimension>;
};
} // namespace mp

#endif
