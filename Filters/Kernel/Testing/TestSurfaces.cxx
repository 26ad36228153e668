// SPDX-License-Identifier: BSD-3-Clause
// Surfaces in 3D: two facetizations of one surface (SurfaceIntersector.h).
#include "Geometry/SurfaceIntersector.h"
#include "GeneratedMeshes.h"
#include "ReachProjection.h"
#include "SearchComparison.h"
#include "Transfer/MortarOperator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using mp::Index;
using mp::SurfaceIntersector;
using mptest::TestMesh;

namespace
{
TestMesh Finished(TestMesh m)
{
  m.Finish();
  return m;
}

double Linear3(const double* x)
{
  return 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2];
}

double Area(const TestMesh& m, Index c)
{
  SurfaceIntersector::Cell cell;
  mp::MeshView v = m.View(false);
  return SurfaceIntersector::Prepare(v, c, cell) ? cell.Measure : 0.0;
}

double SmoothOnSphere(const double* x)
{
  return x[0] * x[1] + std::sin(2.0 * x[2]);
}
} // namespace

TEST(Surfaces, GeneratedFacetsFaceOutward)
{
  const std::pair<TestMesh, double> meshes[] = { { mptest::Icosphere(3), 0.0 },
    { mptest::UvSphere(8, 12), 0.0 }, { mptest::CubeSurface(3, 0), 0.5 },
    { mptest::CubeSurface(3, 1), 0.5 } };
  for (const auto& mesh : meshes)
  {
    const TestMesh& m = mesh.first;
    SurfaceIntersector::Cell cell;
    for (Index c = 0; c < m.NumberOfCells(); ++c)
    {
      ASSERT_TRUE(SurfaceIntersector::Prepare(m.View(false), c, cell));
      double centre[3];
      SurfaceIntersector::Center(cell, centre);
      double outward = 0.0;
      for (int d = 0; d < 3; ++d)
      {
        outward += cell.Normal[d] * (centre[d] - mesh.second);
      }
      ASSERT_GT(outward, 0.0) << "cell " << c << " of a mesh of " << m.NumberOfCells();
    }
  }
}

TEST(Surfaces, SphereFrontEqualsBruteForceAndPiecesTileTheTarget)
{
  const TestMesh target = Finished(mptest::Icosphere(6));     // 720 triangles
  const TestMesh source = Finished(mptest::UvSphere(14, 22)); // 572 triangles
  mptest::SearchComparison<SurfaceIntersector> search(target, source);
  search.ExpectSamePairs("sphere");
  EXPECT_GT(search.Front.Pairs.size(), target.NumberOfCells());
  EXPECT_EQ(search.FrontStats.FullLocatorQueries, 0); // one closed surface: a walk and the front

  mptest::ReachProjection p(target, source);
  ASSERT_TRUE(p.Ok) << p.Op.GetError();
  const auto covered = p.Covered();
  ASSERT_EQ(static_cast<Index>(covered.size()), target.NumberOfCells());
  for (const auto& c : covered)
  {
    // The images of the source facets tile every target facet exactly.
    EXPECT_NEAR(c.second, Area(target, c.first), 1e-12 * Area(target, c.first)) << c.first;
  }
  EXPECT_EQ(p.Op.GetNumberOfValid(), target.NumberOfPoints());
  EXPECT_EQ(p.Op.GetNumberOfOvercoveredCells(), 0);
}

TEST(Surfaces, CubeSurfaceLinearFieldsAreExactAcrossItsSharpEdges)
{
  // Different grids and diagonals on each face; the edges and corners of
  // the cube are shared by both meshes' facets, as a mesh generator keeps them.
  const TestMesh target = Finished(mptest::CubeSurface(5, 0));
  const TestMesh source = Finished(mptest::CubeSurface(7, 1));
  mptest::SearchComparison<SurfaceIntersector> search(target, source);
  search.ExpectSamePairs("cube");
  mptest::ReachProjection p(target, source);
  ASSERT_TRUE(p.Ok) << p.Op.GetError();
  for (const auto& c : p.Covered())
  {
    EXPECT_NEAR(c.second, Area(target, c.first), 1e-13) << c.first;
  }
  const auto ut = p.Apply(mptest::SampleAtPoints(source, Linear3));
  EXPECT_LT(mptest::MaxPointError(target, ut, Linear3), 1e-12);
  // Pieces only between facets of the same face: the normals' angle at the
  // edges is 90 degrees.
  const auto& pieces = p.Op.GetPieces();
  for (Index i = 0; i < pieces.Size(); ++i)
  {
    SurfaceIntersector::Cell t, s;
    SurfaceIntersector::Prepare(target.View(false), pieces.TargetCell[i], t);
    SurfaceIntersector::Prepare(source.View(false), pieces.SourceCell[i], s);
    const double dot =
      t.Normal[0] * s.Normal[0] + t.Normal[1] * s.Normal[1] + t.Normal[2] * s.Normal[2];
    ASSERT_GT(dot, 0.999999) << i;
  }
}

TEST(Surfaces, SphereConvergesAtSecondOrder)
{
  // The source facets lie above and below the target's: the error comes
  // from the source interpolation and from that distance, both O(h^2).
  double previousRms = 0.0;
  double previousMax = 0.0;
  for (int level = 0; level < 4; ++level)
  {
    const int k = 1 << level;
    const TestMesh target = Finished(mptest::Icosphere(3 * k));
    const TestMesh source = Finished(mptest::UvSphere(10 * k, 16 * k));
    mptest::ReachProjection p(target, source);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ASSERT_EQ(p.Op.GetNumberOfValid(), target.NumberOfPoints());
    const auto ut = p.Apply(mptest::SampleAtPoints(source, SmoothOnSphere));
    double sum = 0.0;
    for (Index q = 0; q < target.NumberOfPoints(); ++q)
    {
      const double e = ut[q] - SmoothOnSphere(&target.Points[3 * q]);
      sum += e * e;
    }
    const double rms = std::sqrt(sum / target.NumberOfPoints());
    const double max = mptest::MaxPointError(target, ut, SmoothOnSphere);
    if (level > 0)
    {
      EXPECT_GT(std::log2(previousRms / rms), 1.8)
        << "level " << level << ": rms " << previousRms << " -> " << rms;
    }
    if (level == 3)
    {
      // The largest error reaches its rate on finer meshes (1.5, 1.7, 2.1 here).
      EXPECT_GT(std::log2(previousMax / max), 1.8) << "max " << previousMax << " -> " << max;
    }
    previousRms = rms;
    previousMax = max;
  }
}

TEST(Surfaces, ConservationOnTheCoveredTarget)
{
  const TestMesh target = Finished(mptest::Icosphere(5));
  const TestMesh source = Finished(mptest::UvSphere(12, 20));
  mptest::ReachProjection p(target, source);
  ASSERT_TRUE(p.Ok);
  const auto us = mptest::SampleAtPoints(source, SmoothOnSphere);
  const auto ut = p.Apply(us);
  // int u_t over the covered target = int of the projected source field.
  const auto integrals = p.Integrals(us, ut);
  EXPECT_NEAR(integrals.first, integrals.second, 1e-12 * std::fabs(integrals.second) + 1e-14);
}

TEST(Surfaces, NothingCrossesAThinShell)
{
  // A closed shell of thickness 0.02: outer sphere facing out, inner facing
  // in. The source carries +1 outside and -1 inside.
  TestMesh source = mptest::UvSphere(16, 24, 1.0);
  const Index outerPoints = source.NumberOfPoints();
  mptest::AppendMesh(source, mptest::Icosphere(5, 0.98, true));
  source.Finish();
  TestMesh target = mptest::Icosphere(7, 1.0);
  const Index targetOuter = target.NumberOfPoints();
  mptest::AppendMesh(target, mptest::UvSphere(14, 20, 0.98));
  // The inner target sphere must face inward too: reverse its cells.
  for (size_t c = 3 * static_cast<size_t>(mptest::Icosphere(7).NumberOfCells());
       c < target.Cells.size(); c += 3)
  {
    std::swap(target.Cells[c + 1], target.Cells[c + 2]);
  }
  target.Finish();
  std::vector<double> us(static_cast<size_t>(source.NumberOfPoints()));
  for (Index q = 0; q < source.NumberOfPoints(); ++q)
  {
    us[q] = q < outerPoints ? 1.0 : -1.0;
  }
  // The reach (0.5 of a facet's edge, about 0.1) spans the gap: only the
  // normals keep the sides apart.
  mptest::SearchComparison<SurfaceIntersector> search(target, source);
  search.ExpectSamePairs("shell");
  mptest::ReachProjection p(target, source);
  ASSERT_TRUE(p.Ok) << p.Op.GetError();
  const auto ut = p.Apply(us);
  for (Index q = 0; q < target.NumberOfPoints(); ++q)
  {
    ASSERT_NEAR(ut[q], q < targetOuter ? 1.0 : -1.0, 1e-12) << q;
  }
  // Only the facets' orientation keeps the sides apart (the reach spans
  // the gap): with the inner source sphere facing out, the outer target
  // side takes its values too (a source overlapping itself, which only the
  // brute force takes apart: the front finds one layer).
  TestMesh wrong = mptest::UvSphere(16, 24, 1.0);
  mptest::AppendMesh(wrong, mptest::Icosphere(5, 0.98, false));
  wrong.Finish();
  mptest::ReachProjection mixed(target, wrong, 0.5, 0.7071, mp::SearchMethod::BruteForce);
  EXPECT_GT(mixed.Op.GetNumberOfOvercoveredCells(), 0);
  ASSERT_TRUE(mixed.Ok);
  const auto um = mixed.Apply(us);
  double worst = 0.0;
  for (Index q = 0; q < targetOuter; ++q)
  {
    worst = std::max(worst, std::fabs(um[q] - 1.0));
  }
  EXPECT_GT(worst, 0.1);
}

TEST(Surfaces, GapBetweenTwoPatchesWithinAndBeyondReach)
{
  // Two flat patches 0.01 apart, with cells about 0.1 wide.
  TestMesh target = mptest::GridMesh(10, 10, 0.2, 7);
  target.Surface = true;
  TestMesh source = mptest::GridMesh(13, 9, 0.2, 8);
  source.Surface = true;
  for (Index q = 0; q < source.NumberOfPoints(); ++q)
  {
    source.Points[3 * q + 2] = 0.01;
  }
  target.Finish();
  source.Finish();
  // Within reach: a linear field's values at the source heights are exact.
  mptest::ReachProjection near(target, source, 0.5);
  ASSERT_TRUE(near.Ok);
  auto ut = near.Apply(mptest::SampleAtPoints(source, Linear3));
  for (Index q = 0; q < target.NumberOfPoints(); ++q)
  {
    double x[3] = { target.Points[3 * q], target.Points[3 * q + 1], 0.01 };
    ASSERT_NEAR(ut[q], Linear3(x), 1e-12) << q;
  }
  // Beyond reach (0.05 of about 0.1 = 0.005 < 0.01): nothing meets.
  mptest::ReachProjection far(target, source, 0.05);
  ASSERT_TRUE(far.Ok);
  EXPECT_EQ(far.Op.GetNumberOfValid(), 0);
  EXPECT_EQ(far.Op.GetPieces().Size(), 0);
  mptest::SearchComparison<SurfaceIntersector> search(target, source);
  search.ExpectSamePairs("gap");
}

TEST(Surfaces, VolumeAndSurfaceMeshesAreNotMatched)
{
  TestMesh a = Finished(mptest::GridMesh(4, 4, 0.0, 1));
  TestMesh b = mptest::GridMesh(4, 4, 0.0, 1);
  b.Surface = true;
  b.Finish();
  mp::MortarOperator op;
  mp::BoxGridLocator locator(b.View());
  EXPECT_FALSE(op.Build(a.View(), b.View(), &locator));
  EXPECT_NE(op.GetError().find("different spaces"), std::string::npos) << op.GetError();
}

TEST(Surfaces, ASteepStepDoesNotStopTheFront)
{
  // The source: z = 0 left of x = 0.5, z = 0.2 right of x = 0.55, the
  // facets in between at 76 degrees (screened out by the 45 degree limit).
  // Coarse target facets at z = 0.1 straddle the step: the source facets
  // meeting them on both sides are connected only through the step, so
  // the front must ask the locator there.
  TestMesh source = mptest::GridMesh(20, 20, 0.0, 3);
  source.Surface = true;
  for (Index q = 0; q < source.NumberOfPoints(); ++q)
  {
    source.Points[3 * q + 2] = source.Points[3 * q] > 0.5 + 1e-9 ? 0.2 : 0.0;
  }
  source.Finish();
  TestMesh target = mptest::GridMesh(3, 3, 0.1, 4);
  target.Surface = true;
  for (Index q = 0; q < target.NumberOfPoints(); ++q)
  {
    target.Points[3 * q + 2] = 0.1;
  }
  target.Finish();
  mptest::SearchComparison<SurfaceIntersector> search(target, source);
  search.ExpectSamePairs("step");
  EXPECT_GT(search.FrontStats.FullLocatorQueries, 0);
  // Both sides are found: the pieces cover all but the step's images.
  double covered = 0.0;
  for (const auto& p : search.Front.Pairs)
  {
    covered += std::get<2>(p);
  }
  EXPECT_NEAR(covered, 0.95, 1e-12);
}

TEST(Surfaces, FacingSurfacesMeetWithTheOppositeOrientation)
{
  // Two bodies' boundaries facing each other (contact, fluid-structure
  // coupling): the source sphere's facets face inward.
  const TestMesh target = Finished(mptest::Icosphere(6));
  TestMesh inward = mptest::UvSphere(14, 22);
  for (size_t c = 0; c < inward.Cells.size(); c += 3)
  {
    std::swap(inward.Cells[c + 1], inward.Cells[c + 2]);
  }
  inward.Finish();
  const auto us = mptest::SampleAtPoints(inward, SmoothOnSphere);
  std::vector<double> reference;
  {
    // The same facets facing out, with the default orientation.
    const TestMesh outward = Finished(mptest::UvSphere(14, 22));
    mptest::ReachProjection p(target, outward);
    reference = p.Apply(us);
  }
  for (int orientation = 0; orientation < 3; ++orientation)
  {
    mp::MeshView t = target.View();
    t.SurfaceOrientation = orientation;
    for (const auto method : { mp::SearchMethod::AdvancingFront, mp::SearchMethod::BruteForce })
    {
      mp::BoxGridLocator locator(inward.View());
      mp::OperatorOptions options;
      options.Method = method;
      mp::MortarOperator op;
      ASSERT_TRUE(op.Build(t, inward.View(), &locator, options)) << op.GetError();
      if (orientation == 0)
      {
        EXPECT_EQ(op.GetNumberOfValid(), 0); // facing away: nothing meets
        continue;
      }
      ASSERT_EQ(op.GetNumberOfValid(), target.NumberOfPoints());
      std::vector<double> ut(us.size() > 0 ? target.NumberOfPoints() : 0);
      op.Apply(us.data(), 1, ut.data(), std::nan(""));
      for (Index q = 0; q < target.NumberOfPoints(); ++q)
      {
        ASSERT_NEAR(ut[q], reference[q], 1e-12) << orientation << " " << q;
      }
    }
  }
}

TEST(Surfaces, MisorientedEdgesAreCounted)
{
  TestMesh m = Finished(mptest::Icosphere(4));
  EXPECT_EQ(mp::MisorientedEdges(m.View()), 0);
  std::swap(m.Cells[1], m.Cells[2]); // one triangle turned over: its three edges
  m.Finish();
  EXPECT_EQ(mp::MisorientedEdges(m.View()), 3);
  TestMesh flat = Finished(mptest::CubeSurface(3, 1));
  EXPECT_EQ(mp::MisorientedEdges(flat.View()), 0);
}
