// SPDX-License-Identifier: BSD-3-Clause
// NodalShapes (Geometry/NodalShapes.h), for every NodalType:
//  - the functions are Kronecker at the reference nodes and sum to 1, and
//    their derivatives match central differences;
//  - reproduction: on a cell whose corners are a random affine image of
//    the reference corners (and whose other nodes lie on the corners' map),
//    interpolating the nodal values of a polynomial of total degree <= 2 in
//    x gives the polynomial at the mapped point, for every type but
//    Pyramid13; on straight cells that are not affine images (random
//    corners, other nodes on the corners' multilinear map) Quad9, Hexa27,
//    Wedge18 still reproduce degree 2, Quad8, Hexa20, Wedge15 and Pyramid13
//    degree 1 only (and some quadratic fails); Pyramid13 reproduces
//    1, x, y, z, xy, xz, yz, z^2 and not x^2, y^2 on its square-based
//    straight cell;
//  - NodalReference inverts the map on straight and curved cells (mid
//    nodes moved by 10% of the cell's size), inside and a little outside,
//    exactly (to rounding) on straight simplices, and finds the foot of a
//    point off a curved surface or curve in space;
//  - NodalIsStraight tells straight cells from curved ones.
#include "Geometry/NodalShapes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

namespace
{
using mp::NodalType;

const NodalType AllTypes[] = { NodalType::Edge3, NodalType::Triangle6, NodalType::Quad8,
  NodalType::Quad9, NodalType::Tetra10, NodalType::Hexa20, NodalType::Hexa27, NodalType::Wedge15,
  NodalType::Wedge18, NodalType::Pyramid13 };

std::vector<double> ReferenceNodes(NodalType type)
{
  std::vector<double> xi(3 * mp::NodalNodeCount(type));
  mp::NodalReferenceNodes(type, xi.data());
  return xi;
}

/// A random point of the reference cell (well inside), widened by `margin`
/// past its faces.
void RandomReferencePoint(NodalType type, std::mt19937& rng, double margin, double* xi)
{
  std::uniform_real_distribution<double> u(-margin, 1.0 + margin);
  const int d = mp::NodalCellDimension(type);
  xi[0] = xi[1] = xi[2] = 0.0;
  for (;;)
  {
    for (int a = 0; a < d; ++a)
    {
      xi[a] = u(rng);
    }
    const bool simplex = type == NodalType::Triangle6 || type == NodalType::Tetra10;
    const bool wedge = type == NodalType::Wedge15 || type == NodalType::Wedge18;
    const double sum = simplex ? xi[0] + xi[1] + xi[2] : (wedge ? xi[0] + xi[1] : 0.0);
    const bool apex = type == NodalType::Pyramid13 && xi[2] > 0.9;
    if (sum <= 1.0 + margin && !apex)
    {
      return;
    }
  }
}

/// The corners' (multi)linear functions, written here independently of
/// the kernel: barycentric, products of xi or 1 - xi, triangle times
/// line, and the pyramid's collapsed cube (apex t, base corners (1 - t)).
std::vector<double> CornerWeights(NodalType type, const double* xi)
{
  const std::vector<double> nodes = ReferenceNodes(type);
  const int corners = mp::NodalCornerCount(type);
  const int d = mp::NodalCellDimension(type);
  std::vector<double> w(corners, 1.0);
  const bool simplex =
    type == NodalType::Edge3 || type == NodalType::Triangle6 || type == NodalType::Tetra10;
  const bool wedge = type == NodalType::Wedge15 || type == NodalType::Wedge18;
  for (int c = 0; c < corners; ++c)
  {
    const double* node = &nodes[3 * c];
    if (simplex)
    {
      w[c] = c > 0 ? xi[c - 1] : 1.0;
      for (int a = 0; c == 0 && a < d; ++a)
      {
        w[c] -= xi[a];
      }
    }
    else if (wedge)
    {
      const double l[3] = { 1.0 - xi[0] - xi[1], xi[0], xi[1] };
      w[c] = l[c % 3] * (node[2] == 1.0 ? xi[2] : 1.0 - xi[2]);
    }
    else if (type == NodalType::Pyramid13 && c == 4)
    {
      w[c] = xi[2];
    }
    else
    {
      for (int a = 0; a < (type == NodalType::Pyramid13 ? 3 : d); ++a)
      {
        w[c] *= node[a] == 1.0 ? xi[a] : 1.0 - xi[a];
      }
    }
  }
  return w;
}

/**
 * A straight cell: its corners given (3 per corner), every other node where
 * the corners' map puts its reference point.
 */
std::vector<double> StraightCell(NodalType type, const std::vector<double>& corners)
{
  const std::vector<double> nodes = ReferenceNodes(type);
  const int count = mp::NodalNodeCount(type);
  std::vector<double> X(3 * count, 0.0);
  for (int n = 0; n < count; ++n)
  {
    const std::vector<double> w = CornerWeights(type, &nodes[3 * n]);
    for (size_t c = 0; c < w.size(); ++c)
    {
      for (int i = 0; i < 3; ++i)
      {
        X[3 * n + i] += w[c] * corners[3 * c + i];
      }
    }
  }
  return X;
}

/// The reference corners (the pyramid's apex above its base's centre)
/// under x -> A x + b, A = I + 0.3 random (columns beyond the cell's
/// dimension unused), b random; with `jitter`, each corner moved further
/// by up to that much (no longer an affine image).
std::vector<double> MappedCorners(NodalType type, std::mt19937& rng, double jitter)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double A[3][3];
  double b[3];
  for (int i = 0; i < 3; ++i)
  {
    b[i] = 5.0 * u(rng);
    for (int j = 0; j < 3; ++j)
    {
      A[i][j] = (i == j ? 1.0 : 0.0) + 0.3 * u(rng);
    }
  }
  const std::vector<double> nodes = ReferenceNodes(type);
  const int corners = mp::NodalCornerCount(type);
  std::vector<double> X(3 * corners);
  for (int c = 0; c < corners; ++c)
  {
    double p[3] = { nodes[3 * c], nodes[3 * c + 1], nodes[3 * c + 2] };
    if (type == NodalType::Pyramid13 && c == 4)
    {
      p[0] = p[1] = 0.5;
    }
    for (int i = 0; i < 3; ++i)
    {
      X[3 * c + i] = b[i] + jitter * u(rng);
      for (int j = 0; j < 3; ++j)
      {
        X[3 * c + i] += A[i][j] * p[j];
      }
    }
  }
  return X;
}

/// sum_n N_n(xi) X_n.
void MapPoint(NodalType type, const std::vector<double>& X, const double* xi, double* x)
{
  double N[mp::MaxNodalNodes];
  mp::NodalValues(type, xi, N);
  x[0] = x[1] = x[2] = 0.0;
  for (int n = 0; n < mp::NodalNodeCount(type); ++n)
  {
    for (int i = 0; i < 3; ++i)
    {
      x[i] += N[n] * X[3 * n + i];
    }
  }
}

/// The monomials x^a y^b z^c of total degree <= `degree` in d variables.
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

namespace
{
/// A curved cell: the straight one's non-corner nodes moved in random
/// directions by `amount` times the cell's shortest distance between
/// two corners (at most its shortest edge), in the space's coordinates.
std::vector<double> Curved(
  NodalType type, std::vector<double> X, int space, double amount, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int corners = mp::NodalCornerCount(type);
  double shortest = HUGE_VAL;
  for (int c = 0; c < corners; ++c)
  {
    for (int e = c + 1; e < corners; ++e)
    {
      double d2 = 0.0;
      for (int i = 0; i < space; ++i)
      {
        d2 += (X[3 * c + i] - X[3 * e + i]) * (X[3 * c + i] - X[3 * e + i]);
      }
      shortest = std::min(shortest, std::sqrt(d2));
    }
  }
  for (int n = corners; n < mp::NodalNodeCount(type); ++n)
  {
    double v[3] = { 0.0, 0.0, 0.0 };
    double length = 0.0;
    do // a random direction: uniform in the ball, normalized
    {
      length = 0.0;
      for (int i = 0; i < space; ++i)
      {
        v[i] = u(rng);
        length += v[i] * v[i];
      }
    } while (length > 1.0 || length < 1e-4);
    const double radius = amount * shortest / std::sqrt(length);
    for (int i = 0; i < space; ++i)
    {
      X[3 * n + i] += radius * v[i];
    }
  }
  return X;
}

/// The determinant of the map's Jacobian at xi, in the cell's own
/// dimension (its first coordinates).
double Orientation(NodalType type, const std::vector<double>& X, const double* xi)
{
  const int d = mp::NodalCellDimension(type);
  double dN[mp::MaxNodalNodes * 3];
  mp::NodalDerivatives(type, xi, dN);
  double J[3][3] = {};
  for (int n = 0; n < mp::NodalNodeCount(type); ++n)
  {
    for (int i = 0; i < d; ++i)
    {
      for (int a = 0; a < d; ++a)
      {
        J[i][a] += dN[n * 3 + a] * X[3 * n + i];
      }
    }
  }
  if (d == 1)
  {
    return J[0][0];
  }
  if (d == 2)
  {
    return J[0][0] * J[1][1] - J[0][1] * J[1][0];
  }
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
    J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
    J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

struct RoundTrips
{
  double Worst = 0.0;    ///< the largest error in xi of the points found
  double Residual = 0.0; ///< the largest |x(found) - x| of every success
  int Failed = 0;        ///< refused although x's xi is on the cell's sheet
  int Folded = 0;        ///< x's xi past a fold (left out of Worst)
};

/**
 * Round trips xi -> x -> xi for 50 random points of the cell (inside and
 * up to `margin` outside) in its first `space` (= its dimension)
 * coordinates. Points whose xi lies past a fold of the extrapolated map
 * (its Jacobian turned against the centre's) have another preimage on the
 * cell's own sheet, so their xi cannot be asked back: they are counted
 * apart.
 */
RoundTrips RoundTrip(
  NodalType type, const std::vector<double>& X, int space, double margin, std::mt19937& rng)
{
  const std::vector<double> nodes = ReferenceNodes(type);
  double centre[3] = { 0.0, 0.0, 0.0 };
  const int corners = mp::NodalCornerCount(type);
  for (int c = 0; c < corners; ++c)
  {
    for (int a = 0; a < 3; ++a)
    {
      centre[a] += nodes[3 * c + a] / corners;
    }
  }
  RoundTrips result;
  for (int k = 0; k < 50; ++k)
  {
    double xi[3];
    RandomReferencePoint(type, rng, margin, xi);
    double x[3];
    MapPoint(type, X, xi, x);
    double found[3];
    const bool ok = mp::NodalReference(type, X.data(), space, x, found);
    if (ok)
    {
      double y[3];
      MapPoint(type, X, found, y);
      for (int i = 0; i < space; ++i)
      {
        result.Residual = std::max(result.Residual, std::abs(y[i] - x[i]));
      }
    }
    if (Orientation(type, X, xi) * Orientation(type, X, centre) <= 0.0)
    {
      ++result.Folded;
      continue;
    }
    if (!ok)
    {
      ++result.Failed;
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      result.Worst = std::max(result.Worst, std::abs(found[a] - xi[a]));
    }
  }
  return result;
}
} // namespace

TEST(NodalShapes, ReferenceRoundTrip)
{
  // Straight cells, and curved ones inside: every point found to 1e-13.
  // Curved cells 0.1 outside (mid nodes moved by 10% of the shortest edge):
  // the few points past a fold of the extrapolated map are left out, and
  // at most 1% of the others may be refused (found on the folded sheet).
  std::mt19937 rng(6);
  for (NodalType type : AllTypes)
  {
    int outsideFailed = 0;
    int folded = 0;
    for (int trial = 0; trial < 20; ++trial)
    {
      const int space = mp::NodalCellDimension(type);
      const std::vector<double> straight = StraightCell(type, MappedCorners(type, rng, 0.1));
      const std::vector<double> curved = Curved(type, straight, space, 0.1, rng);
      const RoundTrips runs[3] = { RoundTrip(type, straight, space, 0.0, rng),
        RoundTrip(type, straight, space, 0.1, rng), RoundTrip(type, curved, space, 0.0, rng) };
      for (const RoundTrips& run : runs)
      {
        EXPECT_EQ(run.Failed + run.Folded, 0) << int(type);
        EXPECT_LT(run.Worst, 1e-13) << int(type);
        EXPECT_LT(run.Residual, 1e-13) << int(type);
      }
      const RoundTrips outside = RoundTrip(type, curved, space, 0.1, rng);
      EXPECT_LT(outside.Worst, 1e-13) << int(type);
      EXPECT_LT(outside.Residual, 1e-13) << int(type);
      outsideFailed += outside.Failed;
      folded += outside.Folded;
    }
    EXPECT_LE(outsideFailed, 10) << int(type) << " of 1000 points 0.1 outside";
    std::printf("type %d: 0.1 outside curved cells: %d of 1000 past a fold, %d refused\n",
      int(type), folded, outsideFailed);
  }
}

TEST(NodalShapes, StraightSimplexIsOneAffineSolve)
{
  // The corners' affine map inverted directly: xi = J^-1 (x - X_0).
  std::mt19937 rng(7);
  for (NodalType type : { NodalType::Triangle6, NodalType::Tetra10 })
  {
    const int d = mp::NodalCellDimension(type);
    const std::vector<double> X = StraightCell(type, MappedCorners(type, rng, 0.0));
    for (int k = 0; k < 50; ++k)
    {
      double xi[3];
      RandomReferencePoint(type, rng, 0.1, xi);
      double x[3];
      MapPoint(type, X, xi, x);
      double found[3];
      ASSERT_TRUE(mp::NodalReference(type, X.data(), d, x, found));
      // The residual of the corners' affine map at the found xi.
      for (int i = 0; i < d; ++i)
      {
        double y = X[i];
        for (int a = 0; a < d; ++a)
        {
          y += found[a] * (X[3 * (a + 1) + i] - X[i]);
        }
        EXPECT_NEAR(y, x[i], 1e-14 * 8.0);
      }
      EXPECT_EQ(found[2], d < 3 ? 0.0 : found[2]);
    }
  }
}

TEST(NodalShapes, FootOnCurvedSurfacesAndCurves)
{
  // Curves and surfaces in 3D (and curves in 2D): a point moved off the
  // curved cell along its normal at xi finds xi again (the foot).
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const NodalType types[] = { NodalType::Edge3, NodalType::Triangle6, NodalType::Quad8,
    NodalType::Quad9 };
  for (NodalType type : types)
  {
    const int d = mp::NodalCellDimension(type);
    for (int space = d + 1; space <= 3; ++space)
    {
      for (int trial = 0; trial < 10; ++trial)
      {
        const std::vector<double> X =
          Curved(type, StraightCell(type, MappedCorners(type, rng, 0.1)), space, 0.1, rng);
        for (int k = 0; k < 20; ++k)
        {
          double xi[3];
          RandomReferencePoint(type, rng, 0.05, xi);
          double x[3];
          MapPoint(type, X, xi, x);
          // A normal: a random vector less its tangential part.
          double dN[mp::MaxNodalNodes * 3];
          mp::NodalDerivatives(type, xi, dN);
          double tangent[2][3] = {};
          for (int n = 0; n < mp::NodalNodeCount(type); ++n)
          {
            for (int a = 0; a < d; ++a)
            {
              for (int i = 0; i < space; ++i)
              {
                tangent[a][i] += dN[n * 3 + a] * X[3 * n + i];
              }
            }
          }
          double normal[3] = { u(rng), u(rng), space == 3 ? u(rng) : 0.0 };
          for (int pass = 0; pass < 2; ++pass) // Gram-Schmidt, twice
          {
            double q[2][3];
            for (int a = 0; a < d; ++a)
            {
              std::copy(tangent[a], tangent[a] + 3, q[a]);
              for (int b = 0; b < a; ++b)
              {
                const double t = q[a][0] * q[b][0] + q[a][1] * q[b][1] + q[a][2] * q[b][2];
                for (int i = 0; i < 3; ++i)
                {
                  q[a][i] -= t * q[b][i];
                }
              }
              const double l = std::sqrt(q[a][0] * q[a][0] + q[a][1] * q[a][1] + q[a][2] * q[a][2]);
              for (int i = 0; i < 3; ++i)
              {
                q[a][i] /= l;
              }
              const double t = normal[0] * q[a][0] + normal[1] * q[a][1] + normal[2] * q[a][2];
              for (int i = 0; i < 3; ++i)
              {
                normal[i] -= t * q[a][i];
              }
            }
          }
          const double offset = 1e-3; // far below the curvature radius
          for (int i = 0; i < space; ++i)
          {
            x[i] += offset * normal[i];
          }
          double found[3];
          ASSERT_TRUE(mp::NodalReference(type, X.data(), space, x, found)) << int(type);
          for (int a = 0; a < 3; ++a)
          {
            EXPECT_NEAR(found[a], xi[a], 1e-12) << int(type) << " space " << space;
          }
        }
      }
    }
  }
}

TEST(NodalShapes, FailsOnDegenerateCells)
{
  // Every node at one point: no Jacobian to invert.
  std::vector<double> X(3 * 10, 1.5);
  double x[3] = { 1.5, 1.5, 1.5 };
  double xi[3];
  EXPECT_FALSE(mp::NodalReference(NodalType::Tetra10, X.data(), 3, x, xi));
  // A flat tetrahedron.
  std::mt19937 rng(9);
  std::vector<double> corners = MappedCorners(NodalType::Tetra10, rng, 0.0);
  for (int i = 0; i < 3; ++i)
  {
    corners[9 + i] = 0.5 * (corners[3 + i] + corners[6 + i]);
  }
  X = StraightCell(NodalType::Tetra10, corners);
  EXPECT_FALSE(mp::NodalReference(NodalType::Tetra10, X.data(), 3, x, xi));
}

TEST(NodalShapes, IsStraight)
{
  std::mt19937 rng(10);
  for (NodalType type : AllTypes)
  {
    const int d = mp::NodalCellDimension(type);
    for (int space = d; space <= 3; ++space)
    {
      std::vector<double> X = StraightCell(type, MappedCorners(type, rng, 0.1));
      EXPECT_TRUE(mp::NodalIsStraight(type, X.data(), space, 1e-12)) << int(type);
      // One mid node off by 1e-4 of the cell's size (about 1).
      X[3 * mp::NodalCornerCount(type) + space - 1] += 1e-4;
      EXPECT_FALSE(mp::NodalIsStraight(type, X.data(), space, 1e-6)) << int(type);
      EXPECT_TRUE(mp::NodalIsStraight(type, X.data(), space, 1e-3)) << int(type);
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
