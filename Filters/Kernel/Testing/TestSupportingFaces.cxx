// SPDX-License-Identifier: BSD-3-Clause
// Supporting boundary faces (Search/SupportingFaces.h): the fast test
// against an exact brute-force oracle, and the front that trusts them
// against the brute-force search where a target cell's cover is cut apart.
#include "Geometry/Predicates.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Search/SupportingFaces.h"
#include "SearchComparison.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <vector>

using mp::Index;
using mp::TetrahedronIntersector;
using mptest::TestMesh;

namespace
{
/// `m` without the cells whose centre `drop` says, then its neighbours.
TestMesh WithoutCells(const TestMesh& m, const std::function<bool(const double*)>& drop)
{
  TestMesh out = m;
  out.Cells.clear();
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    double centre[3] = { 0, 0, 0 };
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d)
        centre[d] += m.Points[3 * m.Cells[4 * c + k] + d] / 4;
    if (!drop(centre))
      out.Cells.insert(out.Cells.end(), m.Cells.begin() + 4 * c, m.Cells.begin() + 4 * c + 4);
  }
  out.Finish();
  return out;
}

/// Every used point against every boundary face's plane, exactly.
std::vector<unsigned char> Oracle(const TestMesh& m)
{
  const mp::MeshView v = m.View();
  std::vector<char> used(static_cast<size_t>(m.NumberOfPoints()), 0);
  for (Index p : m.Cells)
    used[p] = 1;
  std::vector<unsigned char> flags(static_cast<size_t>(m.NumberOfCells()), 0);
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    const mp::CellCorners ids = v.Cell(c);
    for (int k = 0; k < 4; ++k)
    {
      if (v.Neighbor(c, k) >= 0)
        continue;
      const double* a = v.Point(ids[(k + 1) % 4]);
      const double* b = v.Point(ids[(k + 2) % 4]);
      const double* d = v.Point(ids[(k + 3) % 4]);
      const double inner = mp::Orient3D(a, b, d, v.Point(ids[k]));
      bool supports = inner != 0.0;
      for (Index p = 0; p < m.NumberOfPoints() && supports; ++p)
        supports = !used[p] || mp::Orient3D(a, b, d, v.Point(p)) * inner >= 0.0;
      if (supports)
        flags[c] |= static_cast<unsigned char>(1u << k);
    }
  }
  return flags;
}

std::vector<unsigned char> Fast(const TestMesh& m)
{
  std::vector<Index> boundary;
  mp::BoundaryCells(m.View(), boundary);
  return mp::SupportingFaces(m.View(), boundary);
}

/// How many boundary faces the flags name.
Index Count(const std::vector<unsigned char>& flags)
{
  Index n = 0;
  for (unsigned char f : flags)
    for (int k = 0; k < 4; ++k)
      n += (f >> k) & 1u;
  return n;
}

Index BoundaryFaces(const TestMesh& m)
{
  Index n = 0;
  for (mp::NeighborId id : m.Neighbors)
    n += id < 0;
  return n;
}

/// Boundary points moved by up to `amount` along random directions: a
/// boundary with small folds both ways, faces nearly in one plane.
void Roughen(TestMesh& m, double amount, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  std::vector<char> onBoundary(static_cast<size_t>(m.NumberOfPoints()), 0);
  for (Index c = 0; c < m.NumberOfCells(); ++c)
    for (int k = 0; k < 4; ++k)
      if (m.Neighbors[4 * c + k] < 0)
        for (int j = 1; j < 4; ++j)
          onBoundary[m.Cells[4 * c + (k + j) % 4]] = 1;
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
    if (onBoundary[p])
      for (int d = 0; d < 3; ++d)
        m.Points[3 * p + d] += u(rng);
}

/// Locators that trust every boundary face, or none.
struct TrustingLocator : mp::BoxGridLocator
{
  TrustingLocator(const mp::MeshView& mesh, bool trust)
    : mp::BoxGridLocator(mesh)
    , Trust(trust)
  {}
  bool Supports(Index, int) const override { return this->Trust; }
  bool Trust;
};

struct FrontRun
{
  mptest::PairRecorder<TetrahedronIntersector> Pairs;
  mp::SearchStatistics Stats;
  FrontRun(const TestMesh& target, const TestMesh& source, mp::CandidateLocator& locator)
  {
    mp::AdvancingFrontSearch<TetrahedronIntersector>(
      target.View(), source.View(), locator, this->Pairs, this->Stats);
    std::sort(this->Pairs.Pairs.begin(), this->Pairs.Pairs.end());
  }
};
} // namespace

TEST(SupportingFaces, MatchTheExactOracle)
{
  struct Case
  {
    std::string Name;
    TestMesh Mesh;
    bool Convex;
  };
  std::vector<Case> cases;
  cases.push_back({ "small cube", mptest::CubeMesh(3, 4, 5, 0.15, 1), true });
  // 25 x 25 points on the two large sides: more than a face's own budget,
  // so the faces of each side are tested together; with one of those
  // points raised by 1e-9, none of that side's faces supports the box.
  const TestMesh slab = mptest::CubeMesh(24, 24, 2, 0.15, 2);
  cases.push_back({ "flat box", slab, true });
  TestMesh raised = slab;
  raised.Points[3 * ((2 * 25 + 20) * 25 + 7) + 2] += 1e-9; // a point of the top side
  cases.push_back({ "flat box, one point raised", raised, false });
  cases.push_back({ "notched",
    WithoutCells(
      mptest::CubeMesh(8, 8, 8, 0.15, 3), [](const double* x) { return x[0] > 0.5 && x[1] > 0.5; }),
    false });
  TestMesh rough = mptest::CubeMesh(6, 7, 8, 0.15, 4);
  Roughen(rough, 1e-3 / 8, 5);
  cases.push_back({ "rough", rough, false });
  // Far from the origin and small: the bounds' rounding matters.
  TestMesh far = rough;
  mptest::Move3D(far, 0.4, 0.7, 1e-6, 1e3, -2e3, 5e2);
  cases.push_back({ "rough, small and far", far, false });
  TestMesh coarse = mptest::CubeMesh(1, 1, 1, 0.0, 6);
  mptest::Move3D(coarse, 0, 0, 1e5, 3, -7, 11); // exact: the sides stay flat
  cases.push_back({ "one cube of six tetrahedra", coarse, true });
  // Points beyond a face's plane by rounding size only: a tilted face far
  // from the origin, and a small cell with a corner where the rounded
  // value of the plane's equation says "inside" but the exact sign says
  // "beyond" (the bounds' slack must keep such points).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0, found = 0; trial < 200000 && found < 3; ++trial)
  {
    double a[3], b[3], c[3], x[3], e1[3], e2[3];
    for (int d = 0; d < 3; ++d)
    {
      a[d] = 1000.0 + u(rng);
      b[d] = 1000.0 + u(rng);
      c[d] = 1000.0 + u(rng);
    }
    const double sb = 3.0 + u(rng), sc = -2.5 + u(rng); // far outside the triangle
    for (int d = 0; d < 3; ++d)
    {
      e1[d] = b[d] - a[d];
      e2[d] = c[d] - a[d];
      x[d] = a[d] + sb * e1[d] + sc * e2[d];
    }
    const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    double value = 0.0; // the rounded equation, positive beyond
    for (int d = 0; d < 3; ++d)
      value += n[d] * (x[d] - a[d]);
    if (!(mp::Orient3D(a, b, c, x) > 0.0) || !(value < 0.0))
      continue;
    ++found;
    TestMesh m;
    m.Dimension = 3;
    const double inner[3] = { a[0] - n[0], a[1] - n[1], a[2] - n[2] };
    for (const double* q : std::initializer_list<const double*>{ inner, a, b, c })
      m.Points.insert(m.Points.end(), { q[0], q[1], q[2] });
    const double h = 1e-3;
    m.Points.insert(m.Points.end(), { x[0], x[1], x[2] });
    m.Points.insert(m.Points.end(), { x[0] - h * n[0], x[1] - h * n[1] + h, x[2] - h * n[2] });
    m.Points.insert(m.Points.end(), { x[0] - h * n[0] + h, x[1] - h * n[1], x[2] - h * n[2] });
    m.Points.insert(m.Points.end(), { x[0] - h * n[0], x[1] - h * n[1], x[2] - h * n[2] + h });
    m.Cells = { 0, 1, 2, 3, 4, 5, 6, 7 };
    m.Finish();
    cases.push_back({ "rounding-size overhang " + std::to_string(found), m, false });
  }
  ASSERT_EQ(cases.size(), size_t(10));
  for (const Case& c : cases)
  {
    const std::vector<unsigned char> fast = Fast(c.Mesh);
    const std::vector<unsigned char> exact = Oracle(c.Mesh);
    ASSERT_EQ(fast.size(), exact.size()) << c.Name;
    for (size_t i = 0; i < fast.size(); ++i)
    {
      ASSERT_EQ(int(fast[i]), int(exact[i])) << c.Name << ", cell " << i;
    }
    if (c.Convex)
    {
      EXPECT_EQ(Count(fast), BoundaryFaces(c.Mesh)) << c.Name;
    }
    else
    {
      EXPECT_GT(Count(fast), 0) << c.Name;
      EXPECT_LT(Count(fast), BoundaryFaces(c.Mesh)) << c.Name;
    }
  }
}

TEST(SupportingFaces, NoneWithoutFiniteBoundaryOrForOtherMeshes)
{
  TestMesh m = mptest::CubeMesh(3, 3, 3, 0.15, 7);
  m.Points[0] = std::numeric_limits<double>::quiet_NaN(); // a corner of the box
  EXPECT_EQ(Count(Fast(m)), 0);
  const TestMesh flat = mptest::GridMesh(4, 4, 0.2, 8);
  std::vector<Index> boundary;
  mp::BoundaryCells(flat.View(), boundary);
  EXPECT_TRUE(mp::SupportingFaces(flat.View(), boundary).empty());
}

TEST(SupportingFaces, FrontFindsCoversCutApartByTheSource)
{
  // Two slabs with a gap: coarse target cells across the gap meet both,
  // and the slabs' faces along the gap support neither: the front must
  // ask the locator there. Trusting every face misses pairs, which shows
  // that this case needs the query.
  const TestMesh slabs = WithoutCells(mptest::CubeMesh(8, 8, 8, 0.15, 9),
    [](const double* x) { return x[0] > 0.375 && x[0] < 0.625; });
  // A slot from the top: one connected source, concave along the slot.
  const TestMesh slotted = WithoutCells(mptest::CubeMesh(8, 8, 8, 0.15, 10),
    [](const double* x) { return x[0] > 0.375 && x[0] < 0.625 && x[2] > 0.25; });
  // The middle column of cubes (x from 1/3 to 2/3) spans the gap.
  const TestMesh target = mptest::CubeMesh(3, 2, 2, 0.15, 11);
  for (const TestMesh* source : { &slabs, &slotted })
  {
    const std::string what = source == &slabs ? "slabs" : "slotted";
    mptest::SearchComparison<TetrahedronIntersector> s(target, *source);
    s.ExpectSamePairs(what);
    if (source == &slabs)
    {
      TrustingLocator careless(source->View(), true);
      const FrontRun missing(target, *source, careless);
      EXPECT_LT(missing.Pairs.Pairs.size(), s.Brute.Pairs.size()) << what;
    }
  }
}

TEST(SupportingFaces, SpareTheQueriesOnConvexSources)
{
  // A smaller box in the target's domain (its sides exactly flat: scaled
  // and moved along the axes): the target's cells reach beyond its
  // boundary all around. Trusting the supporting faces finds the same
  // pairs with far fewer queries among the boundary cells than trusting
  // none (both ask among all cells for the target cells it misses).
  std::mt19937 rng(12);
  for (int n = 0; n < 6; ++n)
  {
    TestMesh source = mptest::CubeMesh(5 + n % 2, 6, 5, 0.15, rng());
    mptest::Move3D(source, 0, 0, 0.75 - 0.125 * (n % 3), 0.125, 0.0625 * (n % 2), 0.25);
    const TestMesh target = mptest::CubeMesh(6, 5 + n % 3, 6, 0.15, rng());
    const std::string what = "case " + std::to_string(n);
    mptest::SearchComparison<TetrahedronIntersector> s(target, source);
    s.ExpectSamePairs(what);
    TrustingLocator none(source.View(), false);
    const FrontRun asking(target, source, none);
    EXPECT_EQ(asking.Pairs.Pairs, s.Front.Pairs) << what;
    const Index trusting = s.FrontStats.LocatorQueries - s.FrontStats.FullLocatorQueries;
    const Index all = asking.Stats.LocatorQueries - asking.Stats.FullLocatorQueries;
    EXPECT_LT(4 * trusting, all) << what;
  }
}

TEST(SupportingFaces, OnlySubstantialPiecesAreTrusted)
{
  // From a projection of image data onto a Gmsh box (renumbered): the front
  // met the target cell first in source cell A, whose piece is a rounding
  // sliver at Intersect's floor; A's neighbour across the face the sliver
  // lies on does not meet the cell, and the cell's real cover (B's piece,
  // among others) was reached only by the boundary query. Such a piece
  // must not spare that query.
  const double t[4][3] = { { 0, 0.80000000000000004, 0.5 }, { 0, 0.80000000000000004, 0.75 },
    { 0.16666666666666666, 1, 0.75 }, { 0, 1, 0.75 } };
  const double a[4][3] = { { 0, 0.90519492276591973, 0.50009609567510971 },
    { 0, 0.78902439024390203, 0.49999999999999989 }, { 0, 0.85522054191364383, 0.3679200936970265 },
    { 0.16396897933529997, 0.82604532665850006, 0.36746206371251156 } };
  const double b[4][3] = { { 0, 0.78902439024390203, 0.49999999999999989 },
    { 0, 0.90519492276591973, 0.50009609567510971 }, { 0, 0.86171324987264719, 0.6339257120304993 },
    { 0.17627975138032753, 0.83778337479834919, 0.56785762652698857 } };
  TestMesh m;
  m.Dimension = 3;
  for (const auto* cell : { t, a, b })
    for (int k = 0; k < 4; ++k)
      m.Points.insert(m.Points.end(), { cell[k][0], cell[k][1], cell[k][2] });
  m.Cells = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11 };
  TetrahedronIntersector::Cell ct, ca, cb;
  ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 0, ct));
  ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 1, ca));
  ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 2, cb));
  TetrahedronIntersector::Piece piece;
  ASSERT_TRUE(TetrahedronIntersector::Intersect(ct, ca, piece)); // at the floor
  EXPECT_LT(TetrahedronIntersector::Measure(piece), 1e-15);
  EXPECT_FALSE(TetrahedronIntersector::Substantial(ct, ca, piece));
  ASSERT_TRUE(TetrahedronIntersector::Intersect(ct, cb, piece));
  EXPECT_GT(TetrahedronIntersector::Measure(piece), 1e-5);
  EXPECT_TRUE(TetrahedronIntersector::Substantial(ct, cb, piece));
}

TEST(SupportingFaces, FrontEqualsBruteForceOnShuffledBoxes)
{
  // Boxes whose sides are exactly flat against boxes that reach beyond
  // them or share their sides, on lattices that align (faces and corners
  // in common: pieces at Intersect's floor) or not, the cells of both in
  // random order so that the front meets the boundary from every side.
  std::mt19937 rng(13);
  auto shuffled = [&rng](TestMesh m) {
    const Index n = m.NumberOfCells();
    std::vector<Index> order(static_cast<size_t>(n));
    for (Index c = 0; c < n; ++c)
      order[c] = c;
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<Index> cells;
    for (Index c : order)
      cells.insert(cells.end(), m.Cells.begin() + 4 * c, m.Cells.begin() + 4 * c + 4);
    m.Cells = cells;
    m.Finish();
    return m;
  };
  for (int n = 0; n < 60; ++n)
  {
    const double jitter = n % 3 == 0 ? 0.0 : 0.15;
    TestMesh source = shuffled(mptest::CubeMesh(2 + n % 4, 3 + n % 3, 2 + n % 5, jitter, rng()));
    TestMesh target =
      shuffled(mptest::CubeMesh(3 + n % 5, 2 + n % 4, 3 + n % 3, n % 2 ? jitter : 0.0, rng()));
    // Shifts and scales by powers of two keep the sides exactly flat.
    if (n % 4 == 1)
      mptest::Move3D(source, 0, 0, 0.75, 0.125, 0.125, 0.0);
    if (n % 4 == 2)
      mptest::Move3D(target, 0, 0, 1.0, 0.5, 0.25, -0.25);
    mptest::SearchComparison<TetrahedronIntersector> s(target, source);
    s.ExpectSamePairs("case " + std::to_string(n));
    if (HasFatalFailure())
      return;
  }
}
