// SPDX-License-Identifier: BSD-3-Clause
// The advancing front must find exactly the pairs the brute force finds, and
// the pieces of every covered target cell must add up to the cell.
#include "SearchComparison.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
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
    const auto keep =
      mask == 0 ? std::function<bool(double, double)>() : (mask == 1 ? LShape : LShapeWithHole);
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
  // Same domain: one walk starts the front, the source boundary is asked
  // about its own cells only, and no index over all source cells is needed.
  EXPECT_EQ(s.FrontStats.SeedWalks, 1);
  EXPECT_GT(s.FrontStats.LocatorQueries, 0);
  EXPECT_EQ(s.FrontStats.FullLocatorQueries, 0);
}

TEST(PairSearch, AllSourceCellsAskedOnlyWhereTheBoundaryCannotTell)
{
  // A target reaching beyond the source: its outer cells meet no source
  // boundary cell; in the plane a ray from a corner proves them outside,
  // so no query among all source cells is needed.
  const TestMesh source = mptest::GridMesh(10, 10, 0.25, 21, 0.3, 0.3, 0.7, 0.7);
  const TestMesh target = mptest::GridMesh(12, 12, 0.25, 22);
  Searches out(target, source);
  out.ExpectSamePairs("target around the source");
  EXPECT_GT(out.FrontStats.OutsideCells, 0);
  EXPECT_EQ(out.FrontStats.FullLocatorQueries, 0);
  // A target inside a source with holes: walks toward cells past a hole
  // stop at its boundary, the boundary cells nearby settle the rest.
  const TestMesh holed = mptest::GridMesh(16, 16, 0.25, 23, 0, 0, 1, 1, LShapeWithHole);
  const TestMesh inside = mptest::GridMesh(11, 13, 0.25, 24, 0.05, 0.05, 0.45, 0.95);
  Searches in(inside, holed);
  in.ExpectSamePairs("target over holes");
}

TEST(PairSearch, RayFromAPointOutsideWindsZeroTimes)
{
  // Unjittered 16 x 16 grid of the unit square: an L with a square hole and
  // a notch. Points in the hole, the notch, the missing corner and beyond
  // are outside; points in the source are not (the boundary faces wind
  // once around them), nor are points on a boundary face's line
  // within its span (no verdict).
  const TestMesh holed = mptest::GridMesh(16, 16, 0.0, 23, 0, 0, 1, 1, LShapeWithHole);
  mp::BoxGridLocator locator(holed.View());
  const double outside[][3] = { { 0.375, 0.375, 0 }, { 0.1, 0.9, 0 }, { 0.8, 0.8, 0 },
    { -0.5, 0.3, 0 }, { 1.5, 0.3, 0 }, { 0.3, -2.0, 0 }, { 0.3, 1.5, 0 } };
  for (const auto& q : outside)
  {
    EXPECT_TRUE(locator.Outside(q)) << q[0] << ", " << q[1];
  }
  const double notProven[][3] = { { 0.1, 0.1, 0 }, { 0.6, 0.2, 0 }, { 0.1, 0.6, 0 },
    { 0.3, 0.8, 0 }, { 0.2, 0.3, 0 }, { 0.5, 0.3, 0 } };
  for (const auto& q : notProven)
  {
    EXPECT_FALSE(locator.Outside(q)) << q[0] << ", " << q[1];
  }
}

namespace
{
/// Mesh `b`'s points and cells after `a`'s in one mesh (no point merged),
/// b's cells turned clockwise when `flip`; with neighbours.
TestMesh Unmerged(const TestMesh& a, TestMesh b, bool flip)
{
  TestMesh m = a;
  const Index offset = a.NumberOfPoints();
  for (size_t c = 0; c + 2 < b.Cells.size(); c += 3)
  {
    if (flip)
    {
      std::swap(b.Cells[c + 1], b.Cells[c + 2]);
    }
    for (int k = 0; k < 3; ++k)
    {
      m.Cells.push_back(b.Cells[c + k] + offset);
    }
  }
  m.Points.insert(m.Points.end(), b.Points.begin(), b.Points.end());
  m.Finish();
  return m;
}
} // namespace

TEST(PairSearch, RayCountsOverlappingLayersAndFoldsAsInside)
{
  // Two unmerged layers overlapping on [0.4, 1] x [0, 1] (overset blocks),
  // the second turned clockwise: a point in both is held twice (its
  // crossings are even, its winding number 2), not outside.
  const TestMesh left = mptest::GridMesh(10, 10, 0.25, 31, 0.0, 0.0, 1.0, 1.0);
  const TestMesh right = mptest::GridMesh(10, 10, 0.25, 32, 0.4, 0.0, 1.4, 1.0);
  for (bool flip : { false, true })
  {
    const TestMesh layers = Unmerged(left, right, flip);
    mp::BoxGridLocator locator(layers.View());
    const double both[][3] = { { 0.55, 0.5, 0 }, { 0.7, 0.33, 0 }, { 0.85, 0.61, 0 } };
    for (const auto& q : both)
    {
      EXPECT_FALSE(locator.Outside(q)) << "in both layers: " << q[0] << ", " << q[1];
    }
    const double one[][3] = { { 0.2, 0.5, 0 }, { 1.2, 0.5, 0 } };
    for (const auto& q : one)
    {
      EXPECT_FALSE(locator.Outside(q)) << "in one layer: " << q[0] << ", " << q[1];
    }
    const double none[][3] = { { -0.3, 0.5, 0 }, { 1.6, 0.5, 0 }, { 0.7, 1.3, 0 } };
    for (const auto& q : none)
    {
      EXPECT_TRUE(locator.Outside(q)) << "in no layer: " << q[0] << ", " << q[1];
    }
  }
  // One mesh folded over itself: its cells right of x = 0.5 mirrored onto
  // the left half (points shared along the fold). Left of the fold every
  // point is held twice, with no boundary face crossed to its right: the
  // winding number is 0 there, so no verdict (the fold is seen).
  TestMesh folded = mptest::GridMesh(10, 10, 0.0, 33);
  for (size_t p = 0; p + 2 < folded.Points.size(); p += 3)
  {
    folded.Points[p] = folded.Points[p] > 0.5 ? 1.0 - folded.Points[p] : folded.Points[p];
  }
  folded.Finish();
  mp::BoxGridLocator foldLocator(folded.View());
  const double doubled[3] = { 0.27, 0.43, 0 };
  EXPECT_FALSE(foldLocator.Outside(doubled));
  const double beyond[3] = { -0.5, 0.43, 0 };
  EXPECT_FALSE(foldLocator.Outside(beyond)); // no verdict anywhere on a folded source
}

TEST(PairSearch, WalkStoppedByAHoleStartsAgainNearTheCell)
{
  // The first walk starts at source cell 0 (bottom left) and heads for a
  // target beyond a hole in the middle of the source, along the diagonal
  // through the hole's middle: the hole stops it (for any jitter of the
  // grid). A second walk, from the sampled source cell nearest the target
  // cell, starts the front without a query among all source cells.
  auto holed = [](double x, double y) { return !(x > 0.3 && x < 0.7 && y > 0.3 && y < 0.7); };
  const TestMesh source = mptest::GridMesh(40, 40, 0.25, 31, 0, 0, 1, 1, holed);
  const TestMesh target = mptest::GridMesh(6, 6, 0.25, 32, 0.8, 0.8, 0.95, 0.95);
  Searches s(target, source);
  s.ExpectSamePairs("beyond a hole");
  s.ExpectCompleteCover(target, "beyond a hole");
  EXPECT_EQ(s.FrontStats.SeedWalks, 1);
  EXPECT_EQ(s.FrontStats.WalkRestarts, 1);
  EXPECT_EQ(s.FrontStats.FullLocatorQueries, 0);
}

TEST(PairSearch, TargetOfDisconnectedCellsInRandomOrder)
{
  // Every target cell its own piece (no shared points), in random order:
  // each cell starts a front of its own. Walks toward them stay within
  // their budget (linear in the cells), then the locator seeds the rest.
  const TestMesh grid = mptest::GridMesh(30, 30, 0.25, 27);
  TestMesh soup;
  std::vector<Index> order(static_cast<size_t>(grid.NumberOfCells()));
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<Index>(i);
  std::shuffle(order.begin(), order.end(), std::mt19937(28));
  for (Index c : order)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Index p = grid.Cells[3 * c + k];
      soup.Cells.push_back(soup.NumberOfPoints());
      soup.Points.insert(
        soup.Points.end(), grid.Points.begin() + 3 * p, grid.Points.begin() + 3 * p + 3);
    }
  }
  soup.Finish();
  const TestMesh source = mptest::GridMesh(41, 37, 0.25, 29);
  Searches s(soup, source);
  s.ExpectSamePairs("target soup");
  s.ExpectCompleteCover(soup, "target soup");
  const Index cells = soup.NumberOfCells();
  const Index maxWalk = 100 + 4 * static_cast<Index>(std::sqrt(double(source.NumberOfCells())));
  EXPECT_LE(s.FrontStats.WalkSteps, 16 * cells + 64 * maxWalk + maxWalk);
  EXPECT_GT(s.FrontStats.FullLocatorQueries, 0); // the budget ran out: the locator took over
}

TEST(PairSearch, ZeroAreaSourceCellsDoNotCutTheFrontOff)
{
  // Two halves of a grid joined only through zero-area triangles: the
  // points on x = 0.5 exist twice (left and right copies), and a fan of
  // needles (p_i, p_i+1, p'_i), (p'_i, p_i+1, p'_i+1) stitches the copies.
  TestMesh source = mptest::GridMesh(8, 8, 0.0, 25);
  const Index n = source.NumberOfPoints();
  std::vector<Index> copy(static_cast<size_t>(n), -1);
  std::vector<std::pair<double, Index>> seam; // (y, left id) of the points on x = 0.5
  for (Index p = 0; p < n; ++p)
  {
    if (source.Points[3 * p] == 0.5)
    {
      copy[p] = source.NumberOfPoints();
      source.Points.insert(
        source.Points.end(), { 0.5, source.Points[3 * p + 1], source.Points[3 * p + 2] });
      seam.emplace_back(source.Points[3 * p + 1], p);
    }
  }
  ASSERT_EQ(seam.size(), size_t(9));
  for (Index c = 0; c < source.NumberOfCells(); ++c)
  {
    double cx = 0;
    for (int k = 0; k < 3; ++k)
      cx += source.Points[3 * source.Cells[3 * c + k]] / 3;
    for (int k = 0; k < 3 && cx > 0.5; ++k)
    {
      Index& id = source.Cells[3 * c + k];
      id = copy[id] >= 0 ? copy[id] : id; // the right half uses the copies
    }
  }
  std::sort(seam.begin(), seam.end());
  for (size_t i = 0; i + 1 < seam.size(); ++i)
  {
    const Index a = seam[i].second;
    const Index b = seam[i + 1].second;
    source.Cells.insert(source.Cells.end(), { a, b, copy[a], copy[a], b, copy[b] });
  }
  source.Finish();
  const TestMesh target = mptest::GridMesh(7, 9, 0.25, 26);
  Searches s(target, source);
  s.ExpectSamePairs("zero-area seam");
  s.ExpectCompleteCover(target, "zero-area seam");
  // The seam is no boundary: no cell needs a query among all source cells.
  EXPECT_EQ(s.FrontStats.FullLocatorQueries, 0);
}

namespace
{
/// Moves interior source points onto nearby target points or target edge
/// midpoints (when no source triangle turns over), so that vertices of one
/// mesh lie on vertices and edges of the other.
void Snap(TestMesh& source, const TestMesh& target, double radius)
{
  std::vector<char> boundary(static_cast<size_t>(source.NumberOfPoints()), 0);
  for (Index c = 0; c < source.NumberOfCells(); ++c)
    for (int k = 0; k < 3; ++k)
      if (source.Neighbors[3 * c + k] < 0)
      {
        boundary[source.Cells[3 * c + (k + 1) % 3]] = 1;
        boundary[source.Cells[3 * c + (k + 2) % 3]] = 1;
      }
  std::vector<double> spots = target.Points;
  for (Index c = 0; c < target.NumberOfCells(); ++c)
    for (int k = 0; k < 3; ++k)
    {
      const double* a = &target.Points[3 * target.Cells[3 * c + k]];
      const double* b = &target.Points[3 * target.Cells[3 * c + (k + 1) % 3]];
      spots.insert(spots.end(), { 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.0 });
    }
  auto positive = [&]() {
    for (Index c = 0; c < source.NumberOfCells(); ++c)
    {
      const double* a = &source.Points[3 * source.Cells[3 * c]];
      const double* b = &source.Points[3 * source.Cells[3 * c + 1]];
      const double* d = &source.Points[3 * source.Cells[3 * c + 2]];
      if ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]) <= 0)
        return false;
    }
    return true;
  };
  for (Index p = 0; p < source.NumberOfPoints(); ++p)
  {
    if (boundary[p])
      continue;
    double* x = &source.Points[3 * p];
    for (size_t q = 0; q < spots.size(); q += 3)
    {
      if (std::hypot(spots[q] - x[0], spots[q + 1] - x[1]) < radius)
      {
        const double old[2] = { x[0], x[1] };
        x[0] = spots[q];
        x[1] = spots[q + 1];
        if (!positive())
        {
          x[0] = old[0];
          x[1] = old[1];
        }
        break;
      }
    }
  }
}
} // namespace

TEST(PairSearch, SnappedVerticesTranslatedAndScaled)
{
  std::mt19937 rng(99);
  int snapped = 0;
  for (int n = 0; n < 120; ++n)
  {
    const TestMesh target = mptest::GridMesh(4 + n % 5, 4 + n % 4, 0.25, rng());
    TestMesh source = mptest::GridMesh(5 + n % 6, 3 + n % 5, 0.25, rng());
    const std::vector<double> before = source.Points;
    Snap(source, target, 0.3 / (5 + n % 6));
    snapped += before != source.Points;
    const std::string what = "case " + std::to_string(n);
    Searches plain(target, source);
    plain.ExpectSamePairs(what);
    plain.ExpectCompleteCover(target, what);
    // The same pair far from the origin and at other scales.
    for (const auto& motion : { std::make_tuple(1.0, 1e6, -1e6), std::make_tuple(1e-6, 0.0, 0.0),
           std::make_tuple(1e6, 0.0, 0.0) })
    {
      TestMesh t = target;
      TestMesh s = source;
      mptest::Move(t, 0.0, std::get<0>(motion), std::get<1>(motion), std::get<2>(motion));
      mptest::Move(s, 0.0, std::get<0>(motion), std::get<1>(motion), std::get<2>(motion));
      Searches moved(t, s);
      moved.ExpectSamePairs(what + " moved");
      // Rounding of the moved coordinates themselves (~1e-10 at 1e6).
      moved.ExpectCompleteCover(t, what + " moved", std::get<1>(motion) != 0.0 ? 1e-7 : 1e-12);
    }
    if (HasFatalFailure())
      return;
  }
  EXPECT_GT(snapped, 60);
}
