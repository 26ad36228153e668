// SPDX-License-Identifier: BSD-3-Clause
// FringeRoots (Transfer/FringeRoots.h): on straight tri6 and tet10 meshes
// whose nodes beyond a plane are not usable, a root extension reads only
// usable nodes of one parent, sums to 1, stays within
// FringeRootAmplification and reproduces every quadratic at the node
// extrapolated to (1e-12); curved cells are no roots.
#include "Transfer/FringeRoots.h"

#include "Geometry/NodalShapes.h"
#include "NodalMeshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
using mp::Index;
using nodaltest::NodalMesh;

/// A quadratic with every term.
double Quadratic(const double* x, int d)
{
  const double z = d == 3 ? x[2] : 0.0;
  return 0.7 + 1.3 * x[0] - 0.4 * x[1] + 0.9 * z + 2.1 * x[0] * x[0] - 1.7 * x[0] * x[1] +
    0.6 * x[1] * x[1] + 1.1 * x[0] * z - 0.8 * x[1] * z + 1.9 * z * z;
}

/// Every point beyond x = 0.55 extended from the usable ones before it.
void ExpectQuadraticRoots(const NodalMesh& m)
{
  const mp::MeshView mesh = m.View();
  const int d = mesh.SpaceDimension;
  std::vector<char> usable(static_cast<size_t>(mesh.NumberOfPoints));
  for (Index p = 0; p < mesh.NumberOfPoints; ++p)
  {
    usable[static_cast<size_t>(p)] = mesh.Point(p)[0] < 0.55;
  }
  std::vector<char> roots(static_cast<size_t>(mesh.Parents()));
  for (Index p = 0; p < mesh.Parents(); ++p)
  {
    roots[static_cast<size_t>(p)] = mp::IsAffineRoot(mesh, p);
    EXPECT_TRUE(roots[static_cast<size_t>(p)]) << "parent " << p;
  }
  std::vector<Index> cells;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    cells.push_back(c);
  }
  int extended = 0;
  for (Index i = 0; i < mesh.NumberOfPoints; ++i)
  {
    const double* x = mesh.Point(i);
    if (usable[static_cast<size_t>(i)] || x[0] > 0.8)
    {
      continue;
    }
    std::vector<Index> points;
    std::vector<double> weights;
    ASSERT_TRUE(mp::RootExtension(mesh, i, cells, roots, usable, points, weights)) << i;
    ASSERT_EQ(points.size(), weights.size());
    double sum = 0.0, amplification = 0.0, value = 0.0;
    for (size_t k = 0; k < points.size(); ++k)
    {
      EXPECT_TRUE(usable[static_cast<size_t>(points[k])]);
      sum += weights[k];
      amplification += std::abs(weights[k]);
      value += weights[k] * Quadratic(mesh.Point(points[k]), d);
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "point " << i;
    EXPECT_LE(amplification, mp::FringeRootAmplification);
    EXPECT_NEAR(value, Quadratic(x, d), 1e-12 * amplification) << "point " << i;
    // One parent's nodes, nearest first.
    for (size_t k = 1; k < points.size(); ++k)
    {
      const double* a = mesh.Point(points[k - 1]);
      const double* b = mesh.Point(points[k]);
      double ra = 0.0, rb = 0.0;
      for (int c = 0; c < d; ++c)
      {
        ra += (a[c] - x[c]) * (a[c] - x[c]);
        rb += (b[c] - x[c]) * (b[c] - x[c]);
      }
      EXPECT_LE(ra, rb);
    }
    ++extended;
  }
  EXPECT_GT(extended, 3);
}

TEST(FringeRoots, ReproducesQuadraticsOnStraightTriangles)
{
  ExpectQuadraticRoots(nodaltest::Square(6, 0.2, 3));
}

TEST(FringeRoots, ReproducesQuadraticsOnStraightTetrahedra)
{
  ExpectQuadraticRoots(nodaltest::Cube(3, 0.1, 5));
}

TEST(FringeRoots, CurvedCellsAreNoRoots)
{
  const NodalMesh m = nodaltest::Disk(4);
  const mp::MeshView mesh = m.View();
  int curved = 0;
  for (Index p = 0; p < mesh.Parents(); ++p)
  {
    const Index begin = m.Offsets[static_cast<size_t>(p)];
    double X[3 * mp::MaxNodalNodes];
    for (int n = 0; n < 6; ++n)
    {
      const double* x = mesh.Point(m.Nodes[static_cast<size_t>(begin + n)]);
      std::copy(x, x + 3, X + 3 * n);
    }
    const bool straight = mp::NodalIsStraight(m.Types[static_cast<size_t>(p)], X, 2, 1e-9);
    EXPECT_EQ(mp::IsAffineRoot(mesh, p), straight) << "parent " << p;
    curved += !straight;
  }
  EXPECT_GT(curved, 0);
}
} // namespace
