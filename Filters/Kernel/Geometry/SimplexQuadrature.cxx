// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/SimplexQuadrature.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace mp
{
namespace
{
/// The Jacobi polynomial P_n^(alpha, 0) at x and its derivative, by the
/// three-term recurrence (and its derivative).
void Jacobi(int n, double alpha, double x, double& p, double& dp)
{
  double p0 = 1.0;
  double d0 = 0.0;
  double p1 = 0.5 * alpha + 0.5 * (alpha + 2.0) * x;
  double d1 = 0.5 * (alpha + 2.0);
  if (n == 0)
  {
    p = p0;
    dp = d0;
    return;
  }
  for (int k = 2; k <= n; ++k)
  {
    const double s = 2.0 * k + alpha; // 2k + alpha + beta, beta = 0
    const double a1 = 2.0 * k * (k + alpha) * (s - 2.0);
    const double a2 = (s - 1.0) * alpha * alpha;
    const double a3 = (s - 2.0) * (s - 1.0) * s;
    const double a4 = 2.0 * (k + alpha - 1.0) * (k - 1.0) * s;
    const double p2 = ((a2 + a3 * x) * p1 - a4 * p0) / a1;
    const double d2 = ((a2 + a3 * x) * d1 + a3 * p1 - a4 * d0) / a1;
    p0 = p1;
    d0 = d1;
    p1 = p2;
    d1 = d2;
  }
  p = p1;
  dp = d1;
}

double JacobiValue(int n, double alpha, double x)
{
  double p = 0.0;
  double dp = 0.0;
  Jacobi(n, alpha, x, p, dp);
  return p;
}

/// The root of P_n^(alpha, 0) in [lo, hi] (a sign change), by bisection to
/// the last bit: the roots are simple, so the sign is reliable there.
double BisectRoot(int n, double alpha, double lo, double hi)
{
  double flo = JacobiValue(n, alpha, lo);
  for (int iteration = 0; iteration < 200; ++iteration)
  {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi)
    {
      break;
    }
    const double fmid = JacobiValue(n, alpha, mid);
    if ((fmid < 0.0) == (flo < 0.0))
    {
      lo = mid;
      flo = fmid;
    }
    else
    {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

/**
 * The n-point Gauss-Jacobi rule for int_0^1 g(a) (1 - a)^alpha da: nodes
 * in (0, 1), positive weights. On [-1, 1] the nodes are the roots of
 * P_n^(alpha, 0) (separated by far more than the scan's step, so each sits
 * alone in one step) and the weights 2^(alpha + 1) / ((1 - x^2) P_n'(x)^2).
 */
void GaussJacobi01(int n, double alpha, std::vector<double>& nodes, std::vector<double>& weights)
{
  nodes.clear();
  weights.clear();
  const int steps = 20000;
  double previous = JacobiValue(n, alpha, -1.0);
  for (int i = 1; i <= steps; ++i)
  {
    const double lo = -1.0 + 2.0 * (i - 1) / steps;
    const double hi = -1.0 + 2.0 * i / steps;
    const double value = JacobiValue(n, alpha, hi);
    if ((value < 0.0) != (previous < 0.0))
    {
      const double x = BisectRoot(n, alpha, lo, hi);
      double p = 0.0;
      double dp = 0.0;
      Jacobi(n, alpha, x, p, dp);
      nodes.push_back(0.5 * (1.0 + x));
      // int_0^1 g (1 - a)^alpha da = 2^-(alpha + 1) int_-1^1 g (1 - x)^alpha dx.
      weights.push_back(1.0 / ((1.0 - x * x) * dp * dp));
    }
    previous = value;
  }
  if (static_cast<int>(nodes.size()) != n)
  {
    throw std::logic_error("SimplexQuadrature: a Gauss-Jacobi root was missed");
  }
}

/// Stroud's conical product rule on the d-simplex exact to `degree`.
SimplexRule ConicalProduct(int dimension, int degree)
{
  const int n = (degree + 2) / 2; // ceil((degree + 1) / 2)
  std::vector<std::vector<double>> nodes(dimension);
  std::vector<std::vector<double>> weights(dimension);
  for (int j = 0; j < dimension; ++j)
  {
    GaussJacobi01(n, dimension - 1 - j, nodes[j], weights[j]);
  }
  SimplexRule rule;
  rule.Dimension = dimension;
  rule.Degree = degree;
  int count = 1;
  for (int j = 0; j < dimension; ++j)
  {
    count *= n;
  }
  rule.Points = count;
  double factorial = 1.0; // the simplex's measure is 1 / d!
  for (int j = 2; j <= dimension; ++j)
  {
    factorial *= j;
  }
  for (int q = 0; q < count; ++q)
  {
    double left = 1.0; // prod (1 - a_j) so far
    double weight = factorial;
    double barycentric[4];
    int digits = q;
    for (int j = 0; j < dimension; ++j)
    {
      const int i = digits % n;
      digits /= n;
      const double a = nodes[j][i];
      barycentric[j + 1] = a * left;
      left *= 1.0 - a;
      weight *= weights[j][i];
    }
    barycentric[0] = left;
    rule.Barycentric.insert(rule.Barycentric.end(), barycentric, barycentric + dimension + 1);
    rule.Weight.push_back(weight);
  }
  return rule;
}

std::vector<SimplexRule> AllRules()
{
  std::vector<SimplexRule> rules;
  for (int dimension = 1; dimension <= 3; ++dimension)
  {
    for (int degree = 0; degree <= MaxSimplexDegree; ++degree)
    {
      rules.push_back(ConicalProduct(dimension, degree));
    }
  }
  return rules;
}
} // namespace

const SimplexRule& SimplexQuadrature(int dimension, int degree)
{
  if (dimension < 1 || dimension > 3 || degree < 0 || degree > MaxSimplexDegree)
  {
    throw std::out_of_range("SimplexQuadrature: dimension 1-3 and degree 0-12 only");
  }
  static const std::vector<SimplexRule> rules = AllRules();
  return rules[(dimension - 1) * (MaxSimplexDegree + 1) + degree];
}
} // namespace mp
