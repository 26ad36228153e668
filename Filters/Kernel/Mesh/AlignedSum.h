// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file AlignedSum.h
 * @brief The mean direction of a set of directions known up to sign: their
 *        sum, each taken with the sign that agrees with the sum so far.
 *
 * A point's normal on a surface whose cells are not oriented alike (or a
 * curve's tangent along segments that point either way) is the sum of its
 * cells' area vectors (chords), each flipped where it points against the
 * sum so far. The sum depends on the order of the terms (the first sets
 * the sign): callers add them in a fixed order so that the same mesh gives
 * the same sum. A term perpendicular to the sum so far (or the first, to a
 * zero sum) is added as it is.
 *
 * Parts of one sum made apart (a point shared by processes, each with the
 * sum over its own cells) cannot be added as they are: each part's sign
 * is its own. What they share is sign-invariant: the outer products
 * s s^T of the parts (AddOuter: 6 numbers, which add up over the parts).
 * Each part then takes the sign that agrees with the principal axis of
 * their sum (AlignWithAxis), and the parts so aligned add up: as the
 * serial sum, parts that point opposite ways are flipped rather than
 * cancelled.
 */
#ifndef MeshProjection_Kernel_AlignedSum_h
#define MeshProjection_Kernel_AlignedSum_h

#include "Mesh/Vec3.h"

namespace mp
{
/// Adds the direction `w` (3 values) to `sum` with the sign that agrees with it.
inline void AddAligned(double* sum, const double* w)
{
  const double sign = Dot(sum, w) < 0.0 ? -1.0 : 1.0;
  for (int k = 0; k < 3; ++k)
  {
    sum[k] += sign * w[k];
  }
}

/// Adds the outer product w w^T to `m` (6 values: xx, yy, zz, xy, xz, yz).
inline void AddOuter(double* m, const double* w)
{
  m[0] += w[0] * w[0];
  m[1] += w[1] * w[1];
  m[2] += w[2] * w[2];
  m[3] += w[0] * w[1];
  m[4] += w[0] * w[2];
  m[5] += w[1] * w[2];
}

/**
 * The unit eigenvector of the largest eigenvalue of the symmetric matrix
 * `m` (6 values, as AddOuter's) in `axis`; zero when `m` is zero or not
 * finite. The same `m` gives the same axis (its sign too).
 */
void PrincipalAxis(const double* m, double* axis);

/// Flips `s` (3 values) when it points against `axis`.
inline void AlignWithAxis(double* s, const double* axis)
{
  if (Dot(s, axis) < 0.0)
  {
    for (int k = 0; k < 3; ++k)
    {
      s[k] = -s[k];
    }
  }
}
} // namespace mp

#endif
