// SPDX-License-Identifier: BSD-3-Clause
// Curved second-order cells split on the lattice of order 2L
// (Geometry/CurvedSplit.h): conforming across shared curved edges and
// faces, one orientation, the measure converging as 1 / L^2 within the
// stated bound.
#include "Geometry/CurvedSplit.h"
#include "Geometry/NodalShapes.h"
#include "Geometry/Predicates.h"
#include "NodalMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace
{
using mp::Index;
using mp::NodalType;

/// A second-order mesh's cells refined at `level` (every cell: the tests'
/// cells are all curved), points = the mesh's then the added ones.
struct Refined
{
  std::vector<double> Points;
  std::vector<Index> Simplices;
  int Corners = 3;
};

Refined Refine(const nodaltest::NodalMesh& mesh, int level)
{
  Refined r;
  r.Corners = mesh.Dimension + 1;
  mp::CurvedSplitter splitter(mesh.Points.data(), mesh.NumberOfPoints(), level);
  for (size_t c = 0; c < mesh.Types.size(); ++c)
  {
    const Index* nodes = &mesh.Nodes[static_cast<size_t>(mesh.Offsets[c])];
    EXPECT_TRUE(splitter.Split(mesh.Types[c], nodes, r.Simplices)) << "cell " << c;
  }
  r.Points = mesh.Points;
  r.Points.insert(r.Points.end(), splitter.AddedPoints().begin(), splitter.AddedPoints().end());
  return r;
}

double Measure(const Refined& r)
{
  double sum = 0.0;
  for (size_t s = 0; s < r.Simplices.size(); s += r.Corners)
  {
    const double* a = &r.Points[3 * r.Simplices[s]];
    const double* b = &r.Points[3 * r.Simplices[s + 1]];
    const double* c = &r.Points[3 * r.Simplices[s + 2]];
    if (r.Corners == 3)
    {
      sum += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    else
    {
      sum += mp::Orient3D(a, b, c, &r.Points[3 * r.Simplices[s + 3]]) / 6.0;
    }
  }
  return sum;
}

/// How many simplices have each face (sorted corner ids of d corners).
std::map<std::vector<Index>, int> FaceUses(const Refined& r)
{
  std::map<std::vector<Index>, int> uses;
  for (size_t s = 0; s < r.Simplices.size(); s += r.Corners)
  {
    for (int k = 0; k < r.Corners; ++k)
    {
      std::vector<Index> face;
      for (int j = 0; j < r.Corners; ++j)
      {
        if (j != k)
        {
          face.push_back(r.Simplices[s + j]);
        }
      }
      std::sort(face.begin(), face.end());
      ++uses[face];
    }
  }
  return uses;
}

/// Every point moved by a smooth bend: straight mid nodes become curved.
nodaltest::NodalMesh Bent(nodaltest::NodalMesh mesh)
{
  for (size_t p = 0; p < mesh.Points.size(); p += 3)
  {
    double* x = &mesh.Points[p];
    const double u = x[0], v = x[1], w = x[2];
    x[0] = u + 0.08 * std::sin(3.0 * v) + 0.05 * w * w;
    x[1] = v + 0.06 * std::cos(2.0 * u + w);
    x[2] = w + 0.07 * std::sin(2.5 * u) * v;
  }
  return mesh;
}
} // namespace

TEST(CurvedSplit, DiskAreaConvergesAsOneOverLevelSquaredWithinTheBound)
{
  const nodaltest::NodalMesh disk = nodaltest::Disk(3);
  // The isoparametric disk's area, from a fine level (its error ~1/256 of level 1's).
  const double curved = Measure(Refine(disk, 16));
  // The bound: every boundary edge's sag |d| / (4 L^2) times its length, summed.
  double sagTimesLength = 0.0;
  for (size_t c = 0; c < disk.Types.size(); ++c)
  {
    const Index* n = &disk.Nodes[static_cast<size_t>(disk.Offsets[c])];
    for (auto e : { std::array<int, 3>{ 0, 1, 3 }, { 1, 2, 4 }, { 2, 0, 5 } })
    {
      const double* a = disk.Point(n[e[0]]);
      const double* b = disk.Point(n[e[1]]);
      const double* m = disk.Point(n[e[2]]);
      const double d = std::hypot(m[0] - 0.5 * (a[0] + b[0]), m[1] - 0.5 * (a[1] + b[1]));
      sagTimesLength += d * std::hypot(b[0] - a[0], b[1] - a[1]);
    }
  }
  // Level 1 is the polygon through the nodes (NodalSplit's): the splitter refuses it.
  {
    std::vector<Index> none;
    mp::CurvedSplitter splitter(disk.Points.data(), disk.NumberOfPoints(), 1);
    EXPECT_FALSE(splitter.Split(NodalType::Triangle6, disk.Nodes.data(), none));
    EXPECT_TRUE(none.empty());
  }
  Refined nodesOnly;
  nodesOnly.Points = disk.Points;
  nodesOnly.Simplices = disk.Cells;
  double previous = std::fabs(curved - Measure(nodesOnly));
  EXPECT_LE(previous, sagTimesLength / 4.0);
  for (int level = 2; level <= 4; ++level)
  {
    const double error = std::fabs(curved - Measure(Refine(disk, level)));
    EXPECT_LE(error, sagTimesLength / (4.0 * level * level)) << "level " << level;
    // 1 / L^2: from level L - 1 to L the error falls by (L / (L - 1))^2, within 10%.
    const double expected = double(level * level) / ((level - 1) * (level - 1));
    EXPECT_NEAR(previous / error, expected, 0.1 * expected) << "level " << level;
    previous = error;
  }
  EXPECT_NEAR(curved, M_PI, 2e-3); // boundary mid nodes on the circle
}

TEST(CurvedSplit, BentTet10CubeIsConformingAndOneSigned)
{
  const nodaltest::NodalMesh cube = Bent(nodaltest::Cube(2, 0.1, 7));
  for (int level : { 2, 3 })
  {
    const Refined r = Refine(cube, level);
    const int n = 2 * level;
    EXPECT_EQ(r.Simplices.size() / 4, cube.Types.size() * n * n * n);
    // Conforming: every face met twice but the cube's boundary, met once,
    // and the boundary's faces are those of 6 faces' lattices: 2 n'^2 each,
    // n' = 2 cells x n lattice steps per cube side.
    size_t once = 0;
    for (const auto& face : FaceUses(r))
    {
      ASSERT_LE(face.second, 2);
      once += face.second == 1;
    }
    EXPECT_EQ(once, size_t(6 * 2 * (2 * n) * (2 * n)));
    // Each cell's simplices have its corners' orientation (the grid's
    // Kuhn tetrahedra come in both).
    const size_t perCell = size_t(4 * n * n * n);
    for (size_t s = 0; s < r.Simplices.size(); s += 4)
    {
      const Index* corners = &cube.Nodes[static_cast<size_t>(cube.Offsets[s / perCell])];
      const double cell = mp::Orient3D(cube.Point(corners[0]), cube.Point(corners[1]),
        cube.Point(corners[2]), cube.Point(corners[3]));
      const Index* v = &r.Simplices[s];
      EXPECT_GT(cell *
          mp::Orient3D(
            &r.Points[3 * v[0]], &r.Points[3 * v[1]], &r.Points[3 * v[2]], &r.Points[3 * v[3]]),
        0.0);
    }
    // The lattice points: the nodes and the added ones, each once.
    const int m = 2 * n + 1;
    EXPECT_EQ(r.Points.size() / 3, size_t(m * m * m));
  }
}

TEST(CurvedSplit, BentTet10VolumeConvergesAsOneOverLevelSquared)
{
  const nodaltest::NodalMesh cube = Bent(nodaltest::Cube(2, 0.1, 3));
  const double curved = Measure(Refine(cube, 16));
  double base = 0.0;
  {
    Refined r;
    r.Corners = 4;
    r.Points = cube.Points;
    r.Simplices = cube.Cells; // NodalSplit's split on the nodes: level 1
    base = std::fabs(Measure(r) - curved);
  }
  EXPECT_GT(base, 1e-5);
  // From level 2 to 4 the error falls by 4 (1 / L^2), within 25%; level 2
  // is at least 4 times better than the split on the nodes.
  const double two = std::fabs(Measure(Refine(cube, 2)) - curved);
  const double four = std::fabs(Measure(Refine(cube, 4)) - curved);
  EXPECT_GE(base / two, 4.0);
  EXPECT_NEAR(two / four, 4.0, 1.0);
}

TEST(CurvedSplit, SagIsRelativeAndFallsWithTheLevel)
{
  // A tri6 with one mid node 0.1 off its edge (0, 1) of length 1.
  const double points[] = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, -0.1, 0, 0.5, 0.5, 0, 0, 0.5, 0 };
  const Index nodes[] = { 0, 1, 2, 3, 4, 5 };
  const double size = std::sqrt(2.0);
  EXPECT_NEAR(mp::RelativeCurvedSag(NodalType::Triangle6, points, nodes, 1), 0.1 / 4 / size, 1e-15);
  EXPECT_NEAR(
    mp::RelativeCurvedSag(NodalType::Triangle6, points, nodes, 3), 0.1 / 36 / size, 1e-15);
  // The refined edge's points are within 0.1 / (4 L^2) of the parabola, and on it.
  mp::CurvedSplitter splitter(points, 6, 3);
  std::vector<Index> triangles;
  ASSERT_TRUE(splitter.Split(NodalType::Triangle6, nodes, triangles));
  EXPECT_EQ(triangles.size(), size_t(3 * 36));
  for (size_t k = 0; k < splitter.AddedPoints().size(); k += 3)
  {
    const double* x = &splitter.AddedPoints()[k];
    if (std::fabs(x[1]) > 1e-12 && x[1] < 0.0)
    {
      // On edge (0, 1): y = -0.4 x (1 - x).
      EXPECT_NEAR(x[1], -0.4 * x[0] * (1 - x[0]), 1e-15);
    }
  }
}
