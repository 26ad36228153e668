// SPDX-License-Identifier: BSD-3-Clause
// The space of non-affine serendipity cells (Geometry/HiddenNodes.h) as
// NodalFunctions (Transfer/NodalSpace.h) evaluates it: every quadratic of
// the physical coordinates on straight but non-affine Quad8, Hexa20 and
// Wedge15 cells (a trapezoid, a frustum, an extruded trapezoid, a wedge
// with a tilted top), linear fields on curved ones, the serendipity
// weights on affine cells, and the same face-centre weights from both
// cells on a face.
#include "Geometry/HiddenNodes.h"
#include "Transfer/NodalSpace.h"
#include "NodalMeshes.h"
#include "NodalTestCells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace
{
using mp::Index;
using mp::NodalType;
using namespace nodaltest;

/// A mesh of one cell with nodes X (3 per node), its points stored in a
/// shuffled order (so that ids and local numbers differ), and one simplex
/// on its first corners.
NodalMesh OneCell(NodalType type, const std::vector<double>& X, std::mt19937& rng, int space)
{
  const int count = mp::NodalNodeCount(type);
  std::vector<Index> ids(count);
  std::iota(ids.begin(), ids.end(), 0);
  std::shuffle(ids.begin(), ids.end(), rng);
  NodalMesh m;
  m.Dimension = mp::NodalCellDimension(type);
  m.Space = space;
  m.Points.assign(3 * count, 0.0);
  for (int n = 0; n < count; ++n)
  {
    std::copy(&X[3 * n], &X[3 * n] + 3, &m.Points[3 * ids[n]]);
  }
  m.Types.push_back(type);
  m.Nodes = ids;
  m.Offsets.push_back(count);
  if (m.Dimension == 2)
  {
    m.Simplex({ ids[0], ids[1], ids[2] });
  }
  else
  {
    m.Simplex({ ids[0], ids[1], ids[2], ids[3] });
  }
  m.Finish();
  return m;
}

/// The cell's own map at xi: sum_n N_n(xi) X_n.
std::array<double, 3> Map(NodalType type, const std::vector<double>& X, const double* xi)
{
  double N[mp::MaxNodalNodes];
  mp::NodalValues(type, xi, N);
  std::array<double, 3> x{};
  for (int n = 0; n < mp::NodalNodeCount(type); ++n)
  {
    for (int a = 0; a < 3; ++a)
    {
      x[a] += N[n] * X[3 * n + a];
    }
  }
  return x;
}

/// The monomials of degree <= `degree` (1 or 2) in d coordinates of x.
std::vector<double> Monomials(int d, const double* x, int degree)
{
  std::vector<double> m{ 1.0 };
  for (int a = 0; a < d; ++a)
  {
    m.push_back(x[a]);
  }
  for (int a = 0; a < d && degree == 2; ++a)
  {
    for (int b = a; b < d; ++b)
    {
      m.push_back(x[a] * x[b]);
    }
  }
  return m;
}

/**
 * The worst error, over random points inside the cell and the monomials of
 * `degree`, of the bound functions' interpolant of each monomial, relative
 * to the monomial's largest value at the nodes.
 */
double WorstMonomialError(
  NodalType type, const std::vector<double>& X, int space, int degree, std::mt19937& rng)
{
  const NodalMesh mesh = OneCell(type, X, rng, space);
  mp::NodalFunctions f;
  f.Bind(mesh.View(), mp::SpaceType::P1, 0);
  EXPECT_FALSE(f.IsAffine());
  const int count = mp::NodalNodeCount(type);
  double worst = 0.0;
  for (int trial = 0; trial < 50; ++trial)
  {
    double xi[3];
    RandomReferencePoint(type, rng, -0.05, xi);
    const std::array<double, 3> x = Map(type, X, xi);
    double phi[mp::MaxNodalFunctions];
    f.Values(x.data(), phi);
    const std::vector<double> exact = Monomials(space, x.data(), degree);
    std::vector<double> sum(exact.size(), 0.0), range(exact.size(), 0.0);
    for (int i = 0; i < count; ++i)
    {
      const std::vector<double> at = Monomials(space, mesh.Point(f.Dofs[i]), degree);
      for (size_t m = 0; m < at.size(); ++m)
      {
        sum[m] += phi[i] * at[m];
        range[m] = std::max(range[m], std::fabs(at[m]));
      }
    }
    for (size_t m = 0; m < exact.size(); ++m)
    {
      worst = std::max(worst, std::fabs(sum[m] - exact[m]) / range[m]);
    }
  }
  return worst;
}

std::vector<double> Trapezoid()
{
  return StraightCell(NodalType::Quad8, { 0.1, 0.2, 0, 2.3, -0.1, 0, 1.6, 1.1, 0, 0.4, 1.3, 0 });
}

std::vector<double> Frustum()
{
  return StraightCell(NodalType::Hexa20,
    { 0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0, 0.5, 0.4, 1, 1.5, 0.4, 1, 1.5, 1.4, 1, 0.5, 1.4, 1 });
}

std::vector<double> ExtrudedTrapezoid()
{
  return StraightCell(NodalType::Hexa20,
    { 0.1, 0.2, 0, 2.3, -0.1, 0, 1.6, 1.1, 0, 0.4, 1.3, 0, 0.1, 0.2, 0.7, 2.3, -0.1, 0.7, 1.6, 1.1,
      0.7, 0.4, 1.3, 0.7 });
}

/// Its three side faces planar (y = 0, x = 0, x + y = 1), its top tilted.
std::vector<double> TiltedWedge()
{
  return StraightCell(
    NodalType::Wedge15, { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1.5, 0, 1, 0.6 });
}

/// Mid nodes moved off their straight places by up to `amount`.
std::vector<double> Curved(NodalType type, std::vector<double> X, double amount, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-amount, amount);
  for (int n = mp::NodalCornerCount(type); n < mp::NodalNodeCount(type); ++n)
  {
    for (int a = 0; a < mp::NodalCellDimension(type); ++a)
    {
      X[3 * n + a] += u(rng);
    }
  }
  return X;
}

TEST(HiddenNodes, Siblings)
{
  EXPECT_EQ(mp::CompleteSibling(NodalType::Quad8), NodalType::Quad9);
  EXPECT_EQ(mp::CompleteSibling(NodalType::Hexa20), NodalType::Hexa27);
  EXPECT_EQ(mp::CompleteSibling(NodalType::Wedge15), NodalType::Wedge18);
  EXPECT_EQ(mp::CompleteSibling(NodalType::Pyramid13), NodalType::None);
  EXPECT_EQ(mp::CompleteSibling(NodalType::Quad9), NodalType::None);
}

TEST(HiddenNodes, QuadraticsOnStraightNonAffineCells)
{
  std::mt19937 rng(54);
  EXPECT_LT(WorstMonomialError(NodalType::Quad8, Trapezoid(), 2, 2, rng), 1e-12);
  EXPECT_LT(WorstMonomialError(NodalType::Hexa20, Frustum(), 3, 2, rng), 1e-12);
  EXPECT_LT(WorstMonomialError(NodalType::Hexa20, ExtrudedTrapezoid(), 3, 2, rng), 1e-12);
  EXPECT_LT(WorstMonomialError(NodalType::Wedge15, TiltedWedge(), 3, 2, rng), 1e-12);
  // A planar trapezoid in space (a shell cell), tilted out of z = 0.
  std::vector<double> shell = Trapezoid();
  for (size_t n = 0; n < shell.size(); n += 3)
  {
    shell[n + 2] = 0.3 * shell[n] - 0.2 * shell[n + 1] + 1.0;
  }
  EXPECT_LT(WorstMonomialError(NodalType::Quad8, shell, 3, 2, rng), 1e-12);
}

TEST(HiddenNodes, SerendipityAloneMissesThem)
{
  // The check above can fail: the serendipity functions by themselves on
  // the same trapezoid miss x^2 at its centre.
  const std::vector<double> X = Trapezoid();
  const double centre[3] = { 0.5, 0.5, 0.0 };
  double N[8];
  mp::NodalValues(NodalType::Quad8, centre, N);
  const std::array<double, 3> x = Map(NodalType::Quad8, X, centre);
  double sum = 0.0;
  for (int n = 0; n < 8; ++n)
  {
    sum += N[n] * X[3 * n] * X[3 * n];
  }
  EXPECT_GT(std::fabs(sum - x[0] * x[0]), 1e-3);
}

TEST(HiddenNodes, LinearFieldsOnCurvedCells)
{
  std::mt19937 rng(7);
  EXPECT_LT(WorstMonomialError(
              NodalType::Quad8, Curved(NodalType::Quad8, Trapezoid(), 0.15, rng), 2, 1, rng),
    1e-12);
  EXPECT_LT(WorstMonomialError(
              NodalType::Hexa20, Curved(NodalType::Hexa20, Frustum(), 0.1, rng), 3, 1, rng),
    1e-12);
  EXPECT_LT(WorstMonomialError(
              NodalType::Wedge15, Curved(NodalType::Wedge15, TiltedWedge(), 0.05, rng), 3, 1, rng),
    1e-12);
}

TEST(HiddenNodes, SmoothlyBentCellsKeepBoundedWeights)
{
  // Small frustums and wedges bent by a smooth map (their faces curved
  // alike, as a mesh bent whole): the weights stay near the serendipity
  // ones (a face's normal coordinate, nearly affine in the others there,
  // must not make its constraints nearly dependent) and linear fields
  // stay exact.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double largest = 0.0, linear = 0.0;
  for (int trial = 0; trial < 60; ++trial)
  {
    const NodalType type = trial % 2 ? NodalType::Hexa20 : NodalType::Wedge15;
    std::vector<double> X = type == NodalType::Hexa20 ? Frustum() : TiltedWedge();
    const double offset[3] = { u(rng), u(rng), u(rng) };
    for (size_t n = 0; n < X.size(); n += 3)
    {
      double y[3];
      for (int a = 0; a < 3; ++a)
      {
        y[a] = offset[a] + 0.12 * X[n + a];
      }
      X[n] = y[0] + 0.04 * std::sin(3.0 * y[1]);
      X[n + 1] = y[1] + 0.04 * std::sin(3.0 * y[2]);
      X[n + 2] = y[2] + 0.04 * std::sin(3.0 * y[0]);
    }
    const int own = mp::NodalNodeCount(type);
    const int hidden = mp::NodalNodeCount(mp::CompleteSibling(type)) - own;
    std::vector<Index> ids(own);
    std::iota(ids.begin(), ids.end(), 0);
    std::shuffle(ids.begin(), ids.end(), rng);
    std::vector<double> W(hidden * own);
    mp::HiddenNodeWeights(type, X.data(), ids.data(), 3, W.data());
    for (double w : W)
    {
      largest = std::max(largest, std::fabs(w));
    }
    linear = std::max(linear, WorstMonomialError(type, X, 3, 1, rng));
  }
  EXPECT_LT(largest, 0.6);
  EXPECT_LT(linear, 1e-12);
}

TEST(HiddenNodes, SerendipityWeightsOnAffineCells)
{
  std::mt19937 rng(3);
  for (NodalType type : { NodalType::Quad8, NodalType::Hexa20, NodalType::Wedge15 })
  {
    const std::vector<double> X = StraightCell(type, MappedCorners(type, rng, 0.0));
    const int own = mp::NodalNodeCount(type);
    const int hidden = mp::NodalNodeCount(mp::CompleteSibling(type)) - own;
    std::vector<Index> ids(own);
    std::iota(ids.begin(), ids.end(), 0);
    std::vector<double> W(hidden * own);
    mp::HiddenNodeWeights(type, X.data(), ids.data(), mp::NodalCellDimension(type), W.data());
    const std::vector<double> reference = ReferenceNodes(mp::CompleteSibling(type));
    for (int h = 0; h < hidden; ++h)
    {
      double N[mp::MaxNodalNodes];
      mp::NodalValues(type, &reference[3 * (own + h)], N);
      for (int n = 0; n < own; ++n)
      {
        EXPECT_NEAR(W[h * own + n], N[n], 1e-13) << int(type) << " hidden " << h << " node " << n;
      }
    }
    // NodalFunctions keeps such a cell on its affine path.
    const NodalMesh mesh = OneCell(type, X, rng, mp::NodalCellDimension(type));
    mp::NodalFunctions f;
    f.Bind(mesh.View(), mp::SpaceType::P1, 0);
    EXPECT_TRUE(f.IsAffine());
    EXPECT_EQ(f.Degree, mp::NodalDegree(type));
  }
}

TEST(HiddenNodes, FaceCentresAgreeAcrossFaces)
{
  // Two frustums stacked: the lower one's top face is the upper one's
  // bottom, numbered differently in each.
  const std::vector<double> lower = Frustum();
  std::vector<double> upper = StraightCell(NodalType::Hexa20,
    { 0.5, 0.4, 1, 1.5, 0.4, 1, 1.5, 1.4, 1, 0.5, 1.4, 1, 0.2, 0.1, 2, 1.9, 0.3, 2, 1.8, 1.6, 2,
      0.3, 1.7, 2.2 });
  // Global ids: the shared face's nodes (lower 4..7, 12..15 = upper 0..3,
  // 8..11) get the same numbers; the others their own.
  std::vector<Index> lowerIds(20), upperIds(20);
  std::iota(lowerIds.begin(), lowerIds.end(), 100);
  std::iota(upperIds.begin(), upperIds.end(), 200);
  const int lowerTop[8] = { 4, 5, 6, 7, 12, 13, 14, 15 };
  const int upperBottom[8] = { 0, 1, 2, 3, 8, 9, 10, 11 };
  for (int k = 0; k < 8; ++k)
  {
    upperIds[upperBottom[k]] = lowerIds[lowerTop[k]];
  }
  std::vector<double> Wl(7 * 20), Wu(7 * 20);
  mp::HiddenNodeWeights(NodalType::Hexa20, lower.data(), lowerIds.data(), 3, Wl.data());
  mp::HiddenNodeWeights(NodalType::Hexa20, upper.data(), upperIds.data(), 3, Wu.data());
  // Hexa27's node 25 is the face z = 1, node 24 the face z = 0.
  const int top = 25 - 20, bottom = 24 - 20;
  double sum = 0.0;
  for (int k = 0; k < 8; ++k)
  {
    EXPECT_EQ(Wl[top * 20 + lowerTop[k]], Wu[bottom * 20 + upperBottom[k]]);
    sum += Wl[top * 20 + lowerTop[k]];
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
  for (int n = 0; n < 20; ++n)
  {
    if (std::find(lowerTop, lowerTop + 8, n) == lowerTop + 8)
    {
      EXPECT_EQ(Wl[top * 20 + n], 0.0); // only the face's own nodes
    }
  }
}
} // namespace
