// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vec3.h
 * @brief The few 3-vector operations the 3D geometry needs.
 */
#ifndef MeshProjection_Kernel_Vec3_h
#define MeshProjection_Kernel_Vec3_h

namespace mp
{
using Vec = double[3];

inline void Sub(const double* a, const double* b, double* r)
{
  r[0] = a[0] - b[0];
  r[1] = a[1] - b[1];
  r[2] = a[2] - b[2];
}
inline void Cross(const double* a, const double* b, double* r)
{
  r[0] = a[1] * b[2] - a[2] * b[1];
  r[1] = a[2] * b[0] - a[0] * b[2];
  r[2] = a[0] * b[1] - a[1] * b[0];
}
inline double Dot(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
} // namespace mp

#endif
