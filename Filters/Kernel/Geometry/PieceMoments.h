// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PieceMoments.h
 * @brief The moments of a piece of two tetrahedra, summed over the
 *        tetrahedra it is split into (private to TetrahedronIntersector and
 *        its tests).
 *
 * A piece's moments (its volume, first and second moments about a point:
 * TetrahedronIntersector::Piece::M) are what the assembly integrates the
 * basis functions with. Both ways a piece is made (the decomposition of a
 * vertex graph, VertexGraphFaces.h, and the tetrahedra of the reference
 * clipper, TetrahedronIntersector::SumMoments) add them here, tetrahedron
 * by tetrahedron with the same operations, so the two give the same
 * moments for the same tetrahedra.
 */
#ifndef MeshProjection_Kernel_PieceMoments_h
#define MeshProjection_Kernel_PieceMoments_h

#include "Geometry/TetrahedronIntersector.h"

namespace mp
{
namespace clipping
{
/**
 * Adds a tetrahedron's moments about a point o to m0, m1, m2 (upper
 * triangle): `p` holds its corners minus o, all four, or three when the
 * fourth is o itself. On a tetrahedron of volume V, the integral of x_i is
 * V mean(x_i) and of x_i x_j V/20 (sum_a x_ai x_aj + sum_a x_ai sum_a x_aj).
 */
template <int N>
inline void AddTetrahedronMoments(
  double volume, const double (&p)[N][3], double& m0, double (&m1)[3], double (&m2)[3][3])
{
  static_assert(N == 3 || N == 4, "corners about o, without o itself");
  double sum[3];
  for (int i = 0; i < 3; ++i)
  {
    sum[i] = p[0][i];
    for (int a = 1; a < N; ++a)
    {
      sum[i] += p[a][i];
    }
  }
  m0 += volume;
  for (int i = 0; i < 3; ++i)
  {
    m1[i] += volume * sum[i] / 4.0;
    for (int j = i; j < 3; ++j)
    {
      double sq = p[0][i] * p[0][j];
      for (int a = 1; a < N; ++a)
      {
        sq += p[a][i] * p[a][j];
      }
      m2[i][j] += volume / 20.0 * (sq + sum[i] * sum[j]);
    }
  }
}

/// Stores summed moments in the piece: M unset unless the volume is positive.
inline void SetMoments(
  double m0, const double (&m1)[3], const double (&m2)[3][3], TetrahedronIntersector::Piece& piece)
{
  piece.M[0][0] = m0;
  if (!(m0 > 0.0))
  {
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    piece.M[0][a + 1] = piece.M[a + 1][0] = m1[a];
    for (int b = 0; b < 3; ++b)
    {
      piece.M[a + 1][b + 1] = b >= a ? m2[a][b] : m2[b][a];
    }
  }
}
} // namespace clipping
} // namespace mp

#endif
