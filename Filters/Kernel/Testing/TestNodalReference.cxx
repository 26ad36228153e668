// SPDX-License-Identifier: BSD-3-Clause
// NodalReference and NodalIsStraight (Geometry/NodalShapes.h), for every
// NodalType:
//  - NodalReference inverts the map on straight and curved cells (mid
//    nodes moved by 10% of the shortest edge), inside and 0.1 outside
//    (points past a fold of the extrapolated map apart), exactly (to
//    rounding) on straight simplices; it finds the foot of a point off a
//    curved surface or curve in space, and refuses degenerate cells;
//  - NodalIsStraight tells straight cells from curved ones.
#include "Geometry/NodalShapes.h"

#include "NodalTestCells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace
{
using mp::NodalType;
using namespace nodaltest;

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

TEST(NodalReference, ReferenceRoundTrip)
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

TEST(NodalReference, StraightSimplexIsOneAffineSolve)
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

TEST(NodalReference, FootOnCurvedSurfacesAndCurves)
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

TEST(NodalReference, InverseFromANearbyStart)
{
  // NodalInverse, prepared once per cell: FindFromCentre is NodalReference
  // (the same xi, bit for bit); Find from a start 0.05 off in each
  // reference coordinate gives the same point to 1e-13 on curved cells of
  // every type; on a degenerate cell both fail.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> off(-0.05, 0.05);
  for (NodalType type : AllTypes)
  {
    const int space = mp::NodalCellDimension(type);
    const std::vector<double> straight = StraightCell(type, MappedCorners(type, rng, 0.1));
    const std::vector<double> curved = Curved(type, straight, space, 0.1, rng);
    mp::NodalInverse inverse;
    ASSERT_TRUE(inverse.Prepare(type, curved.data(), space));
    for (int k = 0; k < 50; ++k)
    {
      double xi[3];
      RandomReferencePoint(type, rng, 0.0, xi);
      double x[3];
      MapPoint(type, curved, xi, x);
      double reference[3], centre[3], near[3];
      const bool ok = mp::NodalReference(type, curved.data(), space, x, reference);
      ASSERT_EQ(inverse.FindFromCentre(x, centre), ok) << int(type);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(centre[a], reference[a]) << int(type);
      }
      double start[3] = { 0.0, 0.0, 0.0 };
      for (int a = 0; a < space; ++a)
      {
        start[a] = xi[a] + off(rng);
      }
      ASSERT_TRUE(inverse.Find(x, start, near)) << int(type);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(near[a], xi[a], 1e-13) << int(type);
      }
    }
  }
  std::vector<double> X(3 * 10, 1.5);
  const double x[3] = { 1.5, 1.5, 1.5 };
  const double start[3] = { 0.25, 0.25, 0.25 };
  double xi[3];
  mp::NodalInverse inverse;
  ASSERT_TRUE(inverse.Prepare(NodalType::Tetra10, X.data(), 3));
  EXPECT_FALSE(inverse.Find(x, start, xi));
  EXPECT_FALSE(inverse.FindFromCentre(x, xi));
}

TEST(NodalReference, FailsOnDegenerateCells)
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

TEST(NodalReference, IsStraight)
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
