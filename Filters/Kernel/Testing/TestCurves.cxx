// SPDX-License-Identifier: BSD-3-Clause
// Curves: two discretizations of one curve, in the plane or in space (SegmentIntersector.h).
#include "Geometry/SegmentIntersector.h"
#include "GeneratedMeshes.h"
#include "ReachProjection.h"
#include "SearchComparison.h"
#include "Transfer/MortarOperator.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <random>

using mp::Index;
using mp::SegmentIntersector;
using mptest::Polyline;
using mptest::TestMesh;
using mptest::Uniform;

namespace
{
const double Pi = 3.14159265358979323846;

void Circle(double s, double* p)
{
  p[0] = std::cos(s);
  p[1] = std::sin(s);
}

void Helix(double s, double* p)
{
  p[0] = std::cos(s);
  p[1] = std::sin(s);
  p[2] = 0.3 * s;
}

double Smooth(const double* x)
{
  return std::sin(2.0 * x[0]) + x[1] * x[1] + 0.5 * x[2];
}

double Linear(const double* x)
{
  return 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2];
}

double Length(const TestMesh& m, Index c)
{
  SegmentIntersector::Cell cell;
  return SegmentIntersector::Prepare(m.View(false), c, cell) ? cell.Measure : 0.0;
}
} // namespace

TEST(Curves, CircleFrontEqualsBruteForceAndPiecesTileTheTarget)
{
  const TestMesh target = Polyline(Uniform(50, 0, 2 * Pi, 0.3, 1, true), Circle, true);
  const TestMesh source = Polyline(Uniform(37, 0.1, 2 * Pi + 0.1, 0.3, 2, true), Circle, true);
  mptest::SearchComparison<SegmentIntersector> search(target, source);
  search.ExpectSamePairs("circle");
  EXPECT_EQ(search.FrontStats.FullLocatorQueries, 0);
  mptest::ReachProjection p(target, source);
  ASSERT_TRUE(p.Ok) << p.Op.GetError();
  const auto covered = p.Covered();
  ASSERT_EQ(static_cast<Index>(covered.size()), target.NumberOfCells());
  for (const auto& c : covered)
  {
    EXPECT_NEAR(c.second, Length(target, c.first), 1e-12 * Length(target, c.first)) << c.first;
  }
  EXPECT_EQ(p.Op.GetNumberOfValid(), target.NumberOfPoints());
  EXPECT_EQ(p.Op.GetNumberOfOvercoveredCells(), 0);
}

TEST(Curves, LinearFieldsExactOnStraightAndCorneredLines)
{
  // A straight segment [0, 1] against a longer one; then an L (its corner a
  // point of both), the legs at 90 degrees are never matched.
  auto line = [](double s, double* p) {
    p[0] = s;
    p[1] = 0.5 * s;
  };
  auto ell = [](double s, double* p) {
    p[0] = std::min(s, 1.0);
    p[1] = std::max(s - 1.0, 0.0);
    p[2] = 0.2;
  };
  for (int shape = 0; shape < 2; ++shape)
  {
    const auto& x = shape == 0 ? std::function<void(double, double*)>(line) : ell;
    std::vector<double> ts = Uniform(13, 0, 2, 0.3, 3, false);
    std::vector<double> ss =
      Uniform(17, shape == 0 ? -0.1 : 0, shape == 0 ? 2.1 : 2, 0.3, 4, false);
    if (shape == 1)
    {
      ts.push_back(1.0); // the corner in both
      ss.push_back(1.0);
      std::sort(ts.begin(), ts.end());
      std::sort(ss.begin(), ss.end());
    }
    const TestMesh target = Polyline(ts, x, false, 3);
    const TestMesh source = Polyline(ss, x, false, 3);
    mptest::SearchComparison<SegmentIntersector> search(target, source);
    search.ExpectSamePairs(shape == 0 ? "line" : "L");
    mptest::ReachProjection p(target, source);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    EXPECT_LT(
      mptest::MaxPointError(target, p.Apply(mptest::SampleAtPoints(source, Linear)), Linear), 1e-12)
      << shape;
    for (const auto& c : p.Covered())
    {
      EXPECT_NEAR(c.second, Length(target, c.first), 1e-13) << shape << " " << c.first;
    }
  }
}

TEST(Curves, CircleAndHelixConvergeAtSecondOrder)
{
  for (int curve = 0; curve < 2; ++curve)
  {
    double previous = 0.0;
    for (int level = 0; level < 4; ++level)
    {
      const int k = 1 << level;
      const bool closed = curve == 0;
      const auto x = curve == 0 ? Circle : Helix;
      const double end = curve == 0 ? 2 * Pi : 4 * Pi;
      const TestMesh target =
        Polyline(Uniform(20 * k, 0, end, 0.3, 5, closed), x, closed, 2 + curve);
      const TestMesh source = Polyline(
        Uniform(27 * k, curve == 0 ? 0.05 : -0.2, end + (curve == 0 ? 0.05 : 0.2), 0.3, 6, closed),
        x, closed, 2 + curve);
      mptest::ReachProjection p(target, source);
      ASSERT_TRUE(p.Ok) << p.Op.GetError();
      ASSERT_EQ(p.Op.GetNumberOfValid(), target.NumberOfPoints());
      const auto ut = p.Apply(mptest::SampleAtPoints(source, Smooth));
      double sum = 0.0;
      for (Index q = 0; q < target.NumberOfPoints(); ++q)
      {
        const double e = ut[q] - Smooth(&target.Points[3 * q]);
        sum += e * e;
      }
      const double rms = std::sqrt(sum / target.NumberOfPoints());
      if (level > 0)
      {
        EXPECT_GT(std::log2(previous / rms), 1.8) << "curve " << curve << " level " << level;
      }
      previous = rms;
    }
  }
}

TEST(Curves, HelixFrontEqualsBruteForceAndConserves)
{
  const TestMesh target = Polyline(Uniform(80, 0, 4 * Pi, 0.3, 7, false), Helix, false, 3);
  const TestMesh source = Polyline(Uniform(61, -0.3, 4 * Pi + 0.3, 0.3, 8, false), Helix, false, 3);
  mptest::SearchComparison<SegmentIntersector> search(target, source);
  search.ExpectSamePairs("helix");
  mptest::ReachProjection p(target, source);
  ASSERT_TRUE(p.Ok);
  const auto us = mptest::SampleAtPoints(source, Smooth);
  const auto ut = p.Apply(us);
  const auto integrals = p.Integrals(us, ut);
  EXPECT_NEAR(integrals.first, integrals.second, 1e-12 * std::fabs(integrals.second));
}

TEST(Curves, ParallelLinesWithinAndBeyondReach)
{
  auto low = [](double s, double* p) { p[0] = s; };
  auto high = [](double s, double* p) {
    p[0] = s;
    p[1] = 0.01;
  };
  const TestMesh target = Polyline(Uniform(10, 0, 1, 0.3, 9, false), low, false);
  const TestMesh source = Polyline(Uniform(13, 0, 1, 0.3, 10, false), high, false);
  mptest::ReachProjection near(target, source, 0.5);
  ASSERT_TRUE(near.Ok);
  auto ut = near.Apply(mptest::SampleAtPoints(source, Linear));
  for (Index q = 0; q < target.NumberOfPoints(); ++q)
  {
    const double x[3] = { target.Points[3 * q], 0.01, 0.0 };
    ASSERT_NEAR(ut[q], Linear(x), 1e-12) << q;
  }
  mptest::ReachProjection far(target, source, 0.05); // 0.05 x about 0.1 < 0.01
  ASSERT_TRUE(far.Ok);
  EXPECT_EQ(far.Op.GetNumberOfValid(), 0);
  mptest::SearchComparison<SegmentIntersector> search(target, source);
  search.ExpectSamePairs("parallel");
}

TEST(Curves, AZigzagOfScreenedSegmentsDoesNotStopTheFront)
{
  // The source runs along y = 0 but crosses x in [0.5, 0.52] as a steep
  // zigzag (segments at 80 degrees, screened out): coarse target segments
  // along y = 0.005 meet source segments on both sides of it.
  TestMesh source;
  source.Dimension = 1;
  std::vector<std::array<double, 2>> xy;
  for (int i = 0; i <= 25; ++i)
  {
    xy.push_back({ 0.02 * i, 0.0 });
  }
  xy.push_back({ 0.5025, 0.01 });
  xy.push_back({ 0.505, 0.0 });
  xy.push_back({ 0.5075, 0.01 });
  xy.push_back({ 0.51, 0.0 });
  for (int i = 0; i <= 24; ++i)
  {
    xy.push_back({ 0.52 + 0.02 * i, 0.0 });
  }
  for (size_t i = 0; i < xy.size(); ++i)
  {
    source.Points.insert(source.Points.end(), { xy[i][0], xy[i][1], 0.0 });
    if (i > 0)
    {
      source.Cells.insert(source.Cells.end(), { Index(i - 1), Index(i) });
    }
  }
  source.Finish();
  auto line = [](double s, double* p) {
    p[0] = s;
    p[1] = 0.005;
  };
  const TestMesh target = Polyline({ 0.0, 0.3, 0.7, 1.0 }, line, false);
  mptest::SearchComparison<SegmentIntersector> search(target, source);
  search.ExpectSamePairs("zigzag");
  EXPECT_GT(search.FrontStats.FullLocatorQueries, 0);
}
