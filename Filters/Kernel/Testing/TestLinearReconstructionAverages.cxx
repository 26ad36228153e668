// SPDX-License-Identifier: BSD-3-Clause
// LinearReconstruction (Transfer/LinearReconstruction.h) from cell averages
// the test takes itself (each parent's simplices' measures and centroids,
// not the reconstruction's centroids): a linear field comes back at every
// corner, unlimited and, away from the boundary, limited; the
// reconstruction's centroids are the measure-weighted ones; and each
// parent's mean of the reconstructed field is its value.
#include "Transfer/LinearReconstruction.h"

#include "GeneratedMeshes.h"
#include "Threads.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
using mp::Index;
using mptest::TestMesh;

double Linear(const double* x)
{
  return -0.5 + 1.25 * x[0] + 2.0 * x[1] - 0.75 * x[2];
}

/// A simplex's measure and centroid, the test's own (triangles in the plane, tetrahedra).
double Simplex(const TestMesh& m, Index c, double* centroid)
{
  const int corners = m.Dimension + 1;
  for (int d = 0; d < 3; ++d)
  {
    centroid[d] = 0.0;
    for (int k = 0; k < corners; ++k)
    {
      centroid[d] += m.Points[3 * m.Cells[corners * c + k] + d] / corners;
    }
  }
  return m.CellArea(c);
}

struct Averages
{
  std::vector<double> Value;    ///< per parent: the mean of Linear over it
  std::vector<double> Centroid; ///< 3 per parent
};

Averages ParentAverages(const TestMesh& m, const std::vector<Index>& parent, Index parents)
{
  Averages a;
  a.Value.assign(static_cast<size_t>(parents), 0.0);
  a.Centroid.assign(3 * static_cast<size_t>(parents), 0.0);
  std::vector<double> measure(static_cast<size_t>(parents), 0.0);
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    double x[3];
    const double v = Simplex(m, c, x);
    const Index p = parent[c];
    measure[p] += v;
    a.Value[p] += v * Linear(x); // a linear field's mean over a simplex: its value at the centroid
    for (int d = 0; d < 3; ++d)
    {
      a.Centroid[3 * p + d] += v * x[d];
    }
  }
  for (Index p = 0; p < parents; ++p)
  {
    a.Value[p] /= measure[p];
    for (int d = 0; d < 3; ++d)
    {
      a.Centroid[3 * p + d] /= measure[p];
    }
  }
  return a;
}

/// Parents of `group` cells (c / group: with 3, pieces of unequal measure, not all convex together).
void ExpectExactFromAverages(const TestMesh& m, int group, const char* what)
{
  std::vector<Index> parent(static_cast<size_t>(m.NumberOfCells()));
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    parent[c] = c / group;
  }
  mp::MeshView view = m.View(false);
  view.Parent = parent.data();
  view.NumberOfParents = parent.back() + 1;
  const Averages averages = ParentAverages(m, parent, view.NumberOfParents);
  mp::LinearReconstruction r;
  r.Prepare(view, mptest::ThreadRunner(2));
  for (Index p = 0; p < view.NumberOfParents; ++p)
  {
    for (int d = 0; d < view.SpaceDimension; ++d)
    {
      EXPECT_NEAR(r.Centroid(p)[d], averages.Centroid[3 * p + d], 1e-13)
        << what << ", parent " << p;
    }
  }
  const int corners = view.CornersPerCell();
  std::vector<double> values(static_cast<size_t>(view.NumberOfCells * corners));
  for (mp::Reconstruction mode : { mp::Reconstruction::Unlimited, mp::Reconstruction::Limited })
  {
    r.Reconstruct(averages.Value.data(), 1, nullptr, mode, mptest::ThreadRunner(3), values.data());
    double worst = 0.0;
    double limitedWorst = 0.0;
    std::vector<double> mean(static_cast<size_t>(view.NumberOfParents), 0.0);
    std::vector<double> measure(static_cast<size_t>(view.NumberOfParents), 0.0);
    for (Index c = 0; c < view.NumberOfCells; ++c)
    {
      double x[3];
      const double v = Simplex(m, c, x);
      double cornerMean = 0.0;
      for (int k = 0; k < corners; ++k)
      {
        const double* point = view.Point(view.Cell(c)[k]);
        const double error = std::fabs(values[c * corners + k] - Linear(point));
        // (The limiter may clip at the boundary, where a corner lies beyond
        // the centroids around it, and around parents of several cells.)
        const bool inside = group == 1 && point[0] > 0.3 && point[0] < 0.7 && point[1] > 0.3 &&
          point[1] < 0.7 && (m.Dimension == 2 || (point[2] > 0.3 && point[2] < 0.7));
        worst = std::max(worst, mode == mp::Reconstruction::Unlimited ? error : 0.0);
        limitedWorst =
          std::max(limitedWorst, mode == mp::Reconstruction::Limited && inside ? error : 0.0);
        cornerMean += values[c * corners + k] / corners;
      }
      mean[parent[c]] += v * cornerMean;
      measure[parent[c]] += v;
    }
    EXPECT_LT(worst, 1e-12) << what;
    EXPECT_LT(limitedWorst, 1e-12) << what << ", limited";
    // Conservation: the reconstructed field's mean over each parent is its value.
    for (Index p = 0; p < view.NumberOfParents; ++p)
    {
      EXPECT_NEAR(mean[p] / measure[p], averages.Value[p], 1e-12) << what << ", parent " << p;
    }
  }
  // Averages shifted by a bump in one parent: no longer linear, so the check above can fail.
  std::vector<double> bumped(averages.Value);
  bumped[view.NumberOfParents / 2] += 0.5;
  r.Reconstruct(bumped.data(), 1, nullptr, mp::Reconstruction::Unlimited, mptest::ThreadRunner(1),
    values.data());
  double worst = 0.0;
  for (Index c = 0; c < view.NumberOfCells; ++c)
  {
    for (int k = 0; k < corners; ++k)
    {
      worst =
        std::max(worst, std::fabs(values[c * corners + k] - Linear(view.Point(view.Cell(c)[k]))));
    }
  }
  EXPECT_GT(worst, 0.1) << what;
}
} // namespace

TEST(LinearReconstruction, ExactFromTheCellAveragesOfALinearField)
{
  const TestMesh triangles = mptest::GridMesh(12, 10, 0.3, 8);
  const TestMesh tetrahedra = mptest::CubeMesh(5, 4, 5, 0.2, 9);
  ExpectExactFromAverages(triangles, 1, "triangles");
  ExpectExactFromAverages(triangles, 3, "triangles in threes");
  ExpectExactFromAverages(tetrahedra, 1, "tetrahedra");
  ExpectExactFromAverages(tetrahedra, 3, "tetrahedra in threes");
}
