// SPDX-License-Identifier: BSD-3-Clause
// SimplexQuadrature (Geometry/SimplexQuadrature.h): in dimensions 1 to 3
// and degrees 0 to 12, every monomial of total degree <= the rule's degree
// integrates to its exact mean over the reference simplex
// (d! a_1! ... a_d! / (a_1 + ... + a_d + d)!), the weights are positive and
// sum to 1, every point is strictly inside, and for odd degrees one degree
// more is not always exact (the rules are not over-sized by accident); the
// compact symmetric rules are used where they have fewer points; the mass
// matrices of the quadratic simplices (int N_i N_j, degree 4) from the
// degree-4 rules (compact in 2D and 3D) equal those from the degree-12
// conical products, their sums the exact integral of 1 and a corner's
// diagonal entry its exact value.
#include "Geometry/SimplexQuadrature.h"

#include "Geometry/NodalShapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

namespace
{
double Factorial(int n)
{
  double f = 1.0;
  for (int i = 2; i <= n; ++i)
  {
    f *= i;
  }
  return f;
}

/// The mean over the reference d-simplex of xi_1^e[0] ... xi_d^e[d-1].
double ExactMean(int dimension, const int* exponents)
{
  int total = 0;
  double numerator = Factorial(dimension);
  for (int k = 0; k < dimension; ++k)
  {
    total += exponents[k];
    numerator *= Factorial(exponents[k]);
  }
  return numerator / Factorial(total + dimension);
}

double RuleMean(const mp::SimplexRule& rule, const int* exponents)
{
  const int d = rule.Dimension;
  double sum = 0.0;
  for (int q = 0; q < rule.Points; ++q)
  {
    double value = 1.0;
    for (int k = 0; k < d; ++k)
    {
      value *= std::pow(rule.Barycentric[q * (d + 1) + k + 1], exponents[k]);
    }
    sum += rule.Weight[q] * value;
  }
  return sum;
}

/// Every exponent tuple of total degree exactly `degree` in `dimension`.
std::vector<std::vector<int>> Monomials(int dimension, int degree)
{
  if (dimension == 1)
  {
    return { { degree, 0, 0 } };
  }
  std::vector<std::vector<int>> all;
  for (int a = 0; a <= degree; ++a)
  {
    if (dimension == 2)
    {
      all.push_back({ a, degree - a, 0 });
      continue;
    }
    for (int b = 0; b <= degree - a; ++b)
    {
      all.push_back({ a, b, degree - a - b });
    }
  }
  return all;
}
} // namespace

TEST(SimplexQuadrature, MonomialsExact)
{
  for (int dimension = 1; dimension <= 3; ++dimension)
  {
    for (int degree = 0; degree <= mp::MaxSimplexDegree; ++degree)
    {
      const mp::SimplexRule& rule = mp::SimplexQuadrature(dimension, degree);
      ASSERT_EQ(rule.Dimension, dimension);
      ASSERT_EQ(rule.Degree, degree);
      ASSERT_EQ(rule.Weight.size(), static_cast<size_t>(rule.Points));
      ASSERT_EQ(rule.Barycentric.size(), static_cast<size_t>(rule.Points * (dimension + 1)));
      for (int p = 0; p <= degree; ++p)
      {
        for (const std::vector<int>& e : Monomials(dimension, p))
        {
          const double exact = ExactMean(dimension, e.data());
          EXPECT_NEAR(RuleMean(rule, e.data()), exact, 1e-13 * exact)
            << "dimension " << dimension << " degree " << degree << " monomial " << e[0] << ","
            << e[1] << "," << e[2];
        }
      }
    }
  }
}

TEST(SimplexQuadrature, NotExactOneDegreeHigher)
{
  // Each rule misses some monomial of degree 2n (n points per direction):
  // the test above would pass for a rule of any larger size too.
  for (int dimension = 1; dimension <= 3; ++dimension)
  {
    for (int degree = 1; degree <= mp::MaxSimplexDegree; degree += 2)
    {
      const mp::SimplexRule& rule = mp::SimplexQuadrature(dimension, degree);
      double worst = 0.0;
      for (const std::vector<int>& e : Monomials(dimension, degree + 1))
      {
        const double exact = ExactMean(dimension, e.data());
        worst = std::max(worst, std::abs(RuleMean(rule, e.data()) - exact) / exact);
      }
      EXPECT_GT(worst, 1e-6) << "dimension " << dimension << " degree " << degree;
    }
  }
}

TEST(SimplexQuadrature, PositiveWeightsInside)
{
  for (int dimension = 1; dimension <= 3; ++dimension)
  {
    for (int degree = 0; degree <= mp::MaxSimplexDegree; ++degree)
    {
      const mp::SimplexRule& rule = mp::SimplexQuadrature(dimension, degree);
      double sum = 0.0;
      for (int q = 0; q < rule.Points; ++q)
      {
        EXPECT_GT(rule.Weight[q], 0.0);
        sum += rule.Weight[q];
        double barycentricSum = 0.0;
        for (int k = 0; k <= dimension; ++k)
        {
          const double l = rule.Barycentric[q * (dimension + 1) + k];
          EXPECT_GT(l, 0.0);
          EXPECT_LT(l, 1.0);
          barycentricSum += l;
        }
        EXPECT_NEAR(barycentricSum, 1.0, 1e-15);
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
    }
  }
}

TEST(SimplexQuadrature, SizesAndArguments)
{
  // The conical products: n = ceil((degree + 1) / 2) points per direction,
  // n^d in all; the compact rules where they have fewer.
  EXPECT_EQ(mp::SimplexQuadrature(1, 0).Points, 1);
  EXPECT_EQ(mp::SimplexQuadrature(1, 12).Points, 7);
  EXPECT_EQ(mp::SimplexQuadrature(2, 1).Points, 1);
  EXPECT_EQ(mp::SimplexQuadrature(2, 2).Points, 3);
  EXPECT_EQ(mp::SimplexQuadrature(2, 3).Points, 4);
  EXPECT_EQ(mp::SimplexQuadrature(2, 4).Points, 6);
  EXPECT_EQ(mp::SimplexQuadrature(2, 5).Points, 7);
  EXPECT_EQ(mp::SimplexQuadrature(2, 6).Points, 12);
  EXPECT_EQ(mp::SimplexQuadrature(2, 7).Points, 16);
  EXPECT_EQ(mp::SimplexQuadrature(3, 2).Points, 4);
  EXPECT_EQ(mp::SimplexQuadrature(3, 3).Points, 8);
  EXPECT_EQ(mp::SimplexQuadrature(3, 4).Points, 14);
  EXPECT_EQ(mp::SimplexQuadrature(3, 5).Points, 14);
  EXPECT_EQ(mp::SimplexQuadrature(3, 6).Points, 24);
  EXPECT_EQ(mp::SimplexQuadrature(3, 7).Points, 64);
  EXPECT_EQ(mp::SimplexQuadrature(3, 12).Points, 343);
  EXPECT_THROW(mp::SimplexQuadrature(0, 2), std::out_of_range);
  EXPECT_THROW(mp::SimplexQuadrature(4, 2), std::out_of_range);
  EXPECT_THROW(mp::SimplexQuadrature(2, -1), std::out_of_range);
  EXPECT_THROW(mp::SimplexQuadrature(2, mp::MaxSimplexDegree + 1), std::out_of_range);
}

TEST(SimplexQuadrature, SameRuleFromEveryThread)
{
  const mp::SimplexRule* seen[4] = {};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
  {
    threads.emplace_back([&seen, t] { seen[t] = &mp::SimplexQuadrature(3, 7); });
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  for (int t = 1; t < 4; ++t)
  {
    EXPECT_EQ(seen[t], seen[0]);
  }
}

TEST(SimplexQuadrature, QuadraticMassMatrices)
{
  const mp::NodalType types[] = { mp::NodalType::Edge3, mp::NodalType::Triangle6,
    mp::NodalType::Tetra10 };
  for (mp::NodalType type : types)
  {
    const int d = mp::NodalCellDimension(type);
    const int count = mp::NodalNodeCount(type);
    auto mass = [&](const mp::SimplexRule& rule) {
      std::vector<double> M(count * count, 0.0);
      for (int q = 0; q < rule.Points; ++q)
      {
        double N[mp::MaxNodalNodes];
        // The reference coordinates are the barycentric ones past the first.
        double xi[3] = { 0.0, 0.0, 0.0 };
        for (int a = 0; a < d; ++a)
        {
          xi[a] = rule.Barycentric[q * (d + 1) + a + 1];
        }
        mp::NodalValues(type, xi, N);
        for (int i = 0; i < count; ++i)
        {
          for (int j = 0; j < count; ++j)
          {
            M[i * count + j] += rule.Weight[q] * N[i] * N[j];
          }
        }
      }
      return M;
    };
    const std::vector<double> low = mass(mp::SimplexQuadrature(d, 4));
    const std::vector<double> high = mass(mp::SimplexQuadrature(d, mp::MaxSimplexDegree));
    double sum = 0.0;
    for (int k = 0; k < count * count; ++k)
    {
      EXPECT_NEAR(low[k], high[k], 1e-15) << int(type) << " entry " << k;
      sum += low[k];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << int(type);
    // A corner's diagonal entry, 4 <l^4> - 4 <l^3> + <l^2> with
    // <l^k> = d! k! / (k + d)!: 2/15, 1/30, 1/70 of the measure.
    const double exact = d == 1 ? 2.0 / 15.0 : (d == 2 ? 1.0 / 30.0 : 1.0 / 70.0);
    EXPECT_NEAR(low[0], exact, 1e-16) << int(type);
  }
}
