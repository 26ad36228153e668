// SPDX-License-Identifier: BSD-3-Clause
// NodalShapes (Geometry/NodalShapes.h), the functions, for every NodalType:
//  - they are Kronecker at the reference nodes and sum to 1, and their
//    derivatives match central differences; NodalDegree is their highest
//    degree;
//  - reproduction: on a cell whose corners are a random affine image of
//    the reference corners (and whose other nodes lie on the corners' map),
//    interpolating the nodal values of a polynomial of total degree <= 2 in
//    x gives the polynomial at the mapped point, for every type but
//    Pyramid13; on straight cells that are not affine images (random
//    corners, other nodes on the corners' multilinear map) Quad9, Hexa27,
//    Wedge18 still reproduce degree 2, Quad8, Hexa20, Wedge15 and Pyramid13
//    degree 1 only (and some quadratic fails); Pyramid13 reproduces
//    1, x, y, z, xy, xz, yz, z^2 and not x^2, y^2 on its square-based
//    straight cell.
// The inverse map is TestNodalReference's.
#include "Geometry/NodalShapes.h"

#include "NodalTestCells.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace
{
using mp::NodalType;
using namespace nodaltest;

std::vector<std::array<int, 3>> Monomials(int d, int degree)
{
  std::vector<std::array<int, 3>> all;
  for (int a = 0; a <= degree; ++a)
  {
    for (int b = 0; b <= (d > 1 ? degree - a : 0); ++b)
    {
      for (int c = 0; c <= (d > 2 ? degree - a - b : 0); ++c)
      {
        all.push_back({ a, b, c });
      }
    }
  }
  return all;
}

/// The largest error of interpolating monomial m from X's nodes, over
/// random reference points, relative to the monomial's largest nodal value
/// (or 1).
double ReproductionError(
  NodalType type, const std::vector<double>& X, const std::array<int, 3>& m, std::mt19937& rng)
{
  auto f = [&m](const double* x) {
    return std::pow(x[0], m[0]) * std::pow(x[1], m[1]) * std::pow(x[2], m[2]);
  };
  double scale = 1.0;
  for (int n = 0; n < mp::NodalNodeCount(type); ++n)
  {
    scale = std::max(scale, std::abs(f(&X[3 * n])));
  }
  double worst = 0.0;
  for (int k = 0; k < 20; ++k)
  {
    double xi[3];
    RandomReferencePoint(type, rng, 0.0, xi);
    double N[mp::MaxNodalNodes];
    mp::NodalValues(type, xi, N);
    double x[3];
    MapPoint(type, X, xi, x);
    double interpolated = 0.0;
    for (int n = 0; n < mp::NodalNodeCount(type); ++n)
    {
      interpolated += N[n] * f(&X[3 * n]);
    }
    worst = std::max(worst, std::abs(interpolated - f(x)) / scale);
  }
  return worst;
}
} // namespace

TEST(NodalShapes, KroneckerAndPartitionOfUnity)
{
  std::mt19937 rng(1);
  for (NodalType type : AllTypes)
  {
    const int count = mp::NodalNodeCount(type);
    const std::vector<double> nodes = ReferenceNodes(type);
    double N[mp::MaxNodalNodes];
    for (int m = 0; m < count; ++m)
    {
      mp::NodalValues(type, &nodes[3 * m], N);
      for (int n = 0; n < count; ++n)
      {
        EXPECT_NEAR(N[n], n == m ? 1.0 : 0.0, 1e-15) << int(type) << " node " << m << " fn " << n;
      }
    }
    for (int k = 0; k < 100; ++k)
    {
      double xi[3];
      RandomReferencePoint(type, rng, 0.2, xi);
      double dN[mp::MaxNodalNodes * 3];
      mp::NodalValues(type, xi, N);
      mp::NodalDerivatives(type, xi, dN);
      double sum = 0.0;
      double slope[3] = { 0.0, 0.0, 0.0 };
      for (int n = 0; n < count; ++n)
      {
        sum += N[n];
        for (int a = 0; a < 3; ++a)
        {
          slope[a] += dN[n * 3 + a];
        }
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << int(type);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(slope[a], 0.0, 1e-13) << int(type);
      }
    }
  }
}

TEST(NodalShapes, DerivativesMatchDifferences)
{
  std::mt19937 rng(2);
  const double h = 1e-6;
  for (NodalType type : AllTypes)
  {
    const int count = mp::NodalNodeCount(type);
    const int d = mp::NodalCellDimension(type);
    for (int k = 0; k < 50; ++k)
    {
      double xi[3];
      RandomReferencePoint(type, rng, 0.2, xi);
      double dN[mp::MaxNodalNodes * 3];
      mp::NodalDerivatives(type, xi, dN);
      for (int a = 0; a < 3; ++a)
      {
        double plus[3] = { xi[0], xi[1], xi[2] };
        double minus[3] = { xi[0], xi[1], xi[2] };
        plus[a] += h;
        minus[a] -= h;
        double Np[mp::MaxNodalNodes];
        double Nm[mp::MaxNodalNodes];
        mp::NodalValues(type, plus, Np);
        mp::NodalValues(type, minus, Nm);
        for (int n = 0; n < count; ++n)
        {
          const double difference = a < d ? (Np[n] - Nm[n]) / (2.0 * h) : 0.0;
          EXPECT_NEAR(dN[n * 3 + a], difference, 1e-8) << int(type) << " fn " << n << " dir " << a;
        }
      }
    }
  }
}

TEST(NodalShapes, DegreeIsTheFunctionsHighest)
{
  // Along the diagonal xi = s (1, 1, 1) / 4 a function of total degree p is
  // a polynomial of degree <= p in s: its (p + 1)-th finite difference
  // vanishes, and for some function the p-th does not.
  for (NodalType type : AllTypes)
  {
    const int p = mp::NodalDegree(type);
    const int count = mp::NodalNodeCount(type);
    const int d = mp::NodalCellDimension(type);
    auto difference = [&](int order, int n) {
      double sum = 0.0;
      double binomial = 1.0;
      for (int j = 0; j <= order; ++j)
      {
        const double s = 0.1 + 0.05 * j;
        double xi[3] = { 0.0, 0.0, 0.0 };
        for (int a = 0; a < d; ++a)
        {
          xi[a] = s * (a == 2 ? 1.0 : 0.9 - 0.3 * a); // a generic direction
        }
        double N[mp::MaxNodalNodes];
        mp::NodalValues(type, xi, N);
        sum += ((order - j) % 2 == 0 ? 1.0 : -1.0) * binomial * N[n];
        binomial = binomial * (order - j) / (j + 1);
      }
      return sum;
    };
    double top = 0.0;
    for (int n = 0; n < count; ++n)
    {
      EXPECT_NEAR(difference(p + 1, n), 0.0, 1e-11) << int(type) << " fn " << n;
      top = std::max(top, std::abs(difference(p, n)));
    }
    EXPECT_GT(top, 1e-9) << int(type);
  }
}

TEST(NodalShapes, QuadraticsOnAffineCells)
{
  std::mt19937 rng(3);
  for (NodalType type : AllTypes)
  {
    const int d = mp::NodalCellDimension(type);
    for (int trial = 0; trial < 5; ++trial)
    {
      const std::vector<double> X = StraightCell(type, MappedCorners(type, rng, 0.0));
      for (const std::array<int, 3>& m : Monomials(3, 2))
      {
        const double error = ReproductionError(type, X, m, rng);
        if (type == NodalType::Pyramid13 || (d < 3 && m[2] > 0) || (d < 2 && m[1] > 0))
        {
          continue; // the pyramid below; monomials in unused directions
        }
        EXPECT_LT(error, 1e-12) << int(type) << " x^" << m[0] << " y^" << m[1] << " z^" << m[2];
      }
    }
  }
}

TEST(NodalShapes, StraightButNotAffineCells)
{
  std::mt19937 rng(4);
  for (NodalType type : AllTypes)
  {
    const int d = mp::NodalCellDimension(type);
    const bool quadratic = type == NodalType::Quad9 || type == NodalType::Hexa27 ||
      type == NodalType::Wedge18 || d == 1 || type == NodalType::Triangle6 ||
      type == NodalType::Tetra10;
    const std::vector<double> X = StraightCell(type, MappedCorners(type, rng, 0.15));
    double worstQuadratic = 0.0;
    for (const std::array<int, 3>& m : Monomials(3, 2))
    {
      const double error = ReproductionError(type, X, m, rng);
      if (m[0] + m[1] + m[2] <= 1 || quadratic)
      {
        EXPECT_LT(error, 1e-12) << int(type) << " x^" << m[0] << " y^" << m[1] << " z^" << m[2];
      }
      worstQuadratic = std::max(worstQuadratic, error);
    }
    if (!quadratic)
    {
      EXPECT_GT(worstQuadratic, 1e-6) << int(type);
    }
  }
}

TEST(NodalShapes, PyramidReproduces)
{
  // The square-based straight pyramid, apex anywhere at height 1.
  std::mt19937 rng(5);
  const std::vector<double> X = StraightCell(NodalType::Pyramid13,
    { 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.3, 0.7, 1.0 });
  for (const std::array<int, 3>& m : Monomials(3, 2))
  {
    const double error = ReproductionError(NodalType::Pyramid13, X, m, rng);
    if (m[0] == 2 || m[1] == 2)
    {
      EXPECT_GT(error, 1e-6) << "x^" << m[0] << " y^" << m[1] << " z^" << m[2];
    }
    else
    {
      EXPECT_LT(error, 1e-14) << "x^" << m[0] << " y^" << m[1] << " z^" << m[2];
    }
  }
}

TEST(NodalShapes, Sizes)
{
  EXPECT_EQ(mp::NodalNodeCount(NodalType::None), 0);
  EXPECT_EQ(mp::NodalCellDimension(NodalType::None), 0);
  const int counts[] = { 3, 6, 8, 9, 10, 20, 27, 15, 18, 13 };
  const int corners[] = { 2, 3, 4, 4, 4, 8, 8, 6, 6, 5 };
  const int dimensions[] = { 1, 2, 2, 2, 3, 3, 3, 3, 3, 3 };
  for (int k = 0; k < 10; ++k)
  {
    EXPECT_EQ(mp::NodalNodeCount(AllTypes[k]), counts[k]);
    EXPECT_EQ(mp::NodalCornerCount(AllTypes[k]), corners[k]);
    EXPECT_EQ(mp::NodalCellDimension(AllTypes[k]), dimensions[k]);
  }
}
