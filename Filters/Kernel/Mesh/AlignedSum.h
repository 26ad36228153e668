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
} // namespace mp

#endif
