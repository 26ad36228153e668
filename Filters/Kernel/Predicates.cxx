// SPDX-License-Identifier: BSD-3-Clause
#include "Predicates.h"

#include <cmath>
#include <limits>

namespace mp
{
namespace
{
// Error-free transformations: a + b == s + e and a * b == p + e exactly.
inline void TwoSum(double a, double b, double& s, double& e)
{
  s = a + b;
  const double bv = s - a;
  const double av = s - bv;
  e = (a - av) + (b - bv);
}

inline void TwoProduct(double a, double b, double& p, double& e)
{
  p = a * b;
  e = std::fma(a, b, -p);
}

// Adds b to the nonoverlapping expansion h[0..n) (increasing magnitude) in
// place; returns the new length. The expansion's sign is that of its last
// nonzero component.
inline int GrowExpansion(double* h, int n, double b)
{
  double q = b;
  for (int i = 0; i < n; ++i)
  {
    double s;
    double e;
    TwoSum(q, h[i], s, e);
    h[i] = e;
    q = s;
  }
  h[n] = q;
  return n + 1;
}
} // namespace

double Orient2DExact(const double* a, const double* b, const double* c)
{
  // (ax - cx)(by - cy) - (ay - cy)(bx - cx) expanded into six products of
  // input coordinates (the cx*cy terms cancel), each split exactly in two.
  const double factors[6][2] = { { a[0], b[1] }, { -a[0], c[1] }, { -c[0], b[1] },
    { -a[1], b[0] }, { a[1], c[0] }, { c[1], b[0] } };
  double h[12];
  int n = 0;
  for (const auto& f : factors)
  {
    double p;
    double e;
    TwoProduct(f[0], f[1], p, e);
    n = GrowExpansion(h, n, e);
    n = GrowExpansion(h, n, p);
  }
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
  {
    sum += h[i];
  }
  // The rounded sum can be zero (or of the wrong sign) only when it
  // underflows; the sign of the most significant component is exact.
  for (int i = n - 1; i >= 0; --i)
  {
    if (h[i] != 0.0)
    {
      return (sum != 0.0 && (sum > 0.0) == (h[i] > 0.0))
        ? sum
        : std::copysign(std::numeric_limits<double>::denorm_min(), h[i]);
    }
  }
  return 0.0;
}

double Orient2D(const double* a, const double* b, const double* c)
{
  const double left = (a[0] - c[0]) * (b[1] - c[1]);
  const double right = (a[1] - c[1]) * (b[0] - c[0]);
  const double det = left - right;
  // Shewchuk's bound for this evaluation order: (3 + 16 eps) eps |left|+|right|.
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2.0;
  constexpr double bound = (3.0 + 16.0 * eps) * eps;
  const double detsum = std::fabs(left) + std::fabs(right);
  if (std::fabs(det) > bound * detsum)
  {
    return det;
  }
  return Orient2DExact(a, b, c);
}
} // namespace mp
