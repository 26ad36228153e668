// SPDX-License-Identifier: BSD-3-Clause
// Traces: a surface or a curve inside a volume mesh (TraceIntersector.h).
#include "Geometry/TraceIntersector.h"
#include "GeneratedMeshes.h"
#include "ReachProjection.h"
#include "SearchComparison.h"
#include "Transfer/MortarOperator.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <string>

using mp::Index;
using mptest::TestMesh;
using SurfaceTrace = mp::SurfaceTraceIntersector;
using CurveTrace2 = mp::CurveTraceIntersector<mp::TriangleIntersector>;
using CurveTrace3 = mp::CurveTraceIntersector<mp::TetrahedronIntersector>;

namespace
{
const double Pi = 3.14159265358979323846;

double Linear(const double* x)
{
  return 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2];
}

/// A jittered grid of triangles over [0, 1]^2 carried into space by `to`
/// (x, y) -> point; `flip` reverses every triangle (the normals).
TestMesh Sheet(int nx, int ny, double jitter, unsigned seed,
  const std::function<void(double, double, double*)>& to, bool flip = false)
{
  TestMesh m = mptest::GridMesh(nx, ny, jitter, seed);
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    double* x = &m.Points[3 * p];
    double y[3];
    to(x[0], x[1], y);
    std::copy(y, y + 3, x);
  }
  if (flip)
  {
    for (Index c = 0; c < m.NumberOfCells(); ++c)
    {
      std::swap(m.Cells[3 * c + 1], m.Cells[3 * c + 2]);
    }
  }
  m.Surface = true;
  m.Finish();
  return m;
}

/// The measure of every target cell (area of a facet, length of a segment).
template <class Intersector>
std::vector<double> Measures(const TestMesh& m)
{
  std::vector<double> measure(static_cast<size_t>(m.NumberOfCells()), 0.0);
  typename Intersector::Cell cell;
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    if (Intersector::Prepare(m.View(false), c, cell))
    {
      measure[c] = cell.Measure;
    }
  }
  return measure;
}

/**
 * The checks every trace passes: front == brute force (same pairs, same
 * pieces), the pieces of each target cell add up to the cell once (or to
 * `inside` of the whole when the target leaves the volume), linear fields
 * exact at the valid points, and the integral conserved.
 */
template <class Intersector>
void CheckTrace(
  const TestMesh& target, const TestMesh& source, const std::string& what, bool whole = true)
{
  mptest::SearchComparison<Intersector> search(target, source);
  search.ExpectSamePairs(what, 1e-14); // the targets' cells are 0.01 to 0.3 long or wide
  const std::vector<double> measure = Measures<Intersector>(target);
  double total = 0.0;
  for (double m : measure)
  {
    total += m;
  }
  for (const auto method : { mp::SearchMethod::AdvancingFront, mp::SearchMethod::BruteForce })
  {
    mptest::ReachProjection p(target, source, 0.5, 0.7071, method);
    ASSERT_TRUE(p.Ok) << what << ": " << p.Op.GetError();
    // The pieces the operator keeps (a piece claimed by the cells around an
    // edge once) add up to every target cell once.
    std::map<Index, double> covered = p.Covered();
    for (Index c = 0; c < target.NumberOfCells(); ++c)
    {
      if (whole)
      {
        ASSERT_NEAR(covered[c], measure[c], 1e-12 * measure[c]) << what << ", target cell " << c;
      }
      else
      {
        ASSERT_LE(covered[c], measure[c] * (1 + 1e-12)) << what << ", target cell " << c;
      }
    }
    if (whole)
    {
      EXPECT_NEAR(p.Op.GetCoveredMeasure(), total, 1e-12 * total) << what;
      EXPECT_EQ(p.Op.GetNumberOfValid(), target.NumberOfPoints()) << what;
    }
    EXPECT_EQ(p.Op.GetNumberOfOvercoveredCells(), 0) << what;
    const std::vector<double> us = mptest::SampleAtPoints(source, Linear);
    const std::vector<double> ut = p.Apply(us);
    double worst = 0.0;
    for (Index i = 0; i < target.NumberOfPoints(); ++i)
    {
      // Where the target leaves the volume (the unit cube), away from its
      // boundary: a function barely covered is ill-conditioned.
      const double* x = &target.Points[3 * i];
      const bool inner =
        whole || (std::min({ x[0], x[1], x[2] }) > 0.1 && std::max({ x[0], x[1], x[2] }) < 0.9);
      if (p.Op.GetValid()[i] && inner)
      {
        worst = std::max(worst, std::fabs(ut[i] - Linear(&target.Points[3 * i])));
      }
    }
    EXPECT_LT(worst, 1e-11) << what << ": a linear field is not reproduced";
    std::vector<double> filled(ut);
    for (Index i = 0; i < target.NumberOfPoints(); ++i)
    {
      filled[i] = p.Op.GetValid()[i] ? ut[i] : 0.0;
    }
    const auto integrals = p.Integrals(us, filled);
    EXPECT_NEAR(integrals.first, integrals.second, 1e-12 * std::fabs(integrals.second)) << what;
  }
}

/// Cell values (P0 source) projected onto P0 on the target.
std::vector<double> CellTrace(const TestMesh& target, const TestMesh& source,
  const std::vector<double>& values, std::vector<char>& valid)
{
  mp::MortarOperator op;
  mp::BoxGridLocator locator(source.View());
  mp::OperatorOptions options;
  options.TargetSpace = mp::SpaceType::P0;
  options.SourceSpace = mp::SpaceType::P0;
  EXPECT_TRUE(op.Build(target.View(), source.View(), &locator, options)) << op.GetError();
  std::vector<double> out(static_cast<size_t>(target.NumberOfCells()));
  op.Apply(values.data(), 1, out.data(), std::nan(""));
  valid = op.GetValid();
  return out;
}

/// Every edge of `m` as a segment of a curve on m's own points.
TestMesh EdgesOf(const TestMesh& m)
{
  TestMesh curve;
  curve.Dimension = 1;
  curve.Surface = m.Dimension == 3; // a curve in space; else in the plane
  curve.Points = m.Points;
  std::set<std::pair<Index, Index>> edges;
  const int n = m.Dimension + 1;
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    for (int a = 0; a < n; ++a)
    {
      for (int b = a + 1; b < n; ++b)
      {
        const Index p = m.Cells[n * c + a];
        const Index q = m.Cells[n * c + b];
        edges.insert({ std::min(p, q), std::max(p, q) });
      }
    }
  }
  for (const auto& e : edges)
  {
    curve.Cells.insert(curve.Cells.end(), { e.first, e.second });
  }
  curve.Finish();
  return curve;
}

/// The centroid's z of every tetrahedron: a value telling which side a facet took.
std::vector<double> CentroidHeights(const TestMesh& m)
{
  std::vector<double> z(static_cast<size_t>(m.NumberOfCells()), 0.0);
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    for (int k = 0; k < 4; ++k)
    {
      z[c] += 0.25 * m.Points[3 * m.Cells[4 * c + k] + 2];
    }
  }
  return z;
}
} // namespace

TEST(Traces, TiltedPlaneInTetrahedra)
{
  const TestMesh source = mptest::CubeMesh(6, 5, 7, 0.3, 11);
  const TestMesh target = Sheet(9, 7, 0.3, 12, [](double x, double y, double* p) {
    p[0] = 0.15 + 0.7 * x;
    p[1] = 0.2 + 0.6 * y;
    p[2] = 0.3 + 0.25 * x + 0.3 * y;
  });
  CheckTrace<SurfaceTrace>(target, source, "tilted plane");
}

TEST(Traces, PlanesOnFacesAreCoveredOnceFromTheSideTheNormalsPointTo)
{
  // An unjittered mesh: the planes z = 0, 0.5 and 1 are made of its faces.
  const TestMesh source = mptest::CubeMesh(4, 4, 4, 0.0, 13);
  const std::vector<double> heights = CentroidHeights(source);
  for (const double z : { 0.0, 0.5, 1.0 })
  {
    for (const bool down : { false, true })
    {
      const std::string what = "plane z = " + std::to_string(z) + (down ? ", down" : ", up");
      const TestMesh target = Sheet(
        5, 3, 0.2, 14,
        [z](double x, double y, double* p) {
          p[0] = x;
          p[1] = y;
          p[2] = z;
        },
        down);
      CheckTrace<SurfaceTrace>(target, source, what);
      // Cell data: an inner plane takes the tetrahedra its normals point
      // to; a boundary plane, the ones there are.
      std::vector<char> valid;
      const std::vector<double> values = CellTrace(target, source, heights, valid);
      for (Index c = 0; c < target.NumberOfCells(); ++c)
      {
        ASSERT_TRUE(valid[c]) << what;
        const bool above = z == 0.0 || (z == 0.5 && !down);
        ASSERT_TRUE(above ? values[c] > z : values[c] < z)
          << what << ", cell " << c << ": " << values[c];
      }
    }
  }
}

TEST(Traces, SphereInTetrahedra)
{
  const TestMesh source = mptest::CubeMesh(7, 8, 6, 0.3, 15);
  TestMesh target = mptest::Icosphere(4, 0.35);
  for (Index p = 0; p < target.NumberOfPoints(); ++p)
  {
    for (int d = 0; d < 3; ++d)
    {
      target.Points[3 * p + d] += 0.5;
    }
  }
  target.Finish();
  CheckTrace<SurfaceTrace>(target, source, "sphere");
}

TEST(Traces, SurfaceLeavingTheVolumeIsCoveredInside)
{
  const TestMesh source = mptest::CubeMesh(5, 5, 5, 0.3, 16);
  const TestMesh target = Sheet(8, 4, 0.3, 17, [](double x, double y, double* p) {
    p[0] = -0.5 + 2.0 * x; // half of it outside
    p[1] = 0.25 + 0.5 * y;
    p[2] = 0.41;
  });
  CheckTrace<SurfaceTrace>(target, source, "leaving", false);
  mptest::ReachProjection p(target, source);
  ASSERT_TRUE(p.Ok);
  EXPECT_NEAR(p.Op.GetCoveredMeasure(), 0.5, 1e-12); // [0, 1] x [0.25, 0.75]
  EXPECT_LT(p.Op.GetNumberOfValid(), target.NumberOfPoints());
}

TEST(Traces, CurvesInTriangles)
{
  const TestMesh source = mptest::GridMesh(10, 9, 0.3, 18);
  const TestMesh circle = mptest::Polyline(
    mptest::Uniform(40, 0, 2 * Pi, 0.3, 19, true),
    [](double s, double* p) {
      p[0] = 0.5 + 0.3 * std::cos(s);
      p[1] = 0.5 + 0.35 * std::sin(s);
    },
    true);
  CheckTrace<CurveTrace2>(circle, source, "circle");
  // Along the lines of an unjittered grid, inside and on the boundary, both ways.
  const TestMesh grid = mptest::GridMesh(4, 4, 0.0, 20);
  for (const auto& line : std::vector<std::array<double, 4>>{
         { 0.5, 0, 0.5, 1 }, { 0.5, 1, 0.5, 0 }, { 0, 0, 1, 0 }, { 1, 0, 0, 0 }, { 0, 0, 1, 1 } })
  {
    const TestMesh target = mptest::Polyline(
      mptest::Uniform(7, 0, 1, 0.3, 21, false),
      [&line](double s, double* p) {
        p[0] = line[0] + s * (line[2] - line[0]);
        p[1] = line[1] + s * (line[3] - line[1]);
      },
      false);
    CheckTrace<CurveTrace2>(target, grid,
      "line (" + std::to_string(line[0]) + ", " + std::to_string(line[1]) + ") to (" +
        std::to_string(line[2]) + ", " + std::to_string(line[3]) + ")");
  }
}

TEST(Traces, CurvesInTetrahedra)
{
  const TestMesh source = mptest::CubeMesh(5, 6, 5, 0.3, 22);
  const TestMesh helix = mptest::Polyline(
    mptest::Uniform(60, 0, 6, 0.3, 23, false),
    [](double s, double* p) {
      p[0] = 0.5 + 0.3 * std::cos(s);
      p[1] = 0.5 + 0.3 * std::sin(s);
      p[2] = 0.1 + 0.13 * s;
    },
    false, 3);
  CheckTrace<CurveTrace3>(helix, source, "helix");
  // Along edges and faces of an unjittered mesh, inside and on the boundary.
  const TestMesh grid = mptest::CubeMesh(3, 3, 3, 0.0, 24);
  const double third = 1.0 / 3.0;
  for (const auto& line :
    std::vector<std::array<double, 6>>{ { 0, third, third, 1, third, third },
      { 1, third, third, 0, third, third }, { 0, 0, 0.5, 1, 0, 0.5 }, { 0, 0, 0, 1, 0, 0 },
      { 0, 1, 1, 1, 1, 1 }, { 1, 1, 0, 0, 1, 0 }, { 0, 0.5, 1, 1, 0.5, 1 }, { 0, 0, 0, 1, 1, 1 } })
  {
    const TestMesh target = mptest::Polyline(
      mptest::Uniform(5, 0, 1, 0.3, 25, false),
      [&line](double s, double* p) {
        for (int d = 0; d < 3; ++d)
        {
          p[d] = line[d] + s * (line[d + 3] - line[d]);
        }
      },
      false, 3);
    std::string what = "line";
    for (double v : line)
    {
      what += " " + std::to_string(v);
    }
    CheckTrace<CurveTrace3>(target, grid, what);
  }
}

TEST(Traces, PlanesThroughVerticesOfTheSource)
{
  // Planes through many vertices and edges of an unjittered mesh: cross-
  // sections with repeated corners (a vertex on the plane).
  const TestMesh source = mptest::CubeMesh(4, 4, 4, 0.0, 26);
  const std::function<void(double, double, double*)> planes[] = { [](
                                                                    double u, double v, double* p) {
                                                                   p[0] = u;
                                                                   p[1] = 0.5 * (1.0 - u);
                                                                   p[2] = v;
                                                                 }, // x + 2y = 1
    [](double u, double v, double* p) {
      p[0] = u;
      p[1] = 1.0 - u;
      p[2] = v;
    },                                  // x + y = 1
    [](double u, double v, double* p) { // x + y + z = 1.5
      p[0] = 0.25 + 0.5 * u;
      p[1] = 0.25 + 0.5 * v;
      p[2] = 1.5 - p[0] - p[1];
    } };
  int k = 0;
  for (const auto& plane : planes)
  {
    CheckTrace<SurfaceTrace>(Sheet(6, 5, 0.2, 27 + k, plane), source, "plane " + std::to_string(k));
    CheckTrace<SurfaceTrace>(
      Sheet(4, 4, 0.0, 30 + k, plane), source, "unjittered plane " + std::to_string(k));
    ++k;
  }
}

TEST(Traces, CurvesAlongEveryEdgeOfTheSource)
{
  // Each edge of the source, inside and on the boundary, as a segment of
  // the target: it lies in the planes of two (2D: one) faces of every cell
  // around it.
  for (const double jitter : { 0.0, 0.25 })
  {
    const TestMesh grid = mptest::GridMesh(5, 4, jitter, 32);
    CheckTrace<CurveTrace2>(
      EdgesOf(grid), grid, "edges of a 2D grid, jitter " + std::to_string(jitter));
    const TestMesh cube = mptest::CubeMesh(3, 3, 3, jitter, 33);
    CheckTrace<CurveTrace3>(
      EdgesOf(cube), cube, "edges of a 3D grid, jitter " + std::to_string(jitter));
  }
}
