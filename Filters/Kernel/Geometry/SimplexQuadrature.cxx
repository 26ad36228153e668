// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/SimplexQuadrature.h"

#include <algorithm>
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

/**
 * An orbit of a symmetric rule: every distinct permutation of the
 * barycentric point (A, A, 1 - 2A) (triangle, B unused), (A, B, 1 - A - B)
 * (triangle, B > 0), (A, A, A, 1 - 3A) (tetrahedron, B unused),
 * (A, A, 1/2 - A, 1/2 - A) (tetrahedron, B < 0) or (A, A, B, 1 - 2A - B)
 * (tetrahedron, B > 0), each with Weight (a fraction of the measure); A = 0
 * is the centroid alone.
 */
struct Orbit
{
  double A;
  double B;
  double Weight;
};

/// A compact rule: its dimension, the degree it is exact to, its orbits.
struct CompactRule
{
  int Dimension;
  int Degree;
  std::vector<Orbit> Orbits;
};

/**
 * The compact symmetric rules (positive weights, points inside), fewer
 * points than the conical products of the same degree. Their parameters
 * solve the moment equations of the symmetric polynomials (products of the
 * power sums of the barycentric coordinates) up to their degree, by Newton
 * in 40-digit arithmetic from the published values (Strang and Fix;
 * Dunavant 1985; Radon 1948; Keast 1986; Walkington); the test checks
 * every monomial.
 */
const std::vector<CompactRule>& CompactRules()
{
  static const std::vector<CompactRule> rules = {
    { 2, 2, { { 1.0 / 6.0, 0.0, 1.0 / 3.0 } } },
    { 2, 4,
      { { 0.445948490915964886318, 0.0, 0.223381589678011465695 },
        { 0.0915762135097707434596, 0.0, 0.109951743655321867638 } } },
    { 2, 5,
      { { 0.0, 0.0, 0.225 }, { 0.47014206410511508977, 0.0, 0.132394152788506180738 },
        { 0.101286507323456338801, 0.0, 0.125939180544827152596 } } },
    { 2, 6,
      { { 0.249286745170910421292, 0.0, 0.116786275726379366025 },
        { 0.0630890144915022283403, 0.0, 0.0508449063702068169209 },
        { 0.0531450498448169473532, 0.310352451033784405417, 0.0828510756183735751936 } } },
    { 3, 2, { { 0.13819660112501051518, 0.0, 0.25 } } },
    { 3, 5,
      { { 0.0927352503108912264023, 0.0, 0.0734930431163619495437 },
        { 0.310885919263300609797, 0.0, 0.112687925718015850799 },
        { 0.0455037041256496494919, -1.0, 0.0425460207770814664381 } } },
    { 3, 6,
      { { 0.214602871259152029289, 0.0, 0.0399227502581674920997 },
        { 0.0406739585346113531156, 0.0, 0.010077211055320642948 },
        { 0.322337890142275510344, 0.0, 0.0553571815436547220952 },
        { 0.0636610018750175252992, 0.269672331458315808034, 0.0482142857142857142857 } } },
  };
  return rules;
}

/// A compact rule's points: each orbit's distinct permutations.
SimplexRule Expand(const CompactRule& compact, int degree)
{
  SimplexRule rule;
  rule.Dimension = compact.Dimension;
  rule.Degree = degree;
  const int d = compact.Dimension;
  for (const Orbit& orbit : compact.Orbits)
  {
    double point[4];
    const double a = orbit.A;
    const double b = orbit.B;
    if (a == 0.0)
    {
      std::fill(point, point + d + 1, 1.0 / (d + 1));
    }
    else if (d == 2)
    {
      point[0] = a;
      point[1] = b > 0.0 ? b : a;
      point[2] = 1.0 - a - point[1];
    }
    else
    {
      point[0] = point[1] = a;
      point[2] = b > 0.0 ? b : (b < 0.0 ? 0.5 - a : a);
      point[3] = b < 0.0 ? 0.5 - a : 1.0 - 2.0 * a - point[2];
    }
    std::sort(point, point + d + 1); // next_permutation visits each distinct one once
    do
    {
      rule.Barycentric.insert(rule.Barycentric.end(), point, point + d + 1);
      rule.Weight.push_back(orbit.Weight);
    } while (std::next_permutation(point, point + d + 1));
  }
  rule.Points = static_cast<int>(rule.Weight.size());
  return rule;
}

/// The rule of fewest points exact to `degree`: a compact one where it has
/// fewer points than the conical product.
SimplexRule Smallest(int dimension, int degree)
{
  SimplexRule best = ConicalProduct(dimension, degree);
  for (const CompactRule& compact : CompactRules())
  {
    if (compact.Dimension == dimension && compact.Degree >= degree)
    {
      SimplexRule candidate = Expand(compact, degree);
      if (candidate.Points < best.Points)
      {
        best = std::move(candidate);
      }
    }
  }
  return best;
}

std::vector<SimplexRule> AllRules()
{
  std::vector<SimplexRule> rules;
  for (int dimension = 1; dimension <= 3; ++dimension)
  {
    for (int degree = 0; degree <= MaxSimplexDegree; ++degree)
    {
      rules.push_back(Smallest(dimension, degree));
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
