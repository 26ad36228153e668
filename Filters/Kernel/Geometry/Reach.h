// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Reach.h
 * @brief Boxes within a reach: what surfaces and curves in 3D share before
 *        their projections (SurfaceIntersector.h, SegmentIntersector.h).
 */
#ifndef MeshProjection_Kernel_Reach_h
#define MeshProjection_Kernel_Reach_h

namespace mp
{
/// `box` (xmin, xmax, ymin, ymax, zmin, zmax) is `corners` widened by `reach` on every side.
inline void WidenBox(const double corners[6], double reach, double box[6])
{
  for (int d = 0; d < 3; ++d)
  {
    box[2 * d] = corners[2 * d] - reach;
    box[2 * d + 1] = corners[2 * d + 1] + reach;
  }
}

/// Whether box `b` overlaps box `a` widened by `reach` (boxes as in WidenBox).
inline bool BoxesWithinReach(const double a[6], const double b[6], double reach)
{
  for (int d = 0; d < 3; ++d)
  {
    if (b[2 * d] > a[2 * d + 1] + reach || b[2 * d + 1] < a[2 * d] - reach)
    {
      return false;
    }
  }
  return true;
}
} // namespace mp

#endif
