// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/AlignedSum.h"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace mp
{
void PrincipalAxis(const double* m, double* axis)
{
  axis[0] = axis[1] = axis[2] = 0.0;
  bool any = false;
  for (int k = 0; k < 6; ++k)
  {
    if (!std::isfinite(m[k]))
    {
      return;
    }
    any = any || m[k] != 0.0;
  }
  if (!any)
  {
    return;
  }
  Eigen::Matrix3d a;
  a << m[0], m[3], m[4], m[3], m[1], m[5], m[4], m[5], m[2];
  // (Eigenvalues in increasing order: the last column is the largest's.)
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(a);
  const Eigen::Vector3d v = solver.eigenvectors().col(2);
  for (int k = 0; k < 3; ++k)
  {
    axis[k] = v[k];
  }
}
} // namespace mp
