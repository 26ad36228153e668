// SPDX-License-Identifier: BSD-3-Clause
// FringeAggregation (Transfer/FringeAggregation.h): on a 2D and a 3D mesh,
// a plane and a line in 3D and a sphere
// whose points beyond a line are ill-posed, P reproduces affine functions
// at the aggregated points from the free values, its aggregated rows sum to
// 1 and read free functions only, P^T M P is the dense product, and the
// support integrals add up to the mesh's measure; the search beyond
// FringeRings and the drop of functions with no stencil; in 3D, quadratic
// fits with bounded weights where the rings allow them.
#include "Transfer/FringeAggregation.h"
#include "Transfer/FringeFits.h"

#include "GeneratedMeshes.h"
#include "Threads.h"
#include "Transfer/MassMatrix.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace
{
using mp::Index;
using mptest::TestMesh;

double Affine(const double* x)
{
  return 0.3 + 1.7 * x[0] - 0.6 * x[1] + 0.9 * x[2];
}

struct Fringe
{
  std::vector<char> Valid;
  std::vector<double> Fraction;
  mp::FringeExtension Extension;
};

/// Every point valid; those with x > `edge` covered 5 % (ill-posed at a threshold of 10 %), 1 % beyond `drop`.
Fringe FringeOf(const TestMesh& m, double edge, double drop, int tasks)
{
  Fringe f;
  const mp::MeshView view = m.View(false);
  f.Valid.assign(static_cast<size_t>(view.NumberOfPoints), 1);
  f.Fraction.assign(static_cast<size_t>(view.NumberOfPoints), 1.0);
  for (Index i = 0; i < view.NumberOfPoints; ++i)
  {
    const double x = view.Point(i)[0];
    f.Fraction[i] = x > drop ? 0.01 : (x > edge ? 0.05 : 1.0);
  }
  f.Extension = mp::ExtendFringe(
    view, f.Valid, f.Fraction, 0.1, mp::FringeDropFraction, mptest::ThreadRunner(tasks));
  return f;
}

/// Points where `valid` holds valid, those where also `ill` holds covered 5 % (ill-posed at a threshold of 10 %).
Fringe FringeWhere(const TestMesh& m, const std::function<bool(const double*)>& valid,
  const std::function<bool(const double*)>& ill, int tasks)
{
  Fringe f;
  const mp::MeshView view = m.View(false);
  f.Valid.assign(static_cast<size_t>(view.NumberOfPoints), 1);
  f.Fraction.assign(static_cast<size_t>(view.NumberOfPoints), 1.0);
  for (Index i = 0; i < view.NumberOfPoints; ++i)
  {
    f.Valid[i] = valid(view.Point(i));
    f.Fraction[i] = f.Valid[i] && ill(view.Point(i)) ? 0.05 : 1.0;
  }
  f.Extension = mp::ExtendFringe(
    view, f.Valid, f.Fraction, 0.1, mp::FringeDropFraction, mptest::ThreadRunner(tasks));
  return f;
}

/// P's rows: identity on free functions; on aggregated ones weights that sum to 1 over free functions and reproduce an affine field.
void ExpectAffineExtension(const TestMesh& m, const Fringe& f, const char* what)
{
  const mp::MeshView view = m.View(false);
  const mp::FringeExtension& e = f.Extension;
  const Index n = view.NumberOfPoints;
  ASSERT_EQ(e.P.Rows, n) << what;
  Index aggregated = 0;
  Index ill = 0;
  for (Index i = 0; i < n; ++i)
  {
    ill += f.Fraction[i] < 0.1;
    if (!e.Aggregated[i])
    {
      ASSERT_EQ(e.P.RowStart[i + 1] - e.P.RowStart[i], 1) << what << ", free " << i;
      EXPECT_EQ(e.P.ColumnIndex[e.P.RowStart[i]], i) << what;
      EXPECT_EQ(e.P.Values[e.P.RowStart[i]], 1.0) << what;
      continue;
    }
    ++aggregated;
    EXPECT_LT(f.Fraction[i], 0.1) << what << ": a well-covered point aggregated";
    EXPECT_EQ(e.Dropped[i], f.Fraction[i] < mp::FringeDropFraction) << what << ", point " << i;
    double sum = 0.0;
    double value = 0.0;
    for (Index q = e.P.RowStart[i]; q < e.P.RowStart[i + 1]; ++q)
    {
      const Index k = e.P.ColumnIndex[q];
      EXPECT_FALSE(e.Aggregated[k]) << what << ": row " << i << " reads an aggregated function";
      EXPECT_GE(f.Fraction[k], 0.1) << what;
      sum += e.P.Values[q];
      value += e.P.Values[q] * Affine(view.Point(k));
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << what << ", row " << i;
    EXPECT_NEAR(value, Affine(view.Point(i)), 1e-11) << what << ", row " << i;
  }
  EXPECT_EQ(aggregated, e.Count) << what;
  // (Ill-posed points without a stable fit within FringeSearchRings rings
  // are not aggregated: dropped, covered 1 % or 5 % here.)
  for (Index i = 0; i < n; ++i)
  {
    EXPECT_TRUE(e.Aggregated[i] || f.Fraction[i] >= 0.1 || e.Dropped[i]) << what << ", " << i;
  }
  EXPECT_LE(aggregated, ill) << what;
  EXPECT_GT(aggregated, ill / 3) << what;
  EXPECT_GT(aggregated, 10) << what;
  // ExtendFromFree: the affine field's free values give it at the aggregated points.
  std::vector<double> u(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    u[i] = e.Aggregated[i] ? 1e3 : Affine(view.Point(i));
  }
  mp::ExtendFromFree(e, u.data(), 1);
  for (Index i = 0; i < n; ++i)
  {
    EXPECT_NEAR(u[i], Affine(view.Point(i)), 1e-11) << what << ", point " << i;
  }
}
} // namespace

TEST(FringeAggregation, ReproducesAffineFunctionsIn2D)
{
  const TestMesh m = mptest::GridMesh(14, 12, 0.25, 3);
  for (int tasks : { 1, 3 })
  {
    const Fringe f = FringeOf(m, 0.75, 0.9, tasks);
    ExpectAffineExtension(m, f, tasks == 1 ? "2D" : "2D, 3 tasks");
  }
}

TEST(FringeAggregation, ReproducesAffineFunctionsIn3D)
{
  const TestMesh m = mptest::CubeMesh(6, 5, 6, 0.2, 4);
  for (int tasks : { 1, 3 })
  {
    const Fringe f = FringeOf(m, 0.7, 0.9, tasks);
    ExpectAffineExtension(m, f, tasks == 1 ? "3D" : "3D, 3 tasks");
  }
}

TEST(FringeAggregation, QuadraticWhereBoundedIn3D)
{
  // Most points beyond the line find, within FringeVolumeRings rings, a
  // quadratic fit whose weights stay bounded: their rows reproduce a
  // quadratic field, with sum |w| at most 12; the others an affine one
  // (ReproducesAffineFunctionsIn3D).
  const TestMesh m = mptest::CubeMesh(8, 7, 8, 0.2, 4);
  const Fringe f = FringeOf(m, 0.7, 0.95, 1);
  const mp::MeshView view = m.View(false);
  const mp::FringeExtension& e = f.Extension;
  auto quadratic = [](const double* x) {
    return 0.5 + x[0] * x[0] - 1.3 * x[0] * x[1] + 0.7 * x[1] * x[2] + 2.1 * x[2] * x[2] - x[1];
  };
  Index reproduced = 0;
  for (Index i = 0; i < view.NumberOfPoints; ++i)
  {
    if (!e.Aggregated[i])
    {
      continue;
    }
    double value = 0.0;
    double amplification = 0.0;
    for (Index q = e.P.RowStart[i]; q < e.P.RowStart[i + 1]; ++q)
    {
      value += e.P.Values[q] * quadratic(view.Point(e.P.ColumnIndex[q]));
      amplification += std::abs(e.P.Values[q]);
    }
    if (std::abs(value - quadratic(view.Point(i))) < 1e-10)
    {
      ++reproduced;
      EXPECT_LE(amplification, 12.0 + 1e-12) << "point " << i;
    }
  }
  EXPECT_GT(e.Count, 20);
  EXPECT_GT(reproduced, e.Count / 2) << reproduced << " of " << e.Count;
}

TEST(FringeAggregation, WeighsFreePointsByTheirCoverage)
{
  // Points beyond x = 0.7 ill-posed, those in (0.55, 0.7] free but covered
  // 30 %: fits weighing their points by their covered fraction squared
  // (FringeCoveragePower) still reproduce affine functions, and the weight
  // they give the partly covered points is smaller than unweighed fits'.
  const TestMesh m = mptest::CubeMesh(8, 7, 8, 0.2, 4);
  const mp::MeshView view = m.View(false);
  const Index n = view.NumberOfPoints;
  Fringe plain;
  plain.Valid.assign(static_cast<size_t>(n), 1);
  plain.Fraction.assign(static_cast<size_t>(n), 1.0);
  for (Index i = 0; i < n; ++i)
  {
    const double x = view.Point(i)[0];
    plain.Fraction[i] = x > 0.7 ? 0.05 : (x > 0.55 ? 0.3 : 1.0);
  }
  Fringe weighed = plain;
  plain.Extension = mp::ExtendFringe(
    view, plain.Valid, plain.Fraction, 0.1, mp::FringeDropFraction, mptest::ThreadRunner(1));
  weighed.Extension = mp::ExtendFringe(view, weighed.Valid, weighed.Fraction, 0.1,
    mp::FringeDropFraction, mptest::ThreadRunner(3), false, mp::FringeCoveragePower);
  ExpectAffineExtension(m, weighed, "weighed by coverage");
  auto partlyCovered = [&](const mp::FringeExtension& e) {
    double sum = 0.0;
    for (Index i = 0; i < n; ++i)
    {
      for (Index q = e.Aggregated[i] ? e.P.RowStart[i] : 0;
           e.Aggregated[i] && q < e.P.RowStart[i + 1]; ++q)
      {
        sum += plain.Fraction[e.P.ColumnIndex[q]] < 1.0 ? std::abs(e.P.Values[q]) : 0.0;
      }
    }
    return sum;
  };
  EXPECT_EQ(weighed.Extension.Count, plain.Extension.Count);
  EXPECT_LT(partlyCovered(weighed.Extension), 0.8 * partlyCovered(plain.Extension));
}

// On surfaces and curves the stencils are fitted in the tangent frame of
// each point (FringeFrames.h, FringeFits.h): on a plane in 3D and a
// straight line in 3D the extension reproduces the ambient affine
// functions; on a sphere too (the fit through the normal coordinates of
// its curved stencils).
TEST(FringeAggregation, ReproducesAffineFunctionsOnAPlaneIn3D)
{
  TestMesh m = mptest::GridMesh(14, 12, 0.25, 3);
  m.Surface = true;
  mptest::Move3D(m, 0.0, 0.6, 1.0, 0.1, -0.2, 0.3); // about the x axis: x kept
  for (int tasks : { 1, 3 })
  {
    const Fringe f = FringeOf(m, 0.75, 0.9, tasks);
    ExpectAffineExtension(m, f, tasks == 1 ? "plane in 3D" : "plane in 3D, 3 tasks");
  }
}

TEST(FringeAggregation, ReproducesAffineFunctionsOnALineIn3D)
{
  // Five gaps of ill-posed points along the line, one at its end.
  const TestMesh m = mptest::Polyline(
    mptest::Uniform(200, 0.0, 1.0, 0.3, 5, false),
    [](double s, double* x) {
      x[0] = s;
      x[1] = 0.2 + 0.5 * s;
      x[2] = -0.3 - 0.7 * s;
    },
    false, 3);
  for (int tasks : { 1, 3 })
  {
    const Fringe f = FringeWhere(
      m, [](const double*) { return true; },
      [](const double* x) { return x[0] * 5 - std::floor(x[0] * 5) > 0.85; }, tasks);
    ExpectAffineExtension(m, f, tasks == 1 ? "line in 3D" : "line in 3D, 3 tasks");
  }
}

TEST(FringeAggregation, ReproducesAffineFunctionsOnAnArcIn3D)
{
  // An arc of a circle in a tilted plane, ill-posed in five gaps of two or
  // three points: its curved stencils fitted through their normal
  // coordinates too (a gap's last point from the inner ring whose points
  // allow that). (At the arc's end the one-sided fit through them would
  // amplify more than QuadraticAmplification: the tangent fit is kept.)
  const TestMesh m = mptest::Polyline(
    mptest::Uniform(120, 0.0, 2.5, 0.3, 6, false),
    [](double s, double* x) {
      x[0] = 0.8 * std::cos(s);
      x[1] = 0.8 * std::sin(s) * std::cos(0.4);
      x[2] = 0.8 * std::sin(s) * std::sin(0.4) + 0.3;
    },
    false, 3);
  for (int tasks : { 1, 3 })
  {
    // (Parameter s from the point: the angle about the circle's centre.)
    const Fringe f = FringeWhere(
      m, [](const double*) { return true; },
      [](const double* x) {
        const double s = std::atan2(x[1] / std::cos(0.4), x[0]);
        return s * 2 - std::floor(s * 2) > 0.9;
      },
      tasks);
    ExpectAffineExtension(m, f, tasks == 1 ? "arc in 3D" : "arc in 3D, 3 tasks");
  }
}

TEST(FringeAggregation, ReproducesAffineFunctionsAtTheEndOfAnArc)
{
  // An arc whose last point is ill-posed: extended from one side through
  // the points' normal offsets (the nearest few amplify more than
  // QuadraticAmplification there, more of them less), so that an ambient
  // affine field stays exact, with bounded weights. (Two cells beyond the
  // last well-covered point the six rings' points still amplify more.)
  for (const double end : { 1.47, 1.46 })
  {
    for (int seed : { 7, 8 })
    {
      const TestMesh m = mptest::Polyline(
        mptest::Uniform(40, 0.0, 1.5, 0.3, seed, false),
        [](double s, double* x) {
          x[0] = 0.8 * std::cos(s);
          x[1] = 0.8 * std::sin(s) * std::cos(0.7);
          x[2] = 0.8 * std::sin(s) * std::sin(0.7) + 0.3;
        },
        false, 3);
      const Fringe f = FringeWhere(
        m, [](const double*) { return true; },
        [end](const double* x) { return std::atan2(x[1] / std::cos(0.7), x[0]) > end; }, 1);
      const mp::MeshView view = m.View(false);
      const mp::FringeExtension& e = f.Extension;
      EXPECT_GE(e.Count, 1) << end << ", seed " << seed;
      for (Index i = 0; i < view.NumberOfPoints; ++i)
      {
        EXPECT_TRUE(e.Aggregated[i] || f.Fraction[i] >= 0.1) << "point " << i;
        if (!e.Aggregated[i])
        {
          continue;
        }
        double sum = 0.0;
        double value = 0.0;
        double amplification = 0.0;
        for (Index q = e.P.RowStart[i]; q < e.P.RowStart[i + 1]; ++q)
        {
          sum += e.P.Values[q];
          value += e.P.Values[q] * Affine(view.Point(e.P.ColumnIndex[q]));
          amplification += std::abs(e.P.Values[q]);
        }
        EXPECT_NEAR(sum, 1.0, 1e-12) << end << ", seed " << seed << ", row " << i;
        EXPECT_NEAR(value, Affine(view.Point(i)), 1e-11)
          << end << ", seed " << seed << ", row " << i;
        EXPECT_LE(amplification, mp::QuadraticAmplification)
          << end << ", seed " << seed << ", row " << i;
      }
    }
  }
}

TEST(FringeAggregation, ReproducesAffineFunctionsOnASphere)
{
  // Valid below x = 0.6, a fringe of about two rings above x = 0.4: extended
  // from one side, over the sphere's curvature.
  const TestMesh m = mptest::Icosphere(4);
  for (int tasks : { 1, 3 })
  {
    const Fringe f = FringeWhere(
      m, [](const double* x) { return x[0] <= 0.6; }, [](const double* x) { return x[0] > 0.4; },
      tasks);
    ExpectAffineExtension(m, f, tasks == 1 ? "sphere" : "sphere, 3 tasks");
  }
}

TEST(FringeAggregation, AggregatedMassIsPTransposedMP)
{
  // P^T M P on a random M of the mass matrix's pattern against the dense
  // product; aggregated rows: 1 on the diagonal.
  const TestMesh m = mptest::GridMesh(8, 7, 0.2, 5);
  const mp::MeshView view = m.View(false);
  const Fringe f = FringeOf(m, 0.7, 2.0, 1);
  const mp::FringeExtension& e = f.Extension;
  ASSERT_GT(e.Count, 0);
  mp::CsrMatrix mass;
  mp::MassPattern(mp::SpaceType::P1, view, mp::TaskRunner(), mass);
  std::mt19937 rng(9);
  for (auto& v : mass.Values)
  {
    v = std::uniform_real_distribution<double>(0.1, 1.0)(rng);
  }
  const Index n = mass.Rows;
  auto dense = [n](const mp::CsrMatrix& a) {
    std::vector<double> d(static_cast<size_t>(n * n), 0.0);
    for (Index i = 0; i < a.Rows; ++i)
    {
      for (Index q = a.RowStart[i]; q < a.RowStart[i + 1]; ++q)
      {
        d[i * n + a.ColumnIndex[q]] += a.Values[q];
      }
    }
    return d;
  };
  const std::vector<double> M = dense(mass);
  const std::vector<double> P = dense(e.P);
  std::vector<double> MP(static_cast<size_t>(n * n), 0.0);
  for (Index i = 0; i < n; ++i)
    for (Index k = 0; k < n; ++k)
      for (Index j = 0; j < n; ++j)
        MP[i * n + j] += M[i * n + k] * P[k * n + j];
  const mp::CsrMatrix A = mp::AggregatedMass(mass, e, mptest::ThreadRunner(2));
  const std::vector<double> got = dense(A);
  for (Index i = 0; i < n; ++i)
  {
    EXPECT_TRUE(std::is_sorted(
      A.ColumnIndex.begin() + A.RowStart[i], A.ColumnIndex.begin() + A.RowStart[i + 1]));
    for (Index j = 0; j < n; ++j)
    {
      double expected = 0.0;
      for (Index k = 0; k < n; ++k)
      {
        expected += P[k * n + i] * MP[k * n + j];
      }
      if (e.Aggregated[i])
      {
        expected = i == j ? 1.0 : 0.0;
      }
      EXPECT_NEAR(got[i * n + j], expected, 1e-12) << "(" << i << ", " << j << ")";
    }
  }
}

TEST(FringeAggregation, SupportIntegralsAddUpToTheMeasure)
{
  for (const TestMesh& m : { mptest::GridMesh(9, 8, 0.3, 6), mptest::CubeMesh(4, 5, 3, 0.2, 7) })
  {
    const mp::MeshView view = m.View(false);
    const auto support = mp::SupportIntegrals(view);
    double total = 0.0;
    for (Index c = 0; c < m.NumberOfCells(); ++c)
    {
      total += m.CellArea(c);
    }
    double sum = 0.0;
    for (double s : support)
    {
      EXPECT_GT(s, 0.0);
      sum += s;
    }
    EXPECT_NEAR(sum, total, 1e-12 * total);
    EXPECT_NEAR(total, 1.0, 1e-12); // the unit square or cube
  }
}

namespace
{
/**
 * A bar of nx x 3 x 3 cubes well covered within `wall` columns of points at
 * each end, ill-posed between (5 % covered, `free` (15 %) in the middle
 * column's upper half; threshold 20 %), a column one ring from the next:
 * P with each kind of point counted, after checking the rules (ill-posed
 * points only aggregated, onto stencils that reproduce affine functions and
 * lie within FringeSearchRings columns; an ill-posed point not aggregated
 * dropped exactly when covered less than FringeStrandedDropFraction).
 */
struct Gap
{
  Index Farther = 0;  ///< aggregated more than FringeRings columns from the wall
  Index Stranded = 0; ///< not aggregated, dropped
  Index Free = 0;     ///< ill-posed, neither aggregated nor dropped
};

Gap FringeInGap(int nx, int wall, double free, int tasks)
{
  const TestMesh m = mptest::CubeMesh(nx, 3, 3, 0.2, 11);
  const mp::MeshView view = m.View(false);
  const Index n = view.NumberOfPoints;
  std::vector<char> valid(static_cast<size_t>(n), 1);
  std::vector<double> fraction(static_cast<size_t>(n), 1.0);
  std::vector<int> away(static_cast<size_t>(n)); // columns to the nearest well-covered one
  for (Index i = 0; i < n; ++i)
  {
    const int column = static_cast<int>(std::lround(view.Point(i)[0] * nx));
    away[i] = std::max(0, std::min(column - wall, nx - wall - column));
    const bool middle = 2 * column == nx && view.Point(i)[1] > 0.5;
    fraction[i] = away[i] == 0 ? 1.0 : (middle ? free : 0.05);
  }
  const mp::FringeExtension e = mp::ExtendFringe(
    view, valid, fraction, 0.2, mp::FringeDropFraction, mptest::ThreadRunner(tasks));
  Gap gap;
  std::vector<double> u(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    const bool ill = fraction[i] < 0.2;
    EXPECT_TRUE(ill || !e.Aggregated[i]) << "point " << i;
    EXPECT_TRUE(!e.Aggregated[i] || away[i] <= mp::FringeSearchRings) << "point " << i;
    if (ill && !e.Aggregated[i])
    {
      EXPECT_EQ(e.Dropped[i], fraction[i] < mp::FringeStrandedDropFraction) << "point " << i;
    }
    gap.Farther += e.Aggregated[i] && away[i] > mp::FringeRings;
    gap.Stranded += ill && !e.Aggregated[i] && e.Dropped[i];
    gap.Free += ill && !e.Aggregated[i] && !e.Dropped[i];
    u[i] = e.Aggregated[i] ? 1e3 : Affine(view.Point(i));
  }
  EXPECT_EQ(gap.Stranded, e.Stranded);
  // The farther stencils reproduce affine functions too.
  mp::ExtendFromFree(e, u.data(), 1);
  for (Index i = 0; i < n; ++i)
  {
    EXPECT_NEAR(u[i], Affine(view.Point(i)), 1e-11) << "point " << i;
  }
  return gap;
}
} // namespace

TEST(FringeAggregation, SeeksFartherRingsThenDropsWhatHasNoStencil)
{
  for (int tasks : { 1, 3 })
  {
    // A gap of 7 columns: its middle one is more than FringeRings rings
    // from both walls, within FringeSearchRings: extended from both.
    const Gap near = FringeInGap(14, 3, 0.05, tasks);
    EXPECT_GT(near.Farther, 0) << tasks << " tasks";
    EXPECT_EQ(near.Stranded, 0) << tasks << " tasks";
    EXPECT_EQ(near.Free, 0) << tasks << " tasks";
    // A gap of 17 columns: its middle column is beyond FringeSearchRings
    // rings of both walls: dropped at 5 %, free (valid) at 15 %.
    const Gap far = FringeInGap(24, 3, 0.15, tasks);
    EXPECT_GT(far.Stranded, 0) << tasks << " tasks";
    EXPECT_GT(far.Free, 0) << tasks << " tasks";
  }
}
