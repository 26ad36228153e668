// SPDX-License-Identifier: BSD-3-Clause
// CellGeometry (Geometry/CellGeometry.h): on volume meshes the simplex
// measure is, bit for bit, the intersectors' (Measures.h), and the
// triangles' measure alone (PrepareMeasure) their Prepare's; on surfaces and
// curves it is the area and length in space (against the Gram determinant
// computed here); a
// cell's centroid is the measure-weighted one (the corners' mean of its
// simplices' means for a cell of no measure), its corner mean the mean of
// its simplices' corners.
#include "Geometry/CellGeometry.h"

#include "GeneratedMeshes.h"
#include "Geometry/Measures.h"
#include "Geometry/TriangleIntersector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace
{
using mp::Index;
using mptest::TestMesh;

/// The area of triangle c in space from its Gram determinant, independently.
double GramArea(const mp::MeshView& mesh, Index c)
{
  const mp::CellCorners ids = mesh.Cell(c);
  double e[2][3];
  for (int a = 0; a < 2; ++a)
  {
    for (int i = 0; i < 3; ++i)
    {
      e[a][i] = mesh.Point(ids[a + 1])[i] - mesh.Point(ids[0])[i];
    }
  }
  auto dot = [](const double* u, const double* v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  return 0.5 * std::sqrt(dot(e[0], e[0]) * dot(e[1], e[1]) - dot(e[0], e[1]) * dot(e[0], e[1]));
}
} // namespace

TEST(CellGeometry, VolumeMeasureIsTheIntersectors)
{
  for (const TestMesh& m : { mptest::GridMesh(17, 13, 0.35, 1), mptest::CubeMesh(6, 5, 7, 0.3, 2) })
  {
    const mp::MeshView view = m.View(false);
    std::vector<double> intersectors(static_cast<size_t>(view.NumberOfCells), -1.0);
    mp::ForEachCellMeasure(view, [&](Index c, double measure) { intersectors[c] = measure; });
    for (Index c = 0; c < view.NumberOfCells; ++c)
    {
      const double measure = mp::SimplexMeasure(view, c);
      EXPECT_EQ(measure, intersectors[c]) << "cell " << c;
      EXPECT_NEAR(measure, m.CellArea(c), 1e-15) << "cell " << c;
    }
  }
}

TEST(CellGeometry, TrianglesMeasureAloneIsPreparesBitForBit)
{
  // Clockwise cells (every third one reversed), and cells of no area: two
  // corners on one point, three on a line.
  TestMesh m = mptest::GridMesh(17, 13, 0.35, 1);
  for (Index c = 0; c < m.NumberOfCells(); c += 3)
  {
    std::swap(m.Cells[3 * c + 1], m.Cells[3 * c + 2]);
  }
  m.Cells[3 * 5 + 2] = m.Cells[3 * 5];
  const Index p = m.NumberOfPoints();
  m.Points.insert(m.Points.end(), { 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 3.0, 3.0, 0.0 });
  m.Cells.insert(m.Cells.end(), { p, p + 1, p + 2 });
  const mp::MeshView view = m.View(false);
  int invalid = 0;
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    mp::TriangleIntersector::Cell cell;
    double measure = -1.0;
    const bool prepared = mp::TriangleIntersector::Prepare(view, c, cell);
    ASSERT_EQ(mp::TriangleIntersector::PrepareMeasure(view, c, measure), prepared) << "cell " << c;
    invalid += !prepared;
    if (prepared)
    {
      EXPECT_EQ(measure, cell.Measure) << "cell " << c;
    }
  }
  EXPECT_EQ(invalid, 2);
}

TEST(CellGeometry, SurfaceAndCurveMeasuresAreInSpace)
{
  TestMesh sphere = mptest::Icosphere(2);
  const mp::MeshView view = sphere.View(false);
  ASSERT_EQ(view.SpaceDimension, 3);
  double total = 0.0;
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    const double area = mp::SimplexMeasure(view, c);
    EXPECT_NEAR(area, GramArea(view, c), 1e-14 * area) << "cell " << c;
    total += area;
  }
  EXPECT_GT(total, 0.9 * 4.0 * M_PI); // an inscribed polyhedron: a little less than the sphere
  EXPECT_LT(total, 4.0 * M_PI);
  // A segment in space: its length.
  TestMesh curve;
  curve.Dimension = 1;
  curve.Surface = true;
  curve.Points = { 1.0, 2.0, 3.0, 4.0, 6.0, 15.0 };
  curve.Cells = { 0, 1 };
  EXPECT_DOUBLE_EQ(mp::SimplexMeasure(curve.View(false), 0), 13.0);
  // A degenerate triangle in space: 0, not NaN.
  TestMesh flat;
  flat.Surface = true;
  flat.Points = { 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0 };
  flat.Cells = { 0, 1, 2 };
  EXPECT_EQ(mp::SimplexMeasure(flat.View(false), 0), 0.0);
}

TEST(CellGeometry, CentroidIsMeasureWeightedAndCornerMeanIsNot)
{
  // A quad of two unequal triangles: (0,0) (3,0) (3,1) and (0,0) (3,1) (0,3).
  TestMesh quad;
  quad.Points = { 0, 0, 0, 3, 0, 0, 3, 1, 0, 0, 3, 0 };
  quad.Cells = { 0, 1, 2, 0, 2, 3 };
  const mp::MeshView view = quad.View(false);
  const Index both[2] = { 0, 1 };
  double centroid[3];
  const double measure = mp::CellCentroid(view, both, 2, centroid);
  EXPECT_DOUBLE_EQ(measure, 1.5 + 4.5);
  // (1.5 (2, 1/3) + 4.5 (1, 4/3)) / 6
  EXPECT_NEAR(centroid[0], (1.5 * 2.0 + 4.5 * 1.0) / 6.0, 1e-15);
  EXPECT_NEAR(centroid[1], (1.5 / 3.0 + 4.5 * 4.0 / 3.0) / 6.0, 1e-15);
  EXPECT_EQ(centroid[2], 0.0);
  double mean[3];
  mp::CornerMean(view, both, 2, mean);
  EXPECT_NEAR(mean[0], (0 + 3 + 3 + 0 + 3 + 0) / 6.0, 1e-15);
  EXPECT_NEAR(mean[1], (0 + 0 + 1 + 0 + 1 + 3) / 6.0, 1e-15);
  EXPECT_GT(std::fabs(mean[1] - centroid[1]), 0.1); // two notions
  // One triangle: both its centroid.
  mp::CellCentroid(view, both + 1, 1, centroid);
  mp::CornerMean(view, both + 1, 1, mean);
  EXPECT_NEAR(centroid[0], 1.0, 1e-15);
  EXPECT_NEAR(mean[0], 1.0, 1e-15);
  EXPECT_NEAR(centroid[1], 4.0 / 3.0, 1e-15);
  EXPECT_NEAR(mean[1], 4.0 / 3.0, 1e-15);
  // No simplex: 0.
  mp::CellCentroid(view, both, 0, centroid);
  mp::CornerMean(view, both, 0, mean);
  EXPECT_EQ(centroid[0], 0.0);
  EXPECT_EQ(mean[1], 0.0);
}

TEST(CellGeometry, CentroidOfACellOfNoMeasureIsItsSimplicesMean)
{
  // Two flat triangles on a line: (0,0) (1,0) (2,0) and (2,0) (4,0) (6,0).
  TestMesh line;
  line.Points = { 0, 0, 0, 1, 0, 0, 2, 0, 0, 4, 0, 0, 6, 0, 0 };
  line.Cells = { 0, 1, 2, 2, 3, 4 };
  const mp::MeshView view = line.View(false);
  const Index both[2] = { 0, 1 };
  double centroid[3];
  EXPECT_EQ(mp::CellCentroid(view, both, 2, centroid), 0.0);
  EXPECT_NEAR(centroid[0], (1.0 + 4.0) / 2.0, 1e-15);
  EXPECT_EQ(centroid[1], 0.0);
}
