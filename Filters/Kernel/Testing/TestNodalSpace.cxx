// SPDX-License-Identifier: BSD-3-Clause
// Point data in the cells' own space (Transfer/NodalSpace.h) projected by
// quadrature (Transfer/QuadratureAssembler.h), on the second-order meshes
// of NodalMeshes.h (tri6 squares, tet10 cubes, curved tri6 disks, tilted
// planes, edge3 lines): what the projection must keep (quadratic fields on
// straight cells, the integral onto a linear target, linear fields on
// curved cells) and the matrices of a brute-force assembly.
#include "Geometry/CellGeometry.h"
#include "Geometry/SimplexQuadrature.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"
#include "Mesh/CellNeighbors.h"
#include "Mesh/NodalCells.h"
#include "Search/CandidateLocator.h"
#include "Transfer/MortarOperator.h"
#include "Transfer/NodalSpace.h"
#include "Transfer/QuadratureAssembler.h"
#include "NodalMeshes.h"
#include "Threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

namespace
{
using mp::Index;
using mp::NodalType;
using namespace nodaltest;

struct Built
{
  mp::MortarOperator Op;
  bool Ok = false;
  Built(const NodalMesh& target, const NodalMesh& source,
    mp::SpaceType targetSpace = mp::SpaceType::P1, mp::SpaceType sourceSpace = mp::SpaceType::P1)
  {
    const mp::MeshView s = source.View();
    mp::BoxGridLocator locator(s);
    mp::OperatorOptions options;
    options.TargetSpace = targetSpace;
    options.SourceSpace = sourceSpace;
    this->Ok = this->Op.Build(target.View(), s, &locator, options);
  }
};

using Field = std::function<double(const double*)>;

double Quadratic2(const double* x)
{
  return 1.0 + x[0] - 2.0 * x[1] + 3.0 * x[0] * x[0] - x[0] * x[1] + 2.0 * x[1] * x[1];
}
double Quadratic3(const double* x)
{
  return Quadratic2(x) + 0.5 * x[2] - 1.5 * x[2] * x[2] + x[0] * x[2] + 2.0 * x[1] * x[2];
}
double LinearField(const double* x)
{
  return 0.5 - 2.0 * x[0] + 3.0 * x[1];
}

std::vector<double> AtPoints(const NodalMesh& mesh, const Field& f)
{
  std::vector<double> u(size_t(mesh.NumberOfPoints()));
  for (Index p = 0; p < mesh.NumberOfPoints(); ++p)
    u[p] = f(mesh.Point(p));
  return u;
}

/// The largest |projected - f| at the target's nodes, over f's range there.
double WorstRelativeError(const NodalMesh& target, const NodalMesh& source, const Field& f)
{
  Built b(target, source);
  EXPECT_TRUE(b.Ok) << b.Op.GetError();
  const std::vector<double> us = AtPoints(source, f);
  const std::vector<double> exact = AtPoints(target, f);
  std::vector<double> ut(exact.size());
  EXPECT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), std::nan("")).Ok);
  const auto range = std::minmax_element(exact.begin(), exact.end());
  double worst = 0.0;
  for (size_t p = 0; p < ut.size(); ++p)
    worst = std::max(worst, std::fabs(ut[p] - exact[p]));
  EXPECT_EQ(b.Op.GetNumberOfValid(), target.NumberOfPoints());
  return worst / (*range.second - *range.first);
}

// (a) A quadratic field at every source node is reproduced at every node
// of a straight second-order target.
TEST(NodalSpace, QuadraticFieldOnStraightTriangles)
{
  const NodalMesh source = Square(5, 0.2, 1);
  const NodalMesh target = Square(7, 0.2, 2);
  EXPECT_LE(WorstRelativeError(target, source, Quadratic2), 1e-9);
}

TEST(NodalSpace, QuadraticFieldOnStraightTetrahedra)
{
  const NodalMesh source = Cube(2, 0.15, 3);
  const NodalMesh target = Cube(3, 0.15, 4);
  EXPECT_LE(WorstRelativeError(target, source, Quadratic3), 1e-9);
}

/// The integral of `u` (nodal values) over `mesh` in its own space, by the
/// quadrature of degree 4 on every simplex of its split.
double NodalIntegral(const NodalMesh& mesh, const std::vector<double>& u)
{
  const mp::MeshView view = mesh.View(false);
  const int d = mesh.Dimension;
  const mp::SimplexRule& rule = mp::SimplexQuadrature(d, 4);
  mp::NodalFunctions f;
  double sum = 0.0;
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    f.Bind(view, mp::SpaceType::P1, c);
    const double measure = mp::SimplexMeasure(view, c);
    for (int q = 0; q < rule.Points; ++q)
    {
      double x[3] = { 0, 0, 0 };
      for (int k = 0; k <= d; ++k)
        for (int a = 0; a < d; ++a)
          x[a] += rule.Barycentric[q * (d + 1) + k] * view.Point(view.Cell(c)[k])[a];
      double values[mp::MaxNodalFunctions];
      f.Values(x, values);
      for (int i = 0; i < f.Count; ++i)
        sum += rule.Weight[q] * measure * values[i] * u[f.Dofs[i]];
    }
  }
  return sum;
}

// (b) A second-order source onto a linear target keeps its exact integral.
TEST(NodalSpace, IntegralOntoLinearTarget)
{
  const NodalMesh source = Square(4, 0.2, 5);
  const NodalMesh target = LinearSquare(6, 0.2, 6);
  Built b(target, source);
  ASSERT_TRUE(b.Ok) << b.Op.GetError();
  const std::vector<double> us =
    AtPoints(source, [](const double* x) { return std::exp(x[0]) * std::sin(3 * x[1]) + 2.0; });
  std::vector<double> ut(size_t(target.NumberOfPoints()));
  ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), std::nan("")).Ok);
  double integral = 0.0;
  for (size_t i = 0; i < ut.size(); ++i)
    integral += b.Op.GetCoveredIntegrals()[i] * ut[i];
  const double exact = NodalIntegral(source, us);
  EXPECT_NEAR(integral, exact, 1e-11 * std::fabs(exact));
  EXPECT_NEAR(b.Op.GetCoveredMeasure(), 1.0, 1e-12);
}

TEST(NodalSpace, IntegralOntoLinearTargetInSpace)
{
  const NodalMesh source = Cube(2, 0.15, 7);
  NodalMesh target = Cube(3, 0.15, 8);
  target.Linear = true;
  Built b(target, source);
  ASSERT_TRUE(b.Ok) << b.Op.GetError();
  const std::vector<double> us = AtPoints(
    source, [](const double* x) { return std::exp(x[0] - x[2]) * std::sin(3 * x[1]) + 2.0; });
  std::vector<double> ut(size_t(target.NumberOfPoints()));
  ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), std::nan("")).Ok);
  double integral = 0.0;
  for (size_t i = 0; i < ut.size(); ++i)
    integral += b.Op.GetCoveredIntegrals()[i] * ut[i];
  const double exact = NodalIntegral(source, us);
  EXPECT_NEAR(integral, exact, 1e-11 * std::fabs(exact));
}

// (c) On curved disks a linear field is exact at every target node.
TEST(NodalSpace, LinearFieldOnCurvedDisks)
{
  const NodalMesh source = Disk(5);
  const NodalMesh target = Disk(4);
  EXPECT_LE(WorstRelativeError(target, source, LinearField), 1e-9);
  // Onto a curved target from a straight-sided source too, and back.
  const NodalMesh square = Square(4, 0.0, 0);
  NodalMesh inside = Disk(3);
  for (double& x : inside.Points)
    x = 0.25 + 0.2 * x; // the disk of radius 0.2 about (0.25, 0.25) (z stays 0.25: unread)
  EXPECT_LE(WorstRelativeError(inside, square, LinearField), 1e-9);
}

// A target reaching past the source: its functions the source does not
// meet are invalid (filled), the others still reproduce a quadratic field.
TEST(NodalSpace, PartlyCovered)
{
  const NodalMesh source = Square(5, 0.2, 24);
  NodalMesh target = Square(4, 0.2, 25);
  for (Index p = 0; p < target.NumberOfPoints(); ++p)
    target.Points[3 * p] += 0.6;
  Built b(target, source);
  ASSERT_TRUE(b.Ok) << b.Op.GetError();
  const std::vector<double> us = AtPoints(source, Quadratic2);
  const std::vector<double> exact = AtPoints(target, Quadratic2);
  std::vector<double> ut(exact.size());
  ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), std::nan("")).Ok);
  Index valid = 0;
  double worst = 0.0;
  for (Index p = 0; p < target.NumberOfPoints(); ++p)
  {
    const double x = target.Point(p)[0];
    if (b.Op.GetValid()[p])
    {
      ++valid;
      worst = std::max(worst, std::fabs(ut[p] - exact[p]));
    }
    else
    {
      EXPECT_TRUE(std::isnan(ut[p]));
      EXPECT_GT(x, 1.0 - 1e-12);
    }
  }
  EXPECT_LT(valid, target.NumberOfPoints());
  EXPECT_GT(valid, target.NumberOfPoints() / 3);
  const auto range = std::minmax_element(exact.begin(), exact.end());
  EXPECT_LE(worst, 1e-9 * (*range.second - *range.first));
}

// The fringe on a second-order target (its supports measured by their
// cells): some functions are aggregated, and a linear field stays exact.
TEST(NodalSpace, Fringe)
{
  const NodalMesh source = Square(5, 0.2, 28);
  NodalMesh target = Square(4, 0.2, 29);
  for (Index p = 0; p < target.NumberOfPoints(); ++p)
    target.Points[3 * p] += 0.63;
  Built b(target, source);
  ASSERT_TRUE(b.Ok) << b.Op.GetError();
  EXPECT_GT(b.Op.AggregateFringe(target.View(), 0.5, mp::SolverHooks()), 0);
  const std::vector<double> us = AtPoints(source, LinearField);
  std::vector<double> ut(size_t(target.NumberOfPoints()));
  const mp::ApplyResult r = b.Op.Apply(us.data(), 1, ut.data(), std::nan(""));
  ASSERT_TRUE(r.Ok);
  ASSERT_TRUE(r.System.Aggregated);
  Index valid = 0;
  for (Index p = 0; p < target.NumberOfPoints(); ++p)
  {
    if ((*r.System.Valid)[p])
    {
      ++valid;
      EXPECT_NEAR(ut[p], LinearField(target.Point(p)), 1e-9);
    }
    // Well inside the source, supports are covered whole: never aggregated
    // (their corner functions' integrals, zero or less, say nothing).
    if (target.Point(p)[0] < 0.85)
    {
      EXPECT_FALSE(b.Op.GetFringe().Aggregated[p]) << p;
    }
  }
  EXPECT_GT(valid, target.NumberOfPoints() / 3);
}

/// The matrices of every pair of cells, dense, by AddByPoints.
template <class I>
void BruteForce(const NodalMesh& target, const NodalMesh& source, std::vector<double>& mts,
  std::vector<double>& mtt)
{
  const mp::MeshView t = target.View(false), s = source.View(false);
  const Index nt = t.NumberOfPoints, ns = s.NumberOfPoints;
  mts.assign(size_t(nt * ns), 0.0);
  mtt.assign(size_t(nt * nt), 0.0);
  mp::NodalFunctions ft, fs;
  for (Index a = 0; a < t.NumberOfCells; ++a)
  {
    typename I::Cell ct;
    ASSERT_TRUE(I::Prepare(t, a, ct));
    ft.Bind(t, mp::SpaceType::P1, a);
    for (Index b = 0; b < s.NumberOfCells; ++b)
    {
      typename I::Cell cs;
      ASSERT_TRUE(I::Prepare(s, b, cs));
      typename I::Piece piece;
      if (!I::Intersect(ct, cs, piece) || !(I::Measure(piece) > 0.0))
        continue;
      fs.Bind(s, mp::SpaceType::P1, b);
      std::vector<double> bts(size_t(ft.Count * fs.Count), 0.0),
        btt(size_t(ft.Count * ft.Count), 0.0);
      // (Every function at every point: the reference for InTargetBasis too.)
      mp::AddByPoints<I>(piece, ct, ft, s, fs, bts.data(), btt.data(), nullptr, nullptr);
      for (int i = 0; i < ft.Count; ++i)
      {
        for (int j = 0; j < fs.Count; ++j)
          mts[ft.Dofs[i] * ns + fs.Dofs[j]] += bts[i * fs.Count + j];
        for (int k = 0; k < ft.Count; ++k)
          mtt[ft.Dofs[i] * nt + ft.Dofs[k]] += btt[i * ft.Count + k];
      }
    }
  }
}

template <class I>
void ExpectBruteForce(const NodalMesh& target, const NodalMesh& source)
{
  Built b(target, source);
  ASSERT_TRUE(b.Ok) << b.Op.GetError();
  std::vector<double> mts, mtt;
  BruteForce<I>(target, source, mts, mtt);
  const Index nt = target.NumberOfPoints(), ns = source.NumberOfPoints();
  const double scale = *std::max_element(mtt.begin(), mtt.end());
  double worst = 0.0;
  for (Index i = 0; i < nt; ++i)
  {
    ASSERT_TRUE(b.Op.GetValid()[i]);
    for (Index j = 0; j < ns; ++j)
      worst = std::max(worst, std::fabs(b.Op.GetMixedMass().Entry(i, j) - mts[i * ns + j]));
    for (Index k = 0; k < nt; ++k)
      worst = std::max(worst, std::fabs(b.Op.GetTargetMass().Entry(i, k) - mtt[i * nt + k]));
  }
  EXPECT_LE(worst, 1e-13 * scale);
  EXPECT_GT(scale, 0.0);
}

// (d) The matrices from the front are those of every pair of cells.
TEST(NodalSpace, MatricesAsBruteForce)
{
  ExpectBruteForce<mp::TriangleIntersector>(Square(3, 0.2, 9), Square(4, 0.2, 10));
  ExpectBruteForce<mp::TriangleIntersector>(Disk(3), Disk(4));
  ExpectBruteForce<mp::TetrahedronIntersector>(Cube(1, 0.0, 0), Cube(2, 0.15, 11));
}

// Cell data to point data and back: a constant stays constant.
TEST(NodalSpace, CellAndPointTransfers)
{
  const NodalMesh source = Square(4, 0.2, 12);
  const NodalMesh target = Square(5, 0.2, 13);
  {
    Built b(target, source, mp::SpaceType::P1, mp::SpaceType::P0);
    ASSERT_TRUE(b.Ok) << b.Op.GetError();
    std::vector<double> us(source.Types.size(), 3.5), ut(size_t(target.NumberOfPoints()));
    ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), 0.0).Ok);
    for (double v : ut)
      EXPECT_NEAR(v, 3.5, 1e-11);
  }
  {
    Built b(target, source, mp::SpaceType::P0, mp::SpaceType::P1);
    ASSERT_TRUE(b.Ok) << b.Op.GetError();
    const std::vector<double> us = AtPoints(source, Quadratic2);
    std::vector<double> ut(target.Types.size());
    ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), 0.0).Ok);
    // Each target cell's value is the source field's mean over it.
    const mp::MeshView view = target.View(false);
    std::vector<double> mean(ut.size(), 0.0), measure(ut.size(), 0.0);
    const mp::SimplexRule& rule = mp::SimplexQuadrature(2, 2);
    for (Index c = 0; c < view.NumberOfCells; ++c)
    {
      const double m = mp::SimplexMeasure(view, c);
      measure[view.ParentOf(c)] += m;
      for (int q = 0; q < rule.Points; ++q)
      {
        double x[2] = { 0, 0 };
        for (int k = 0; k < 3; ++k)
          for (int a = 0; a < 2; ++a)
            x[a] += rule.Barycentric[q * 3 + k] * view.Point(view.Cell(c)[k])[a];
        mean[view.ParentOf(c)] += rule.Weight[q] * m * Quadratic2(x);
      }
    }
    for (size_t p = 0; p < ut.size(); ++p)
      EXPECT_NEAR(ut[p], mean[p] / measure[p], 1e-11);
  }
}

/// The largest difference of two matrices' entries (on a's pattern, which must be b's).
double MatrixDifference(const mp::CsrMatrix& a, const mp::CsrMatrix& b)
{
  EXPECT_EQ(a.RowStart, b.RowStart);
  EXPECT_EQ(a.ColumnIndex, b.ColumnIndex);
  double worst = 0.0;
  for (size_t p = 0; p < a.Values.size() && p < b.Values.size(); ++p)
    worst = std::max(worst, std::fabs(a.Values[p] - b.Values[p]));
  return worst;
}

// Tasks, a search shared with a linear-path operator, and the one-off
// fields give the matrices and values of a plain build.
TEST(NodalSpace, TasksSharedSearchAndFields)
{
  const NodalMesh source = Square(6, 0.2, 14);
  const NodalMesh target = Square(7, 0.2, 15);
  const mp::MeshView t = target.View(), s = source.View();
  const std::vector<double> us = AtPoints(source, Quadratic2);
  Built plain(target, source);
  ASSERT_TRUE(plain.Ok);
  std::vector<double> expected(size_t(target.NumberOfPoints()));
  ASSERT_TRUE(plain.Op.Apply(us.data(), 1, expected.data(), 0.0).Ok);
  const double scale = *std::max_element(
    plain.Op.GetTargetMass().Values.begin(), plain.Op.GetTargetMass().Values.end());
  {
    mp::BoxGridLocator locator(s);
    mp::OperatorOptions options;
    options.Runner = mptest::ThreadRunner(4);
    mp::MortarOperator op;
    ASSERT_TRUE(op.Build(t, s, &locator, options)) << op.GetError();
    EXPECT_LE(MatrixDifference(op.GetMixedMass(), plain.Op.GetMixedMass()), 1e-14 * scale);
    EXPECT_LE(MatrixDifference(op.GetTargetMass(), plain.Op.GetTargetMass()), 1e-14 * scale);
  }
  {
    mp::BoxGridLocator locator(s);
    mp::OperatorOptions points, cells;
    cells.TargetSpace = cells.SourceSpace = mp::SpaceType::P0;
    mp::MortarOperator a, b, alone;
    ASSERT_TRUE(mp::MortarOperator::BuildTogether({ &a, &b }, { points, cells }, t, s, &locator));
    EXPECT_EQ(MatrixDifference(a.GetMixedMass(), plain.Op.GetMixedMass()), 0.0);
    EXPECT_EQ(MatrixDifference(a.GetTargetMass(), plain.Op.GetTargetMass()), 0.0);
    ASSERT_TRUE(alone.Build(t, s, &locator, cells));
    EXPECT_EQ(MatrixDifference(b.GetMixedMass(), alone.GetMixedMass()), 0.0);
    EXPECT_EQ(MatrixDifference(b.GetTargetMass(), alone.GetTargetMass()), 0.0);
  }
  {
    mp::BoxGridLocator locator(s);
    mp::OperatorOptions options;
    options.Fields = us.data();
    options.FieldComponents = 1;
    mp::MortarOperator op;
    ASSERT_TRUE(op.Build(t, s, &locator, options)) << op.GetError();
    EXPECT_FALSE(op.HasMixedMass());
    std::vector<double> ut(expected.size());
    ASSERT_TRUE(op.Apply(us.data(), 1, ut.data(), 0.0).Ok);
    // (The right-hand sides summed during the search, in another order
    // than M_ts's product: the same up to round-off, as on linear cells.)
    for (size_t k = 0; k < ut.size(); ++k)
    {
      ASSERT_NEAR(ut[k], expected[k], 1e-12) << "entry " << k;
    }
  }
}

/// In the tilted plane's coordinates: a quadratic and a linear field.
double TiltedQuadratic(const double* x)
{
  const double u = (x[0] - 0.3) * 0.6 + (x[2] - 0.5) * 0.8, v = x[1] + 0.2;
  const double p[2] = { u, v };
  return Quadratic2(p);
}

// Surfaces in 3D: a quadratic field on straight tri6 facets of a tilted
// plane, and a linear one on curved disks in it.
TEST(NodalSpace, Surfaces)
{
  EXPECT_LE(
    WorstRelativeError(Tilted(Square(5, 0.2, 16)), Tilted(Square(4, 0.2, 17)), TiltedQuadratic),
    1e-9);
  EXPECT_LE(WorstRelativeError(Tilted(Disk(4)), Tilted(Disk(5)),
              [](const double* x) { return 0.5 - 2.0 * x[0] + 3.0 * x[1] + x[2]; }),
    1e-9);
  ExpectBruteForce<mp::SurfaceIntersector>(Tilted(Square(2, 0.2, 18)), Tilted(Square(3, 0.2, 19)));
}

// Curves: a quadratic field along a line of edge3 cells.
TEST(NodalSpace, Curves)
{
  const auto alongLine = [](const double* x) {
    const double s = 0.6 * (x[0] - 0.1) + 0.8 * (x[1] - 0.2);
    return 1.0 - 2.0 * s + 5.0 * s * s;
  };
  EXPECT_LE(WorstRelativeError(Line(7, 20), Line(5, 21), alongLine), 1e-9);
  ExpectBruteForce<mp::SegmentIntersector>(Line(3, 22), Line(4, 23));
}

// Reconstructed cell data (DP1, linear on each source simplex) onto a
// second-order target: a linear field stays exact, and the functions'
// covered integrals add up to the covered measure.
TEST(NodalSpace, ReconstructedCellData)
{
  const NodalMesh source = Square(4, 0.2, 26);
  const NodalMesh target = Square(5, 0.2, 27);
  Built b(target, source, mp::SpaceType::P1, mp::SpaceType::DP1);
  ASSERT_TRUE(b.Ok) << b.Op.GetError();
  const mp::MeshView s = source.View(false);
  std::vector<double> us(size_t(s.NumberOfCells * 3));
  for (Index c = 0; c < s.NumberOfCells; ++c)
    for (int k = 0; k < 3; ++k)
      us[3 * c + k] = LinearField(s.Point(s.Cell(c)[k]));
  std::vector<double> ut(size_t(target.NumberOfPoints()));
  ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), std::nan("")).Ok);
  for (Index p = 0; p < target.NumberOfPoints(); ++p)
    EXPECT_NEAR(ut[p], LinearField(target.Point(p)), 1e-11);
  double sum = 0.0;
  for (double v : b.Op.GetSourceFunctionCovered())
    sum += v;
  EXPECT_NEAR(sum, b.Op.GetCoveredMeasure(), 1e-13);
  EXPECT_NEAR(b.Op.GetCoveredMeasure(), 1.0, 1e-13);
}

// Bounds (clip and assured sum) on a second-order target: a step field
// stays within [0, 1] at every node and keeps its integral.
TEST(NodalSpace, Bounds)
{
  const NodalMesh source = Square(6, 0.2, 30);
  const NodalMesh target = Square(5, 0.2, 31);
  Built b(target, source);
  ASSERT_TRUE(b.Ok) << b.Op.GetError();
  const std::vector<double> us =
    AtPoints(source, [](const double* x) { return x[0] + 0.3 * x[1] > 0.5 ? 1.0 : 0.0; });
  std::vector<double> ut(size_t(target.NumberOfPoints()));
  mp::ApplyOptions options;
  ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), 0.0, options).Ok);
  EXPECT_LT(*std::min_element(ut.begin(), ut.end()), -0.1); // the unbounded one overshoots
  options.Bounded = true;
  ASSERT_TRUE(b.Op.Apply(us.data(), 1, ut.data(), 0.0, options).Ok);
  double integral = 0.0;
  for (size_t i = 0; i < ut.size(); ++i)
  {
    EXPECT_GE(ut[i], 0.0);
    EXPECT_LE(ut[i], 1.0);
    integral += b.Op.GetCoveredIntegrals()[i] * ut[i];
  }
  EXPECT_NEAR(integral, NodalIntegral(source, us), 1e-12);
}

// Traces: a tri6 surface inside a tet10 cube, an edge3 curve inside a tri6
// square and one along edges of a tet10 cube's split (where the cells
// around each edge all claim the piece) take the volume's quadratic field.
TEST(NodalSpace, Traces)
{
  const NodalMesh cube = Cube(2, 0.15, 32);
  EXPECT_LE(WorstRelativeError(InsideCube(Square(3, 0.2, 33)), cube, Quadratic3), 1e-9);
  const NodalMesh square = Square(4, 0.2, 34);
  EXPECT_LE(WorstRelativeError(Line(5, 35), square, Quadratic2), 1e-9);
  // Along the line y = z = 0.5 of a straight cube's split: on its edges.
  const NodalMesh straight = Cube(2, 0.0, 0);
  NodalMesh along = Line(3, 36, { 0.0, 0.5 }, { 1.0, 0.5 }, 0.0);
  for (Index p = 0; p < along.NumberOfPoints(); ++p)
    along.Points[3 * p + 2] = 0.5;
  along.Space = 3;
  along.Finish();
  EXPECT_LE(WorstRelativeError(along, straight, Quadratic3), 1e-9);
  Built b(along, straight);
  ASSERT_TRUE(b.Ok);
  EXPECT_NEAR(b.Op.GetCoveredMeasure(), 1.0, 1e-13); // each tied piece once
  EXPECT_EQ(b.Op.GetNumberOfOvercoveredCells(), 0);
}

// A second-order cell naming a node that does not exist is named.
TEST(NodalSpace, BadNodeNamed)
{
  NodalMesh mesh = Square(2, 0.0, 0);
  mesh.Nodes[6 * 3 + 4] = mesh.NumberOfPoints() + 5;
  Built b(mesh, Square(2, 0.0, 0));
  EXPECT_FALSE(b.Ok);
  EXPECT_NE(b.Op.GetError().find("second-order cell 3"), std::string::npos) << b.Op.GetError();
}
} // namespace

// A failed inverse map is counted, never used silently: on curved disks
// every quadrature point converges; on a tri6 whose mid node 4 is pulled
// across its cell (the map folds), the points of its middle simplex where
// Newton fails are counted and their functions taken at a defined point
// (finite, summing to 1), and every other point's functions give back the
// point itself (x = sum N_n X_n: a true preimage).
TEST(NodalSpace, FailedInversesCounted)
{
  Built disks(Disk(5), Disk(4));
  ASSERT_TRUE(disks.Ok) << disks.Op.GetError();
  EXPECT_EQ(disks.Op.GetNumberOfUnconvergedTargetPoints(), 0);
  EXPECT_EQ(disks.Op.GetNumberOfUnconvergedSourcePoints(), 0);

  NodalMesh folded;
  folded.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, 0, 0, -0.2, -0.2, 0, 0, 0.5, 0 };
  folded.Triangle6({ 0, 1, 2, 3, 4, 5 });
  folded.Finish();
  const mp::MeshView view = folded.View();
  mp::NodalFunctions f;
  int failed = 0;
  int points = 0;
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    f.Bind(view, mp::SpaceType::P1, c);
    const mp::CellCorners corners = view.Cell(c);
    for (int i = 0; i <= 8; ++i)
    {
      for (int j = 0; i + j <= 8; ++j)
      {
        const double b[3] = { (i + 0.5) / 9.5, (j + 0.5) / 9.5, (8.5 - i - j) / 9.5 };
        double x[3] = { 0.0, 0.0, 0.0 };
        for (int k = 0; k < 3; ++k)
        {
          for (int a = 0; a < 2; ++a)
          {
            x[a] += b[k] * view.Point(corners[k])[a];
          }
        }
        const Index before = f.Unconverged;
        double N[mp::MaxNodalFunctions];
        f.Values(x, N);
        ++points;
        double sum = 0.0, y[2] = { 0.0, 0.0 };
        for (int n = 0; n < f.Count; ++n)
        {
          ASSERT_TRUE(std::isfinite(N[n]));
          sum += N[n];
          for (int a = 0; a < 2; ++a)
          {
            y[a] += N[n] * view.Point(f.Dofs[n])[a];
          }
        }
        EXPECT_NEAR(sum, 1.0, 1e-12);
        if (f.Unconverged == before)
        {
          EXPECT_NEAR(y[0], x[0], 1e-12);
          EXPECT_NEAR(y[1], x[1], 1e-12);
        }
        failed += static_cast<int>(f.Unconverged - before);
      }
    }
  }
  EXPECT_EQ(f.Unconverged, failed);
  EXPECT_GT(failed, 0);
  std::printf("folded tri6: %d of %d points without an inverse\n", failed, points);
}
