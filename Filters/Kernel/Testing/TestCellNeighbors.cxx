// SPDX-License-Identifier: BSD-3-Clause
// Face neighbours: the matcher at each face's lowest point (what the kernel
// and the filter use) against the face-by-face matcher it replaced, on
// meshes of every dimension, in generated and shuffled numberings, with
// non-manifold faces and cells that name a point twice, on one task and on
// several concurrent ones.
#include "GeneratedMeshes.h"
#include "Threads.h"
#include "Mesh/CellNeighbors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <numeric>
#include <random>

namespace
{
using mp::Index;
using mp::NeighborId;
using mptest::TestMesh;

/// The reference: MatchFaces over the kernel's point-to-cell lists, one range.
Index Reference(const mp::MeshView& mesh, std::vector<NeighborId>& neighbors)
{
  std::vector<Index> start;
  std::vector<Index> around;
  mp::BuildPointCells(mesh, start, around);
  neighbors.assign(static_cast<size_t>(mesh.NumberOfCells) * mesh.CornersPerCell(), -1);
  return mp::MatchFaces(
           mesh,
           [&](Index p, const auto& visit) {
             for (Index i = start[p]; i < start[p + 1]; ++i)
             {
               visit(around[i]);
             }
           },
           neighbors.data(), 0, mesh.NumberOfCells) /
    2;
}

mp::TaskRunner Threads(int tasks)
{
  return mptest::ThreadRunner(tasks);
}

/// Cells and points in random order (the cells' corners rotated too).
TestMesh Shuffled(const TestMesh& in, unsigned seed)
{
  std::mt19937 rng(seed);
  const int corners = in.Dimension + 1;
  std::vector<Index> cells(static_cast<size_t>(in.NumberOfCells()));
  std::iota(cells.begin(), cells.end(), Index(0));
  std::shuffle(cells.begin(), cells.end(), rng);
  std::vector<Index> points(static_cast<size_t>(in.NumberOfPoints()));
  std::iota(points.begin(), points.end(), Index(0));
  std::shuffle(points.begin(), points.end(), rng); // new id of old point
  TestMesh out = in;
  for (Index p = 0; p < in.NumberOfPoints(); ++p)
  {
    std::copy(&in.Points[3 * p], &in.Points[3 * p] + 3, &out.Points[3 * points[p]]);
  }
  for (size_t c = 0; c < cells.size(); ++c)
  {
    const int turn = static_cast<int>(c % corners);
    for (int k = 0; k < corners; ++k)
    {
      out.Cells[c * corners + k] = points[in.Cells[cells[c] * corners + (k + turn) % corners]];
    }
  }
  return out;
}

void ExpectSameNeighbours(const TestMesh& mesh, const std::string& what, Index nonManifold = 0)
{
  const mp::MeshView view = mesh.View(false);
  std::vector<NeighborId> expected;
  const Index expectedNonManifold = Reference(view, expected);
  EXPECT_EQ(expectedNonManifold, nonManifold) << what << ": the reference's count";
  Index boundary = 0;
  for (NeighborId n : expected)
  {
    boundary += n < 0;
  }
  // A mesh with inner faces: the comparison is not between two empty lists.
  EXPECT_LT(boundary, static_cast<Index>(expected.size())) << what;
  for (int tasks : { 1, 2, 3 })
  {
    std::vector<NeighborId> found(expected.size(), 7); // overwritten everywhere
    const Index count = mp::BuildFaceNeighbors(view, found.data(), Threads(tasks));
    EXPECT_EQ(count, expectedNonManifold) << what << ", " << tasks << " tasks";
    EXPECT_EQ(found, expected) << what << ", " << tasks << " tasks";
  }
}
} // namespace

TEST(CellNeighbors, SameAsFaceByFaceOnTrianglesTetrahedraAndCurves)
{
  // Large enough for 3 tasks (4096 points each at least), and small ones.
  const TestMesh grid = mptest::GridMesh(120, 110, 0.2, 5);
  ExpectSameNeighbours(grid, "triangles");
  ExpectSameNeighbours(Shuffled(grid, 11), "shuffled triangles");
  const TestMesh cube = mptest::CubeMesh(24, 23, 22, 0.2, 3);
  ExpectSameNeighbours(cube, "tetrahedra");
  ExpectSameNeighbours(Shuffled(cube, 12), "shuffled tetrahedra");
  ExpectSameNeighbours(mptest::GridMesh(23, 17, 0.3, 6), "small triangles");
  ExpectSameNeighbours(mptest::Icosphere(3), "closed surface");
  const std::vector<double> t = mptest::Uniform(40, 0.0, 1.0, 0.3, 9, false);
  const TestMesh curve = mptest::Polyline(
    t,
    [](double s, double* x) {
      x[0] = std::cos(3 * s);
      x[1] = std::sin(3 * s);
      x[2] = 0;
    },
    false);
  ExpectSameNeighbours(curve, "open curve");
  ExpectSameNeighbours(Shuffled(curve, 13), "shuffled curve");
}

TEST(CellNeighbors, CellsAroundPointsAreTheSameOnSeveralTasks)
{
  // Concurrent tasks count and place their own cells' uses: the same sorted
  // lists as one task, on meshes with more and fewer uses per point (large
  // enough for several tasks: 65,536 cells per task at least).
  for (const TestMesh& mesh : { Shuffled(mptest::GridMesh(330, 320, 0.2, 21), 22),
         Shuffled(mptest::CubeMesh(36, 35, 34, 0.2, 23), 24) })
  {
    std::vector<Index> start;
    std::vector<Index> cells;
    mp::BuildPointCells(mesh.View(false), start, cells);
    ASSERT_EQ(start.back(), mesh.NumberOfCells() * (mesh.Dimension + 1));
    for (int tasks : { 2, 3 }) // (3: the most these meshes allow, at 65,536 cells per task)
    {
      std::vector<Index> taskStart;
      std::vector<std::int32_t> taskCells32;
      std::vector<std::int32_t> taskStart32;
      mp::BuildPointCells(mesh.View(false), taskStart32, taskCells32, Threads(tasks));
      EXPECT_TRUE(std::equal(start.begin(), start.end(), taskStart32.begin(), taskStart32.end()))
        << tasks << " tasks, dimension " << mesh.Dimension;
      EXPECT_TRUE(std::equal(cells.begin(), cells.end(), taskCells32.begin(), taskCells32.end()))
        << tasks << " tasks, dimension " << mesh.Dimension;
    }
  }
}

TEST(CellNeighbors, AFanOfManyTrianglesAroundOnePoint)
{
  // 3000 triangles around point 0 (a polygon triangulated from one corner
  // makes such a point): its faces are sorted, not compared pairwise.
  TestMesh fan;
  const int n = 3000;
  fan.Points = { 0, 0, 0 };
  for (int i = 0; i <= n; ++i)
  {
    const double a = 3.0 * i / n;
    fan.Points.insert(fan.Points.end(), { std::cos(a), std::sin(a), 0.0 });
  }
  for (int i = 0; i < n; ++i)
  {
    fan.Cells.insert(fan.Cells.end(), { 0, Index(i + 1), Index(i + 2) });
  }
  ExpectSameNeighbours(fan, "a fan");
  std::vector<NeighborId> neighbors;
  mp::BuildFaceNeighbors(fan.View(false), neighbors);
  EXPECT_EQ(neighbors[3 * 1500 + 2], 1499); // across the edge (0, 1501)
  EXPECT_EQ(neighbors[3 * 1500 + 1], 1501); // across the edge (0, 1502)
}

TEST(CellNeighbors, NonManifoldFacesGetNoNeighbour)
{
  // Three triangles on the edge (0, 1), a fourth beside one of them.
  TestMesh fan;
  fan.Points = { 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0.5, 1, 1.5, 1, 0 };
  fan.Cells = { 0, 1, 2, 1, 0, 3, 0, 1, 4, 2, 1, 5 };
  fan.Surface = true;
  ExpectSameNeighbours(fan, "three triangles on one edge", 1);
  std::vector<NeighborId> n;
  mp::BuildFaceNeighbors(fan.View(false), n);
  EXPECT_EQ(n[2 * 3 + 2], -1); // the shared edge (opposite corner 2 of cell 2)
  EXPECT_EQ(n[0 * 3 + 0], 3);  // cells 0 and 3 across the edge (1, 2)
  // Three tetrahedra on the face (0, 1, 2), and one on another face.
  TestMesh book;
  book.Dimension = 3;
  book.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1, 0.3, 0.3, 1, 1, 1, 1 };
  book.Cells = { 0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 2, 5, 1, 2, 3, 6 };
  ExpectSameNeighbours(book, "three tetrahedra on one face", 1);
  // Four curve segments at one point.
  TestMesh star;
  star.Dimension = 1;
  star.Points = { 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 2, 0, 0 };
  star.Cells = { 0, 1, 0, 2, 0, 3, 0, 4, 1, 5 };
  ExpectSameNeighbours(star, "four segments at one point", 2);
}

TEST(CellNeighbors, CellsNamingAPointTwiceAreMatchedFaceByFace)
{
  TestMesh grid = mptest::GridMesh(120, 110, 0.2, 7); // several tasks, one of them finds it
  grid.Cells[3 * 10 + 2] = grid.Cells[3 * 10 + 1];    // a triangle (a, b, b)
  ExpectSameNeighbours(grid, "a triangle naming a point twice");
  TestMesh cube = mptest::CubeMesh(3, 3, 3, 0.1, 4);
  cube.Cells[4 * 20 + 3] = cube.Cells[4 * 20 + 0];
  ExpectSameNeighbours(cube, "a tetrahedron naming a point twice");
}
