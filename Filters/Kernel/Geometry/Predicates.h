// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Predicates.h
 * @brief Robust orientation test in the plane.
 *
 * Every combinatorial decision of the intersector (is a corner inside a cell,
 * do two edges cross) is the sign of an orientation determinant. Deciding
 * these signs exactly makes the decisions of different cell pairs consistent
 * with each other, which is what the advancing front relies on when cells
 * touch in a vertex or along an edge.
 *
 * The test first evaluates the determinant in floating point with a
 * forward error bound (Shewchuk, "Adaptive precision floating-point
 * arithmetic and fast robust geometric predicates", 1997); only when the
 * result is within that bound is it recomputed exactly, as a floating-point
 * expansion of the six exact products of input coordinates.
 */
#ifndef MeshProjection_Kernel_Predicates_h
#define MeshProjection_Kernel_Predicates_h

#include <cmath>

namespace mp
{
/// The unit roundoff of double arithmetic, 2^-53: every error bound of the
/// floating-point filters here and in the intersectors is a multiple of it.
constexpr double RoundingUnit = 1.1102230246251565e-16;

/// The exact-arithmetic path of Orient2D, exposed for tests.
double Orient2DExact(const double* a, const double* b, const double* c);

/**
 * Twice the signed area of triangle (a, b, c): positive when counterclockwise.
 * The sign is exact. The magnitude is the rounded determinant when the
 * floating-point filter decides (its error below the filter's bound, so
 * large relative to the value only for nearly collinear points), else
 * close to the exact value. Inputs are (x, y) pairs. Inline: the floating-point filter decides almost
 * every call; only near-degenerate ones take the exact path.
 */
inline double Orient2D(const double* a, const double* b, const double* c)
{
  const double left = (a[0] - c[0]) * (b[1] - c[1]);
  const double right = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = left - right;
  // Shewchuk's bound for this evaluation order: (3 + 16 u) u, u = RoundingUnit, (|left| + |right|).
  constexpr double bound = (3.0 + 16.0 * RoundingUnit) * RoundingUnit;
  if (std::fabs(det) > bound * (std::fabs(left) + std::fabs(right)))
  {
    return det;
  }
  // A factor of each product exactly zero (points sharing a coordinate, as
  // on the straight boundary of a box): the determinant is exactly zero.
  if ((a[0] == c[0] || b[1] == c[1]) && (a[1] == c[1] || b[0] == c[0]))
  {
    return 0.0;
  }
  return Orient2DExact(a, b, c);
}

/**
 * Six times the signed volume of tetrahedron (a, b, c, d): positive when d
 * lies on the side of plane (a, b, c) where (a, b, c) turns counterclockwise
 * seen from d... i.e. det[b - a, c - a, d - a]. The sign is exact; the
 * magnitude, as Orient2D's, is the rounded determinant when the filter
 * decides (large relative error only for nearly coplanar points), else close
 * to the exact value. Inputs are (x, y, z) triples.
 */
double Orient3D(const double* a, const double* b, const double* c, const double* d);

/// The exact-arithmetic path of Orient3D, exposed for tests.
double Orient3DExact(const double* a, const double* b, const double* c, const double* d);
} // namespace mp

#endif
