// SPDX-License-Identifier: BSD-3-Clause
// The advancing front must find exactly the pairs the brute force finds, and
// the pieces of every covered target cell must add up to the cell.
#include "SearchComparison.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

using mp::Index;
using mp::TriangleIntersector;
using mptest::TestMesh;

namespace
{
using Searches = mptest::SearchComparison<TriangleIntersector>;

bool LShape(double x, double y)
{
  return !(x > 0.5 && y > 0.5);
}
bool LShapeWithHole(double x, double y)
{
  return LShape(x, y) && !(x > 0.25 && x < 0.5 && y > 0.25 && y < 0.5) &&
    !(x > 0.0 && x < 0.25 && y > 0.75);
}
} // namespace

TEST(PairSearch, IdenticalMeshes)
{
  const TestMesh m = mptest::GridMesh(12, 9, 0.25, 1);
  Searches s(m, m);
  s.ExpectSamePairs("identical");
  s.ExpectCompleteCover(m, "identical");
}

TEST(PairSearch, UniformRefinementPutsVerticesOnEdges)
{
  // Unjittered, coordinates are multiples of 1/8: the midpoints are exact,
  // so every fine cell lies in exactly one coarse cell.
  const TestMesh coarse = mptest::GridMesh(8, 8, 0.0, 2);
  const TestMesh fine = mptest::Refine(coarse);
  Searches a(coarse, fine);
  a.ExpectSamePairs("coarse <- fine");
  a.ExpectCompleteCover(coarse, "coarse <- fine");
  Searches b(fine, coarse);
  b.ExpectSamePairs("fine <- coarse");
  b.ExpectCompleteCover(fine, "fine <- coarse");
  Index pieces = 0;
  for (const auto& p : b.Front.Pairs)
    pieces += std::get<2>(p) > 0;
  EXPECT_EQ(pieces, fine.NumberOfCells());

  // Jittered: midpoints are rounded, but the front still equals brute force.
  const TestMesh rough = mptest::GridMesh(7, 9, 0.25, 3);
  const TestMesh rougher = mptest::Refine(rough);
  Searches c(rough, rougher);
  c.ExpectSamePairs("jittered refinement");
  c.ExpectCompleteCover(rough, "jittered refinement");
}

TEST(PairSearch, AlignedGridsShareEdgesAndVertices)
{
  // Unjittered grids whose lines coincide: collinear edges, shared vertices.
  const TestMesh a = mptest::GridMesh(6, 6, 0.0, 3);
  const TestMesh b = mptest::GridMesh(12, 18, 0.0, 4);
  Searches s(a, b);
  s.ExpectSamePairs("aligned");
  s.ExpectCompleteCover(a, "aligned");
}

TEST(PairSearch, RandomNonMatchingMeshesOfTheSameDomain)
{
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> size(1, 8);
  for (int n = 0; n < 300; ++n)
  {
    const int mask = n % 3;
    const auto keep = mask == 0 ? std::function<bool(double, double)>()
                                : (mask == 1 ? LShape : LShapeWithHole);
    // Multiples of 4 align every grid with the cut-outs.
    const int na = 4 * size(rng);
    const int nb = 4 * size(rng);
    const TestMesh a = mptest::GridMesh(na, 4 * size(rng), 0.25, rng(), 0, 0, 1, 1, keep);
    const TestMesh b = mptest::GridMesh(nb, 4 * size(rng), 0.25, rng(), 0, 0, 1, 1, keep);
    const std::string what = "case " + std::to_string(n);
    Searches s(a, b);
    s.ExpectSamePairs(what);
    s.ExpectCompleteCover(a, what);
    if (HasFatalFailure())
      return;
  }
}

TEST(PairSearch, RandomPartialOverlapsRotationsAndScalings)
{
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 300; ++n)
  {
    const TestMesh a = mptest::GridMesh(3 + n % 11, 4 + n % 7, 0.25, rng(), 0, 0, 1, 1,
      n % 2 ? std::function<bool(double, double)>(LShapeWithHole) : nullptr);
    TestMesh b = mptest::GridMesh(2 + n % 13, 3 + n % 5, 0.25, rng(), 0, 0, 1, 1,
      n % 3 ? std::function<bool(double, double)>(LShape) : nullptr);
    mptest::Move(b, 6.3 * u(rng), 0.3 + 1.5 * u(rng), u(rng) - 0.5, u(rng) - 0.5);
    Searches s(a, b);
    s.ExpectSamePairs("case " + std::to_string(n));
    if (HasFatalFailure())
      return;
  }
}

TEST(PairSearch, DisconnectedSourceAndNoOverlap)
{
  // Two separate islands of source cells over one target mesh.
  const TestMesh target = mptest::GridMesh(10, 10, 0.2, 5);
  const TestMesh islands = mptest::GridMesh(12, 12, 0.0, 6, 0, 0, 1, 1,
    [](double x, double y) { return (x < 0.3 && y < 0.3) || (x > 0.6 && y > 0.6); });
  Searches s(target, islands);
  s.ExpectSamePairs("islands");
  double covered = 0;
  for (double a : s.CoveredMeasure(target))
    covered += a;
  EXPECT_NEAR(covered, islands.Area(), 1e-13);

  TestMesh away = mptest::GridMesh(4, 4, 0.2, 7);
  mptest::Move(away, 0.0, 1.0, 5.0, 0.0);
  Searches none(target, away);
  EXPECT_TRUE(none.Front.Pairs.empty());
  EXPECT_TRUE(none.Brute.Pairs.empty());
}

TEST(PairSearch, FrontTestsFarFewerPairsThanBruteForce)
{
  const TestMesh a = mptest::GridMesh(40, 40, 0.25, 8);
  const TestMesh b = mptest::GridMesh(33, 37, 0.25, 9);
  Searches s(a, b);
  s.ExpectSamePairs("40x40");
  // Linear work: a bounded number of tests per pair; locator queries only
  // for the first seed and for target cells near the source boundary.
  EXPECT_LT(s.FrontStats.IntersectionTests, 3 * s.FrontStats.TouchingPairs);
  EXPECT_LT(s.FrontStats.LocatorQueries, a.NumberOfCells() / 4);
  EXPECT_EQ(s.BruteStats.IntersectionTests, a.NumberOfCells() * b.NumberOfCells());
}
