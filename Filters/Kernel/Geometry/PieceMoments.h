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

#include "Geometry/Lanes.h"
#include "Geometry/TetrahedronIntersector.h"

namespace mp
{
namespace clipping
{
/**
 * The moments of a piece summed so far, about a point o: the volume, the
 * first moments (x, y in one vector, z) and the second moments' upper
 * triangle as three pairs of lanes (Lanes.h): (xx, yy), (zz, xy), (xz, yz).
 * Each lane is summed with the scalar expression's operations in its order,
 * two entries per instruction.
 */
struct MomentSums
{
  double M0 = 0.0;
  Doubles2 M1xy = { 0.0, 0.0 };
  double M1z = 0.0;
  Doubles2 M2[3] = { { 0.0, 0.0 }, { 0.0, 0.0 }, { 0.0, 0.0 } };
};

/**
 * Adds a tetrahedron's moments about o to `sums`: `p` holds its corners
 * minus o, all four, or three when the fourth is o itself. On a
 * tetrahedron of volume V, the integral of x_i is V mean(x_i) and of
 * x_i x_j V/20 (sum_a x_ai x_aj + sum_a x_ai sum_a x_aj).
 */
template <int N>
inline void AddTetrahedronMoments(double volume, const double* const (&p)[N], MomentSums& sums)
{
  static_assert(N == 3 || N == 4, "corners about o, without o itself");
  // Per corner a the lanes of the three pairs (i, j): i-lanes, j-lanes.
  // (xx, yy): (x, y) (x, y); (zz, xy): (z, x) (z, y); (xz, yz): (x, y) (z, z).
  Doubles2 xy = LoadLanes(p[0]);
  double z = p[0][2];
  Doubles2 sq[3] = { xy * xy, Doubles2{ z, p[0][0] } * Doubles2{ z, p[0][1] },
    xy * Doubles2{ z, z } };
  Doubles2 sumXY = xy;
  double sumZ = z;
  for (int a = 1; a < N; ++a)
  {
    xy = LoadLanes(p[a]);
    z = p[a][2];
    sq[0] += xy * xy;
    sq[1] += Doubles2{ z, p[a][0] } * Doubles2{ z, p[a][1] };
    sq[2] += xy * Doubles2{ z, z };
    sumXY += xy;
    sumZ += z;
  }
  sums.M0 += volume;
  sums.M1xy += volume * sumXY / 4.0;
  sums.M1z += volume * sumZ / 4.0;
  const double w = volume / 20.0;
  const Doubles2 sumZX = { sumZ, sumXY[0] };
  const Doubles2 sumZY = { sumZ, sumXY[1] };
  const Doubles2 sumZZ = { sumZ, sumZ };
  sums.M2[0] += w * (sq[0] + sumXY * sumXY);
  sums.M2[1] += w * (sq[1] + sumZX * sumZY);
  sums.M2[2] += w * (sq[2] + sumXY * sumZZ);
}

/// Stores summed moments in the piece: M unset unless the volume is positive.
inline void SetMoments(const MomentSums& sums, TetrahedronIntersector::Piece& piece)
{
  piece.M[0][0] = sums.M0;
  if (!(sums.M0 > 0.0))
  {
    return;
  }
  const double m1[3] = { sums.M1xy[0], sums.M1xy[1], sums.M1z };
  // The upper triangle from the lanes: (xx, yy), (zz, xy), (xz, yz).
  const double m2[3][3] = { { sums.M2[0][0], sums.M2[1][1], sums.M2[2][0] },
    { 0.0, sums.M2[0][1], sums.M2[2][1] }, { 0.0, 0.0, sums.M2[1][0] } };
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
