// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/TetrahedronIntersector.h"
#include "Search/PairSearch.h"
#include "GeneratedMeshes.h"
#include "Mesh/WorkerPool.h"
#include "Threads.h"
#include "Transfer/MortarAssembler.h"
#include "Transfer/MortarOperator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <limits>
#include <map>

using mp::Index;
using mptest::TestMesh;

#include "MortarTestSupport.h"

using mortartest::Linear;
using mortartest::LShapeWithHole;
using mortartest::MeshPair;
using mortartest::MixedMassEntry;
using mortartest::Projection;
using mortartest::Smooth;
using mortartest::TargetMassEntry;

// Target: the triangle (0,0),(1,0),(0,1). Source: the same triangle split at
// the midpoint m of its hypotenuse into S1 = (0, (1,0), m), S2 = (0, m, (0,1)),
// both of area 1/4. By hand, with the integral of two linear functions over a
// triangle, A/12 (sum f_a g_a + sum f_a sum g_a), summed over S1 and S2:
// M_ts(origin, origin) = 1/12, M_ts(origin, m) = 1/24, M_ts((1,0), m) = 1/16.
TEST(MortarProjector, HandComputedEntries)
{
  const auto split = mptest::SplitTriangle();
  const TestMesh& target = split.first;
  const TestMesh& source = split.second;
  Projection p(target, source);
  ASSERT_TRUE(p.Ok) << p.Projector.GetError();
  const auto& m = p.Projector;
  EXPECT_NEAR(MixedMassEntry(m, 0, 0), 1.0 / 12.0, 1e-16);
  EXPECT_NEAR(MixedMassEntry(m, 0, 3), 1.0 / 24.0, 1e-16);
  EXPECT_NEAR(MixedMassEntry(m, 1, 3), 1.0 / 16.0, 1e-16);
  // phi_(1,0) = x is zero at the origin and at (0,1): on S1 = (0,(1,0),m),
  // values (0,1,1/2) against psi_(1,0) = (0,1,0): 1/48 (1 + 3/2) = 5/96.
  EXPECT_NEAR(MixedMassEntry(m, 1, 1), 5.0 / 96.0, 1e-16);
  EXPECT_NEAR(MixedMassEntry(m, 1, 2), 0.0 + 1.0 / 48.0 * 0.5, 1e-16);
  // M_tt is the element mass matrix A/12 (1 + delta).
  EXPECT_NEAR(TargetMassEntry(m, 0, 0), 1.0 / 12.0, 1e-16);
  EXPECT_NEAR(TargetMassEntry(m, 0, 1), 1.0 / 24.0, 1e-16);
  // Rows of M_ts and M_tt both sum to the integral of phi_i: A/3 = 1/6.
  for (Index i = 0; i < 3; ++i)
  {
    double rts = 0;
    double rtt = 0;
    for (Index j = 0; j < 4; ++j)
      rts += MixedMassEntry(m, i, j);
    for (Index k = 0; k < 3; ++k)
      rtt += TargetMassEntry(m, i, k);
    EXPECT_NEAR(rts, 1.0 / 6.0, 1e-16);
    EXPECT_NEAR(rtt, 1.0 / 6.0, 1e-16);
  }
}

TEST(MortarProjector, LinearFieldsAreReproduced)
{
  std::mt19937 rng(11);
  for (int n = 0; n < 40; ++n)
  {
    const auto keep = n % 2 ? std::function<bool(double, double)>(LShapeWithHole) : nullptr;
    const TestMesh target =
      mptest::GridMesh(4 * (1 + n % 5), 4 * (2 + n % 3), 0.25, rng(), 0, 0, 1, 1, keep);
    const TestMesh source =
      mptest::GridMesh(4 * (1 + n % 7), 4 * (1 + n % 4), 0.25, rng(), 0, 0, 1, 1, keep);
    Projection p(target, source);
    ASSERT_TRUE(p.Ok);
    EXPECT_EQ(p.Projector.GetNumberOfValid(), target.NumberOfPoints());
    const auto ut = p.Apply(mptest::Sample(source, Linear));
    const auto exact = mptest::Sample(target, Linear);
    for (Index i = 0; i < target.NumberOfPoints(); ++i)
      ASSERT_NEAR(ut[i], exact[i], 1e-12) << "case " << n << " point " << i;
  }
}

TEST(MortarProjector, MultiComponentFieldsAndConstants)
{
  const TestMesh target = mptest::GridMesh(9, 7, 0.25, 21);
  const TestMesh source = mptest::GridMesh(13, 11, 0.25, 22);
  Projection p(target, source);
  ASSERT_TRUE(p.Ok);
  std::vector<double> us;
  for (Index i = 0; i < source.NumberOfPoints(); ++i)
  {
    const double x = source.Points[3 * i];
    const double y = source.Points[3 * i + 1];
    us.insert(us.end(), { 4.25, Linear(x, y), Smooth(x, y) });
  }
  const auto ut = p.Apply(us, 3);
  const auto smooth = p.Apply(mptest::Sample(source, Smooth));
  for (Index i = 0; i < target.NumberOfPoints(); ++i)
  {
    EXPECT_NEAR(ut[3 * i], 4.25, 1e-13);
    EXPECT_NEAR(ut[3 * i + 1], Linear(target.Points[3 * i], target.Points[3 * i + 1]), 1e-12);
    EXPECT_EQ(ut[3 * i + 2], smooth[i]); // components are independent
  }
}

TEST(MortarProjector, IntegralsAreConserved)
{
  std::mt19937 rng(12);
  for (int n = 0; n < 20; ++n)
  {
    const auto keep = n % 2 ? std::function<bool(double, double)>(LShapeWithHole) : nullptr;
    const TestMesh target =
      mptest::GridMesh(4 * (1 + n % 3), 4 * (1 + n % 5), 0.25, rng(), 0, 0, 1, 1, keep);
    const TestMesh source =
      mptest::GridMesh(4 * (2 + n % 4), 4 * (1 + n % 6), 0.25, rng(), 0, 0, 1, 1, keep);
    Projection p(target, source);
    ASSERT_TRUE(p.Ok);
    const auto us = mptest::Sample(source, Smooth);
    const auto ut = p.Apply(us);
    const double is = source.Integral(us);
    EXPECT_NEAR(target.Integral(ut), is, 1e-13 * std::fabs(is)) << "case " << n;
    EXPECT_NEAR(p.Projector.GetCoveredMeasure(), target.Area(), 1e-13);
  }
}

TEST(MortarProjector, BruteForceGivesTheSameProjection)
{
  const TestMesh target = mptest::GridMesh(12, 12, 0.25, 31, 0, 0, 1, 1, LShapeWithHole);
  const TestMesh source = mptest::GridMesh(16, 20, 0.25, 32, 0, 0, 1, 1, LShapeWithHole);
  Projection front(target, source, mp::SearchMethod::AdvancingFront, true);
  Projection brute(target, source, mp::SearchMethod::BruteForce, true);
  ASSERT_TRUE(front.Ok && brute.Ok);
  EXPECT_EQ(front.Projector.GetPieces().Size(), brute.Projector.GetPieces().Size());
  EXPECT_EQ(
    front.Projector.GetStatistics().TouchingPairs, brute.Projector.GetStatistics().TouchingPairs);
  const auto us = mptest::Sample(source, Smooth);
  const auto a = front.Apply(us);
  const auto b = brute.Apply(us);
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_NEAR(a[i], b[i], 1e-13);
}

TEST(MortarProjector, ProjectionConvergesUnderRefinement)
{
  // The L2 projection of a smooth field is second-order accurate at the points.
  double previous = 0;
  for (int level = 0; level < 3; ++level)
  {
    const int n = 8 << level;
    const TestMesh target = mptest::GridMesh(n, n, 0.25, 40 + level);
    const TestMesh source = mptest::GridMesh(2 * n + 3, 2 * n + 1, 0.25, 50 + level);
    Projection p(target, source);
    ASSERT_TRUE(p.Ok);
    const auto ut = p.Apply(mptest::Sample(source, Smooth));
    const auto exact = mptest::Sample(target, Smooth);
    double error = 0;
    for (size_t i = 0; i < ut.size(); ++i)
      error = std::max(error, std::fabs(ut[i] - exact[i]));
    if (level > 0)
    {
      EXPECT_LT(error, previous / 3.0) << "level " << level;
    }
    previous = error;
  }
}

TEST(MortarProjector, PartialOverlapMarksUncoveredPoints)
{
  // Source covers x < 0.5 of the target only (aligned with target lines).
  const TestMesh target = mptest::GridMesh(8, 8, 0.0, 61);
  const TestMesh source = mptest::GridMesh(5, 7, 0.2, 62, -0.25, -0.25, 0.5, 1.25);
  Projection p(target, source, mp::SearchMethod::AdvancingFront, true);
  ASSERT_TRUE(p.Ok);
  const auto ut = p.Apply(mptest::Sample(source, Linear));
  Index valid = 0;
  for (Index i = 0; i < target.NumberOfPoints(); ++i)
  {
    const double x = target.Points[3 * i];
    const double y = target.Points[3 * i + 1];
    // Points with x <= 0.5 touch covered cells; points beyond do not.
    const bool expected = x < 0.5 + 1e-12;
    EXPECT_EQ(bool(p.Projector.GetValid()[i]), expected) << x << " " << y;
    if (expected)
    {
      ++valid;
      EXPECT_NEAR(ut[i], Linear(x, y), 1e-12);
    }
    else
    {
      EXPECT_TRUE(std::isnan(ut[i]));
    }
  }
  EXPECT_EQ(valid, p.Projector.GetNumberOfValid());
  EXPECT_NEAR(p.Projector.GetCoveredMeasure(), 0.5, 1e-14);
  for (Index c = 0; c < target.NumberOfCells(); ++c)
  {
    const Index* ids = &target.Cells[3 * c];
    const double cx =
      (target.Points[3 * ids[0]] + target.Points[3 * ids[1]] + target.Points[3 * ids[2]]) / 3;
    EXPECT_NEAR(p.Projector.GetCoveredFraction()[c], cx < 0.5 ? 1.0 : 0.0, 1e-12);
  }
}

TEST(MortarProjector, EmptyAndInvalidMeshes)
{
  const TestMesh m = mptest::GridMesh(3, 3, 0.1, 71);
  TestMesh empty;
  Projection a(m, empty);
  ASSERT_TRUE(a.Ok);
  EXPECT_EQ(a.Projector.GetNumberOfValid(), 0);
  Projection b(empty, m);
  ASSERT_TRUE(b.Ok);

  TestMesh broken = m;
  broken.Cells[4] = 1000; // a point that does not exist
  mp::MortarOperator projector;
  mp::BoxGridLocator locator(m.View());
  EXPECT_FALSE(projector.Build(broken.View(), m.View(), &locator));
  EXPECT_NE(projector.GetError().find("point that does not exist"), std::string::npos);

  mp::MeshView threeD = m.View();
  threeD.CellDimension = 3;
  threeD.SpaceDimension = 3;
  threeD.NumberOfCells = m.NumberOfCells() * 3 / 4;
  EXPECT_FALSE(projector.Build(threeD, m.View(), &locator));
  EXPECT_NE(projector.GetError().find("different dimensions"), std::string::npos);
}

TEST(MortarProjector, TouchingMeshesCoverNothing)
{
  // Side by side, sharing the edge x = 1: no point has covered support.
  const TestMesh target = mptest::GridMesh(4, 4, 0.2, 81);
  const TestMesh source = mptest::GridMesh(3, 5, 0.2, 82, 1, 0, 2, 1);
  Projection p(target, source);
  ASSERT_TRUE(p.Ok);
  EXPECT_EQ(p.Projector.GetNumberOfValid(), 0);
  EXPECT_EQ(p.Projector.GetCoveredMeasure(), 0.0);
  for (double f : p.Projector.GetCoveredFraction())
    EXPECT_EQ(f, 0.0);
  // The front still visits the touching pairs (zero area): no pieces.
  EXPECT_GT(p.Projector.GetStatistics().TouchingPairs, 0);
  EXPECT_EQ(p.Projector.GetStatistics().Pieces, 0);
  const auto ut = p.Apply(mptest::Sample(source, Linear));
  for (double v : ut)
    EXPECT_TRUE(std::isnan(v));
}

TEST(MortarProjector, MultiComponentSourceExactCoverage)
{
  // Two source islands over a target grid with aligned lines: the covered
  // fractions are exactly 1 under the islands and 0 elsewhere, and exactly
  // the points of the covered cells are valid.
  const TestMesh target = mptest::GridMesh(8, 8, 0.0, 83);
  const auto island = [](double x, double y) {
    return (x < 0.25 && y < 0.5) || (x > 0.5 && x < 0.875 && y > 0.625);
  };
  const TestMesh source = mptest::GridMesh(16, 16, 0.0, 84, 0, 0, 1, 1, island);
  Projection p(target, source);
  ASSERT_TRUE(p.Ok);
  std::vector<char> expectedValid(static_cast<size_t>(target.NumberOfPoints()), 0);
  for (Index c = 0; c < target.NumberOfCells(); ++c)
  {
    const Index* ids = &target.Cells[3 * c];
    double cx = 0;
    double cy = 0;
    for (int k = 0; k < 3; ++k)
    {
      cx += target.Points[3 * ids[k]] / 3;
      cy += target.Points[3 * ids[k] + 1] / 3;
    }
    const bool covered = island(cx, cy);
    EXPECT_EQ(p.Projector.GetCoveredFraction()[c], covered ? 1.0 : 0.0) << c;
    for (int k = 0; covered && k < 3; ++k)
      expectedValid[ids[k]] = 1;
  }
  EXPECT_EQ(p.Projector.GetValid(), expectedValid);
  const auto ut = p.Apply(mptest::Sample(source, Linear));
  for (Index i = 0; i < target.NumberOfPoints(); ++i)
    if (expectedValid[i])
      EXPECT_NEAR(ut[i], Linear(target.Points[3 * i], target.Points[3 * i + 1]), 1e-12);
}

TEST(MortarProjector, ConcurrentTasksGiveTheSerialResult)
{
  const TestMesh target = mptest::GridMesh(30, 30, 0.25, 91, 0, 0, 1, 1, LShapeWithHole);
  const TestMesh source = mptest::GridMesh(28, 36, 0.25, 92, 0, 0, 1, 1, LShapeWithHole);
  const auto us = mptest::Sample(source, Smooth);
  // The tasks one after the other, on threads of their own, or on a pool
  // of three threads (the filter's way: mp::WorkerPool).
  enum Mode
  {
    InTurn,
    OnThreads,
    OnPool
  };
  mp::WorkerPool pool(3);
  auto run = [&](int tasks, Mode mode, std::vector<double>& ut, mp::IntersectionPieces& pieces) {
    mp::BoxGridLocator locator(source.View());
    mp::OperatorOptions options;
    options.Runner.Tasks = tasks;
    options.KeepPieces = true;
    if (mode == OnThreads)
    {
      options.Runner.Run = mptest::RunInThreads;
    }
    else if (mode == OnPool)
    {
      options.Runner = pool.Runner(tasks);
    }
    else
    {
      // The ranges one after the other (a runner without Run is one task).
      options.Runner.Run = [](int count, const std::function<void(int)>& task) {
        for (int k = 0; k < count; ++k)
          task(k);
      };
    }
    mp::MortarOperator projector;
    EXPECT_TRUE(projector.Build(target.View(), source.View(), &locator, options));
    ut.resize(static_cast<size_t>(target.NumberOfPoints()));
    EXPECT_TRUE(projector.Apply(us.data(), 1, ut.data(), std::nan("")));
    pieces = projector.GetPieces();
    return projector.GetStatistics().Pieces;
  };
  std::vector<double> serial;
  mp::IntersectionPieces serialPieces;
  const Index pieces = run(1, InTurn, serial, serialPieces);
  for (int tasks : { 2, 3, 7 })
  {
    std::vector<double> inTurn;
    for (Mode mode : { InTurn, OnThreads, OnPool })
    {
      std::vector<double> ut;
      mp::IntersectionPieces p;
      EXPECT_EQ(run(tasks, mode, ut, p), pieces) << tasks;
      for (size_t i = 0; i < ut.size(); ++i)
        ASSERT_NEAR(ut[i], serial[i], 1e-13) << tasks << " tasks, point " << i;
      // A number of tasks gives one result, however they run.
      if (mode == InTurn)
        inTurn = ut;
      else
        EXPECT_EQ(ut, inTurn) << tasks << " tasks, mode " << mode;
      // The same pieces, in another order.
      std::vector<std::pair<Index, Index>> a;
      std::vector<std::pair<Index, Index>> b;
      for (Index k = 0; k < p.Size(); ++k)
        a.emplace_back(p.TargetCell[k], p.SourceCell[k]);
      for (Index k = 0; k < serialPieces.Size(); ++k)
        b.emplace_back(serialPieces.TargetCell[k], serialPieces.SourceCell[k]);
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      EXPECT_EQ(a, b);
      EXPECT_EQ(p.Offsets.back(), serialPieces.Offsets.back());
    }
  }
}

TEST(MortarProjector, DirectSolverForFieldsConjugateGradientsLeaveUnconverged)
{
  // Several fields at once; with no or one iteration allowed, the direct
  // solver takes over every field that has not converged (all but the zero
  // field): the answers agree with the iterations' to rounding.
  const TestMesh target = mptest::GridMesh(9, 11, 0.25, 61, 0, 0, 1, 1, LShapeWithHole);
  const TestMesh source = mptest::GridMesh(13, 8, 0.25, 62, 0, 0, 1, 1, LShapeWithHole);
  const std::vector<double> smooth = mptest::Sample(source, Smooth);
  const std::vector<double> linear = mptest::Sample(source, Linear);
  std::vector<double> fields;
  for (size_t p = 0; p < smooth.size(); ++p)
  {
    fields.insert(fields.end(), { smooth[p], linear[p], 0.0, -smooth[p] });
  }
  std::vector<std::vector<double>> results;
  for (int iterations : { 500, 0, 1 })
  {
    mp::BoxGridLocator locator(source.View());
    mp::MortarOperator projector;
    ASSERT_TRUE(projector.Build(target.View(), source.View(), &locator));
    mp::SolveOptions solve;
    solve.MaxIterations = iterations;
    std::vector<double> values(static_cast<size_t>(target.NumberOfPoints()) * 4);
    ASSERT_TRUE(projector.Apply(fields.data(), 4, values.data(), std::nan(""), solve));
    results.push_back(values);
  }
  const std::vector<double> exact = mptest::Sample(target, Linear);
  for (const auto& values : results)
  {
    for (Index p = 0; p < target.NumberOfPoints(); ++p)
    {
      EXPECT_NEAR(values[4 * p], results[0][4 * p], 1e-12);
      EXPECT_NEAR(values[4 * p + 1], exact[p], 1e-12); // linear fields stay exact
      EXPECT_EQ(values[4 * p + 2], 0.0);               // a zero field stays zero
      EXPECT_NEAR(values[4 * p + 3], -values[4 * p], 1e-12);
    }
  }
}

namespace
{
/**
 * M_tt as the projector assembles it (the moments of a target cell's pieces
 * summed about its corner, or the element mass matrix when it is covered
 * whole) against the sum of the per-piece reference blocks
 * (mp::AddPieceBlocks), entry by entry, relative to the largest entry; with
 * one task, and with up to three (where the target has 64 cells per task:
 * the M_tt entries of points on cells of several tasks are summed after the
 * tasks).
 */
template <class Intersector>
void ExpectTargetMassMatchesPieces(
  const TestMesh& target, const TestMesh& source, const std::string& what)
{
  constexpr int N = Intersector::Corners;
  std::map<std::pair<Index, Index>, double> reference;
  auto visit = [&](const typename Intersector::Cell& t, const typename Intersector::Cell& s,
                 const typename Intersector::Piece& piece) {
    double mts[N][N] = {};
    double mtt[N][N] = {};
    mp::AddPieceBlocks<Intersector, mp::P1Space<Intersector::Dimension>,
      mp::P1Space<Intersector::Dimension>>(piece, t, s, mts, mtt);
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < N; ++k)
        reference[{ t.Points[i], t.Points[k] }] += mtt[i][k];
  };
  mp::BoxGridLocator locator(source.View());
  mp::SearchStatistics stats;
  mp::AdvancingFrontSearch<Intersector>(target.View(), source.View(), locator, visit, stats);
  for (int tasks : { 1, 3 })
  {
    mp::BoxGridLocator seeds(source.View());
    mp::OperatorOptions options;
    options.Runner.Tasks = tasks;
    options.Runner.Run = [](int count, const std::function<void(int)>& task) {
      for (int k = 0; k < count; ++k)
        task(k);
    };
    mp::MortarOperator projector;
    ASSERT_TRUE(projector.Build(target.View(), source.View(), &seeds, options)) << what;
    double largest = 0.0;
    for (const auto& entry : reference)
      largest = std::max(largest, std::fabs(entry.second));
    ASSERT_GT(largest, 0.0) << what;
    for (const auto& entry : reference)
    {
      const Index i = entry.first.first;
      const Index k = entry.first.second;
      if (projector.GetValid()[i])
      {
        ASSERT_NEAR(TargetMassEntry(projector, i, k), entry.second, 1e-12 * largest)
          << what << " entry " << i << ", " << k << " (" << tasks << " tasks)";
      }
    }
  }
}
} // namespace

TEST(MortarProjector, TargetMassFromMomentsMatchesThePieces)
{
  // Covered whole, covered in part (source boundaries, holes, a shifted and
  // rotated source), in 2D and 3D; in odd cases every other target cell is
  // reversed (its corners 1 and 2 swapped: the intersectors take its
  // corners in another order than the mesh's, which the blocks kept for
  // M_tt must undo).
  auto flip = [](TestMesh& m) {
    const int corners = m.Dimension + 1;
    for (Index c = 0; c < m.NumberOfCells(); c += 2)
    {
      std::swap(m.Cells[c * corners + 1], m.Cells[c * corners + 2]);
    }
    m.Finish();
  };
  for (int n = 0; n < 6; ++n)
  {
    TestMesh target = mptest::GridMesh(8 + n, 7, 0.25, 70 + n, 0, 0, 1, 1, LShapeWithHole);
    if (n % 2 == 1)
    {
      flip(target);
    }
    TestMesh source = mptest::GridMesh(6, 9 + n, 0.25, 80 + n);
    mptest::Move(source, 0.3 * n, 0.9, 0.05 * n, -0.03 * n);
    ExpectTargetMassMatchesPieces<mp::TriangleIntersector>(
      target, source, "2D case " + std::to_string(n));
  }
  for (int n = 0; n < 4; ++n)
  {
    TestMesh target = mptest::CubeMesh(3, 2 + n, 3, 0.15, 90 + n);
    if (n % 2 == 1)
    {
      flip(target);
    }
    TestMesh source = mptest::CubeMesh(2 + n, 3, 2, 0.15, 95 + n);
    mptest::Move3D(source, 0.2 * n, 0.1 * n, 0.9, 0.1 * n, 0.05, -0.05 * n);
    ExpectTargetMassMatchesPieces<mp::TetrahedronIntersector>(
      target, source, "3D case " + std::to_string(n));
  }
}

// Excluded source cells (no data there) act as a hole in the source: the
// operator equals the one built on the source without those cells, for
// every pair of spaces, in 2D and 3D, with the advancing front walking
// through the excluded cells.
TEST(MortarProjector, ExcludedSourceCellsAreAHole)
{
  for (int dimension : { 2, 3 })
  {
    const TestMesh target =
      dimension == 2 ? mptest::GridMesh(9, 8, 0.2, 91) : mptest::CubeMesh(6, 6, 3, 0.2, 92);
    const TestMesh source =
      dimension == 2 ? mptest::GridMesh(11, 10, 0.25, 93) : mptest::CubeMesh(8, 7, 3, 0.2, 94);
    const int corners = dimension + 1;
    // Excluded: a disc of cells in the middle, and a band along x = 0.
    std::vector<char> excluded(static_cast<size_t>(source.NumberOfCells()), 0);
    TestMesh holed = source;
    holed.Cells.clear();
    std::vector<Index> kept; // holed cell -> source cell
    for (Index c = 0; c < source.NumberOfCells(); ++c)
    {
      double center[3] = { 0, 0, 0 };
      for (int k = 0; k < corners; ++k)
      {
        for (int d = 0; d < 3; ++d)
        {
          center[d] += source.Points[3 * source.Cells[corners * c + k] + d] / corners;
        }
      }
      const double r = std::hypot(center[0] - 0.5, center[1] - 0.5);
      excluded[c] = r < 0.35 || center[0] < 0.15;
      if (!excluded[c])
      {
        holed.Cells.insert(
          holed.Cells.end(), &source.Cells[corners * c], &source.Cells[corners * (c + 1)]);
        kept.push_back(c);
      }
    }
    holed.Finish();
    ASSERT_GT(std::count(excluded.begin(), excluded.end(), 1), 5);
    for (auto spaces : { std::make_pair(mp::SpaceType::P1, mp::SpaceType::P1),
           std::make_pair(mp::SpaceType::P0, mp::SpaceType::P1),
           std::make_pair(mp::SpaceType::P1, mp::SpaceType::P0),
           std::make_pair(mp::SpaceType::P0, mp::SpaceType::P0) })
    {
      mp::OperatorOptions options;
      options.TargetSpace = spaces.first;
      options.SourceSpace = spaces.second;
      mp::BoxGridLocator locator(source.View());
      mp::MortarOperator withHole;
      options.ExcludedSourceCells = excluded.data();
      ASSERT_TRUE(withHole.Build(target.View(), source.View(), &locator, options));
      mp::MortarOperator reference;
      options.ExcludedSourceCells = nullptr;
      options.Method = mp::SearchMethod::BruteForce;
      ASSERT_TRUE(reference.Build(target.View(), holed.View(), nullptr, options));
      EXPECT_NEAR(withHole.GetCoveredMeasure(), reference.GetCoveredMeasure(), 1e-14);
      ASSERT_EQ(withHole.GetValid(), reference.GetValid());
      EXPECT_LT(withHole.GetNumberOfValid(), withHole.GetNumberOfTargetFunctions())
        << dimension << "D";
      EXPECT_GT(withHole.GetNumberOfValid(), 0);
      for (size_t c = 0; c < withHole.GetCoveredFraction().size(); ++c)
      {
        EXPECT_NEAR(withHole.GetCoveredFraction()[c], reference.GetCoveredFraction()[c], 1e-13);
      }
      const Index rows = withHole.GetNumberOfTargetFunctions();
      for (Index i = 0; i < rows; ++i)
      {
        for (Index k = 0; k < rows; ++k)
        {
          ASSERT_NEAR(TargetMassEntry(withHole, i, k), TargetMassEntry(reference, i, k), 1e-15);
        }
      }
      // M_ts: P1 columns are the same points; P0 columns of the holed mesh
      // are its kept cells.
      const bool p0 = spaces.second == mp::SpaceType::P0;
      const Index columns = p0 ? holed.NumberOfCells() : source.NumberOfPoints();
      for (Index i = 0; i < rows; ++i)
      {
        for (Index j = 0; j < columns; ++j)
        {
          ASSERT_NEAR(
            MixedMassEntry(withHole, i, p0 ? kept[j] : j), MixedMassEntry(reference, i, j), 1e-15);
        }
        if (p0)
        {
          for (Index c = 0; c < source.NumberOfCells(); ++c)
          {
            if (excluded[c])
            {
              ASSERT_EQ(MixedMassEntry(withHole, i, c), 0.0);
            }
          }
        }
      }
    }
  }
}

// Several operators from one search (the filter's point and cell data):
// each is the operator its own Build gives, bit for bit, with fields given
// or M_ts assembled, on one task or several, in 2D, 3D and on surfaces.
TEST(MortarProjector, BuildTogetherGivesEachOperatorItsOwnBuild)
{
  TestMesh shiftedCube = mptest::CubeMesh(6, 5, 7, 0.2, 122);
  for (size_t i = 0; i < shiftedCube.Points.size(); ++i)
  {
    shiftedCube.Points[i] =
      0.9 * shiftedCube.Points[i] + 0.17 * static_cast<double>(i % 3 + 1) - 0.2;
  }
  shiftedCube.Finish();
  TestMesh sphere = mptest::Icosphere(5);
  TestMesh uv = mptest::UvSphere(12, 19);
  sphere.Finish();
  uv.Finish();
  const MeshPair pairs[] = {
    { "2D", mptest::GridMesh(17, 15, 0.25, 111, 0, 0, 1, 1, LShapeWithHole),
      mptest::GridMesh(13, 19, 0.25, 112, -0.1, 0.05, 1, 1, LShapeWithHole) },
    { "3D", mptest::CubeMesh(7, 6, 5, 0.2, 121), shiftedCube }, { "surface", sphere, uv }
  };
  const mp::SpaceType spaces[4][2] = { { mp::SpaceType::P1, mp::SpaceType::P1 },
    { mp::SpaceType::P1, mp::SpaceType::P0 }, { mp::SpaceType::P0, mp::SpaceType::P1 },
    { mp::SpaceType::P0, mp::SpaceType::P0 } };
  for (const MeshPair& pair : pairs)
  {
    const mp::MeshView target = pair.Target.View();
    const mp::MeshView source = pair.Source.View();
    // Fields per source space: two components.
    std::vector<double> fields[2];
    for (Index p = 0; p < source.NumberOfPoints; ++p)
    {
      const double* x = source.Point(p);
      fields[0].insert(fields[0].end(), { Smooth(x[0], x[1]) + x[2], 1.0 + x[0] - 2.0 * x[2] });
    }
    for (Index c = 0; c < source.NumberOfCells; ++c)
    {
      fields[1].insert(fields[1].end(), { std::cos(3.0 * static_cast<double>(c)), 0.5 });
    }
    for (int tasks : { 1, 3 })
    {
      for (bool given : { false, true })
      {
        std::vector<mp::OperatorOptions> options(4);
        for (int k = 0; k < 4; ++k)
        {
          options[k].TargetSpace = spaces[k][0];
          options[k].SourceSpace = spaces[k][1];
          options[k].KeepPieces = true;
          options[k].Runner.Tasks = tasks;
          options[k].Runner.Run = mptest::RunInThreads;
          // Fields given to every other operator (right-hand sides summed
          // during the search), M_ts assembled for the others.
          if (given == (k % 2 == 0))
          {
            const std::vector<double>& f = fields[spaces[k][1] == mp::SpaceType::P1 ? 0 : 1];
            options[k].Fields = f.data();
            options[k].FieldComponents = 2;
          }
        }
        mp::MortarOperator alone[4];
        mp::MortarOperator together[4];
        for (int k = 0; k < 4; ++k)
        {
          mp::BoxGridLocator locator(source);
          ASSERT_TRUE(alone[k].Build(target, source, &locator, options[k])) << alone[k].GetError();
        }
        mp::BoxGridLocator locator(source);
        ASSERT_TRUE(mp::MortarOperator::BuildTogether(
          { &together[0], &together[1], &together[2], &together[3] }, options, target, source,
          &locator))
          << together[0].GetError();
        for (int k = 0; k < 4; ++k)
        {
          const std::string what = std::string(pair.Name) + " operator " + std::to_string(k) +
            ", " + std::to_string(tasks) + " tasks" + (given ? ", fields given" : "");
          const mp::MortarOperator& a = alone[k];
          const mp::MortarOperator& b = together[k];
          EXPECT_EQ(a.GetTargetMass().RowStart, b.GetTargetMass().RowStart) << what;
          EXPECT_EQ(a.GetTargetMass().ColumnIndex, b.GetTargetMass().ColumnIndex) << what;
          EXPECT_EQ(a.GetTargetMass().Values, b.GetTargetMass().Values) << what;
          EXPECT_EQ(a.GetMixedMass().RowStart, b.GetMixedMass().RowStart) << what;
          EXPECT_EQ(a.GetMixedMass().ColumnIndex, b.GetMixedMass().ColumnIndex) << what;
          EXPECT_EQ(a.GetMixedMass().Values, b.GetMixedMass().Values) << what;
          EXPECT_EQ(a.HasMixedMass(), b.HasMixedMass()) << what;
          EXPECT_EQ(a.GetValid(), b.GetValid()) << what;
          EXPECT_EQ(a.GetCoveredIntegrals(), b.GetCoveredIntegrals()) << what;
          EXPECT_EQ(a.GetCoveredFraction(), b.GetCoveredFraction()) << what;
          EXPECT_EQ(a.GetSourceCovered(), b.GetSourceCovered()) << what;
          EXPECT_EQ(a.GetCoveredMeasure(), b.GetCoveredMeasure()) << what;
          EXPECT_EQ(a.GetStatistics().Pieces, b.GetStatistics().Pieces) << what;
          EXPECT_EQ(a.GetStatistics().IntersectionTests, b.GetStatistics().IntersectionTests)
            << what;
          EXPECT_EQ(a.GetPieces().Size(), b.GetPieces().Size()) << what;
          EXPECT_EQ(a.GetPieces().Measure, b.GetPieces().Measure) << what;
          EXPECT_GT(a.GetNumberOfValid(), 0) << what;
          const std::vector<double>& f = fields[spaces[k][1] == mp::SpaceType::P1 ? 0 : 1];
          std::vector<double> ua(static_cast<size_t>(a.GetNumberOfTargetFunctions()) * 2);
          std::vector<double> ub(ua.size());
          ASSERT_TRUE(a.Apply(f.data(), 2, ua.data(), -1.0)) << what;
          ASSERT_TRUE(b.Apply(f.data(), 2, ub.data(), -1.0)) << what;
          EXPECT_EQ(ua, ub) << what;
        }
      }
    }
  }
  // Two operators of one pair of spaces, or searches that differ, are refused.
  const TestMesh t = mptest::GridMesh(5, 5, 0.2, 131);
  const TestMesh s = mptest::GridMesh(4, 6, 0.2, 132);
  mp::BoxGridLocator locator(s.View());
  mp::MortarOperator a, b;
  std::vector<mp::OperatorOptions> same(2);
  EXPECT_FALSE(mp::MortarOperator::BuildTogether({ &a, &b }, same, t.View(), s.View(), &locator));
  EXPECT_NE(b.GetError().find("pairs of spaces"), std::string::npos) << b.GetError();
  same[1].TargetSpace = mp::SpaceType::P0;
  same[1].Method = mp::SearchMethod::BruteForce;
  EXPECT_FALSE(mp::MortarOperator::BuildTogether({ &a, &b }, same, t.View(), s.View(), &locator));
  EXPECT_NE(a.GetError().find("share their search"), std::string::npos) << a.GetError();
  same[1].Method = mp::SearchMethod::AdvancingFront;
  EXPECT_TRUE(mp::MortarOperator::BuildTogether({ &a, &b }, same, t.View(), s.View(), &locator));
}
