// SPDX-License-Identifier: BSD-3-Clause
// LinearReconstruction (Transfer/LinearReconstruction.h): a linear field's
// cell averages give it back at every corner (cells split into simplices,
// surfaces, curves, holes of missing values); the limiter keeps every corner
// within the range of its cell and its neighbours; the constant mode and a
// lone cell give the cell's value; the mean over each cell is its value.
#include "Transfer/LinearReconstruction.h"

#include "GeneratedMeshes.h"
#include "Threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace
{
using mp::Index;
using mptest::TestMesh;

double Linear(const double* x)
{
  return 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2];
}

/// The mesh's cells two by two as parents (quads made of two triangles,
/// ...): cell c's parent is c / 2.
std::vector<Index> Pairs(const TestMesh& m)
{
  std::vector<Index> parent(static_cast<size_t>(m.NumberOfCells()));
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    parent[c] = c / 2;
  }
  return parent;
}

mp::MeshView WithParents(const TestMesh& m, const std::vector<Index>& parent)
{
  mp::MeshView view = m.View(false);
  if (!parent.empty())
  {
    view.Parent = parent.data();
    view.NumberOfParents = *std::max_element(parent.begin(), parent.end()) + 1;
  }
  return view;
}

/// Per parent: the linear field's mean (its value at the parent's centroid).
std::vector<double> Averages(const mp::LinearReconstruction& r, const mp::MeshView& view)
{
  std::vector<double> u(static_cast<size_t>(view.Parents()));
  for (Index p = 0; p < view.Parents(); ++p)
  {
    double c[3] = { 0.0, 0.0, 0.0 };
    std::copy(r.Centroid(p), r.Centroid(p) + view.SpaceDimension, c);
    u[p] = Linear(c);
  }
  return u;
}

/// The largest difference between the corner values and the linear field at the corners.
double LinearError(const mp::MeshView& view, const std::vector<double>& corners)
{
  double worst = 0.0;
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    for (int k = 0; k < view.CornersPerCell(); ++k)
    {
      double x[3] = { 0.0, 0.0, 0.0 };
      std::copy(view.Point(view.Cell(c)[k]), view.Point(view.Cell(c)[k]) + view.SpaceDimension, x);
      worst = std::max(worst, std::fabs(corners[c * view.CornersPerCell() + k] - Linear(x)));
    }
  }
  return worst;
}

std::vector<double> Reconstructed(const mp::LinearReconstruction& r, const mp::MeshView& view,
  const std::vector<double>& u, const char* defined, mp::Reconstruction mode, int tasks = 1)
{
  std::vector<double> corners(static_cast<size_t>(view.NumberOfCells * view.CornersPerCell()));
  r.Reconstruct(u.data(), 1, defined, mode, mptest::ThreadRunner(tasks), corners.data());
  return corners;
}

void ExpectLinearExact(const TestMesh& m, bool pairs, const char* what)
{
  const std::vector<Index> parent = pairs ? Pairs(m) : std::vector<Index>();
  const mp::MeshView view = WithParents(m, parent);
  mp::LinearReconstruction r;
  r.Prepare(view, mptest::ThreadRunner(2));
  const std::vector<double> u = Averages(r, view);
  for (int tasks : { 1, 2 })
  {
    const std::vector<double> corners =
      Reconstructed(r, view, u, nullptr, mp::Reconstruction::Unlimited, tasks);
    EXPECT_LT(LinearError(view, corners), 1e-12) << what << ", " << tasks << " tasks";
  }
  // The constant mode is not exact (the check can fail).
  const std::vector<double> constant =
    Reconstructed(r, view, u, nullptr, mp::Reconstruction::Constant);
  EXPECT_GT(LinearError(view, constant), 1e-3) << what;
}
} // namespace

TEST(LinearReconstruction, LinearFieldsExactOnTrianglesAndSplitQuads)
{
  TestMesh m = mptest::GridMesh(9, 7, 0.3, 1);
  ExpectLinearExact(m, false, "triangles");
  ExpectLinearExact(m, true, "pairs of triangles");
}

TEST(LinearReconstruction, LinearFieldsExactOnTetrahedra)
{
  TestMesh m = mptest::CubeMesh(4, 3, 4, 0.2, 2);
  ExpectLinearExact(m, false, "tetrahedra");
  ExpectLinearExact(m, true, "pairs of tetrahedra");
}

TEST(LinearReconstruction, LinearFieldsExactOnSurfacesAndCurves)
{
  // A planar grid tilted in space: the gradient lies in its plane.
  TestMesh m = mptest::GridMesh(8, 8, 0.3, 3);
  mptest::Move3D(m, 0.4, 0.7, 1.0, 0.1, -0.2, 0.3);
  m.Surface = true;
  ExpectLinearExact(m, true, "tilted surface");
  // A straight curve in space.
  TestMesh curve = mptest::Polyline(
    mptest::Uniform(20, 0.0, 1.0, 0.3, 4, false),
    [](double s, double* x) {
      x[0] = 0.8 * s;
      x[1] = 0.5 * s;
      x[2] = -0.3 * s;
    },
    false, 3);
  ExpectLinearExact(curve, false, "curve in space");
}

TEST(LinearReconstruction, HolesUseTheNeighboursLeft)
{
  TestMesh m = mptest::GridMesh(10, 10, 0.3, 5);
  const mp::MeshView view = m.View(false);
  mp::LinearReconstruction r;
  r.Prepare(view, mptest::ThreadRunner(1));
  std::vector<double> u = Averages(r, view);
  std::vector<char> defined(u.size(), 1);
  for (Index p = 0; p < view.Parents(); ++p)
  {
    const double* c = r.Centroid(p);
    if (std::hypot(c[0] - 0.5, c[1] - 0.5) < 0.2)
    {
      defined[p] = 0;
      u[p] = 1e30; // never read
    }
  }
  const std::vector<double> corners =
    Reconstructed(r, view, u, defined.data(), mp::Reconstruction::Unlimited);
  double worst = 0.0;
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double value = corners[3 * c + k];
      if (defined[c])
      {
        worst = std::max(worst, std::fabs(value - Linear(view.Point(view.Cell(c)[k]))));
      }
      else
      {
        EXPECT_EQ(value, 0.0);
      }
    }
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(LinearReconstruction, LimiterKeepsCornersWithinTheNeighbours)
{
  TestMesh m = mptest::CubeMesh(5, 5, 5, 0.2, 6);
  const mp::MeshView view = m.View(false);
  mp::LinearReconstruction r;
  r.Prepare(view, mptest::ThreadRunner(1));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> u(static_cast<size_t>(view.Parents()));
  for (double& v : u)
  {
    v = unit(random);
  }
  const std::vector<double> limited =
    Reconstructed(r, view, u, nullptr, mp::Reconstruction::Limited);
  const std::vector<double> unlimited =
    Reconstructed(r, view, u, nullptr, mp::Reconstruction::Unlimited);
  bool overshoots = false;
  std::vector<Index> neighbors;
  for (Index p = 0; p < view.Parents(); ++p)
  {
    r.NeighborsOf(p, neighbors);
    double low = u[p], high = u[p];
    for (Index q : neighbors)
    {
      low = std::min(low, u[q]);
      high = std::max(high, u[q]);
    }
    double mean = 0.0;
    for (int k = 0; k < 4; ++k)
    {
      const double v = limited[4 * p + k];
      EXPECT_GE(v, low - 1e-14);
      EXPECT_LE(v, high + 1e-14);
      overshoots |= unlimited[4 * p + k] < low - 1e-3 || unlimited[4 * p + k] > high + 1e-3;
      mean += v / 4;
    }
    // The corners' mean is the value at the centroid: the cell's value.
    EXPECT_NEAR(mean, u[p], 1e-14);
  }
  EXPECT_TRUE(overshoots) << "the unlimited reconstruction overshoots on random data";
}

TEST(LinearReconstruction, LoneCellKeepsItsValue)
{
  TestMesh m;
  m.Dimension = 2;
  m.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  m.Cells = { 0, 1, 2 };
  const mp::MeshView view = m.View(false);
  mp::LinearReconstruction r;
  r.Prepare(view, mptest::ThreadRunner(1));
  const std::vector<double> corners =
    Reconstructed(r, view, std::vector<double>{ 4.0 }, nullptr, mp::Reconstruction::Unlimited);
  for (double v : corners)
  {
    EXPECT_EQ(v, 4.0);
  }
}

TEST(LinearReconstruction, CopiesOfAPointAreOnePoint)
{
  // Two triangles on their own copies of the shared edge's points (a
  // composite dataset's blocks, gathered parts, unmerged points): still
  // neighbours; a linear field exact.
  TestMesh m;
  m.Dimension = 2;
  m.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
  m.Cells = { 0, 1, 2, 3, 4, 5 };
  const mp::MeshView view = m.View(false);
  mp::LinearReconstruction r;
  r.Prepare(view, mptest::ThreadRunner(1));
  EXPECT_TRUE(r.JoinsCopies());
  std::vector<Index> neighbors;
  r.NeighborsOf(0, neighbors);
  EXPECT_EQ(neighbors, std::vector<Index>{ 1 });
  // Every cell of a grid on points of its own.
  TestMesh grid = mptest::GridMesh(6, 5, 0.3, 8);
  TestMesh apart;
  apart.Dimension = 2;
  for (Index c = 0; c < grid.NumberOfCells(); ++c)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double* x = &grid.Points[3 * grid.Cells[3 * c + k]];
      apart.Points.insert(apart.Points.end(), x, x + 3);
      apart.Cells.push_back(3 * c + k);
    }
  }
  ExpectLinearExact(apart, false, "cells on points of their own");
}

TEST(LinearReconstruction, CellsOfZeroMeasureAreNoNeighbours)
{
  // A straight curve with a repeated point (a segment of zero length): its
  // neighbours' gradients as without it.
  TestMesh curve = mptest::Polyline(
    { 0.0, 0.1, 0.25, 0.25, 0.4, 0.6, 0.7, 1.0 },
    [](double s, double* x) {
      x[0] = 0.8 * s;
      x[1] = 0.5 * s;
      x[2] = 0.0;
    },
    false, 2);
  const mp::MeshView view = curve.View(false);
  mp::LinearReconstruction r;
  r.Prepare(view, mptest::ThreadRunner(1));
  std::vector<double> u = Averages(r, view);
  u[2] = 1e3; // the zero-length segment's value: read by no one
  const std::vector<double> corners =
    Reconstructed(r, view, u, nullptr, mp::Reconstruction::Unlimited);
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    for (int k = 0; c != 2 && k < 2; ++k)
    {
      double x[3] = { 0.0, 0.0, 0.0 };
      std::copy(view.Point(view.Cell(c)[k]), view.Point(view.Cell(c)[k]) + 2, x);
      EXPECT_NEAR(corners[2 * c + k], Linear(x), 1e-12) << "segment " << c;
    }
  }
}
