// SPDX-License-Identifier: BSD-3-Clause
// Cells split into simplices by the vertex-id rule (Geometry/CellSplit.h):
// the pieces fill each cell exactly, neighbours split their shared faces
// alike whatever the numbering, polyhedra from files are oriented first,
// cells the cone cannot tile are refused, and polygons fall back to ears.
#include "Geometry/CellSplit.h"
#include "Geometry/Predicates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <vector>

using mp::CellShape;
using mp::Index;
using mp::SplitStatus;

namespace
{
double TetVolume(const std::vector<double>& x, const Index* t)
{
  return std::fabs(mp::Orient3D(&x[3 * t[0]], &x[3 * t[1]], &x[3 * t[2]], &x[3 * t[3]])) / 6.0;
}

double TriangleArea(const std::vector<double>& x, const Index* t)
{
  const double* a = &x[3 * t[0]];
  const double* b = &x[3 * t[1]];
  const double* c = &x[3 * t[2]];
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
    u[0] * v[1] - u[1] * v[0] };
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/// Every tetrahedron's faces as sorted triples, with how often each occurs.
std::map<std::array<Index, 3>, int> FaceCounts(const std::vector<Index>& tets)
{
  std::map<std::array<Index, 3>, int> count;
  for (size_t t = 0; t < tets.size(); t += 4)
  {
    for (int k = 0; k < 4; ++k)
    {
      std::array<Index, 3> f;
      for (int j = 0, i = 0; j < 4; ++j)
      {
        if (j != k)
        {
          f[i++] = tets[t + j];
        }
      }
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  }
  return count;
}

/// A structured n^3 grid of the unit cube, interior points jittered, its
/// points numbered by `permutation`; the cells as hexahedra (VTK order).
struct HexGrid
{
  std::vector<double> X;
  std::vector<std::array<Index, 8>> Cells;

  HexGrid(int n, unsigned seed)
  {
    const int m = n + 1;
    std::mt19937 random(seed);
    std::vector<Index> number(static_cast<size_t>(m * m * m));
    std::iota(number.begin(), number.end(), Index(0));
    std::shuffle(number.begin(), number.end(), random);
    std::uniform_real_distribution<double> jitter(-0.2 / n, 0.2 / n);
    this->X.resize(3 * number.size());
    auto id = [&](int i, int j, int k) { return number[(k * m + j) * m + i]; };
    for (int k = 0; k < m; ++k)
    {
      for (int j = 0; j < m; ++j)
      {
        for (int i = 0; i < m; ++i)
        {
          const int ijk[3] = { i, j, k };
          for (int d = 0; d < 3; ++d)
          {
            const bool inside = ijk[d] > 0 && ijk[d] < n;
            this->X[3 * id(i, j, k) + d] = double(ijk[d]) / n + (inside ? jitter(random) : 0.0);
          }
        }
      }
    }
    for (int k = 0; k < n; ++k)
    {
      for (int j = 0; j < n; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          this->Cells.push_back(
            { id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
              id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1) });
        }
      }
    }
  }
};
} // namespace

TEST(CellSplit, StandardFacesRunEachEdgeOnceEachWay)
{
  const std::pair<CellShape, int> shapes[] = { { CellShape::Hexahedron, 8 },
    { CellShape::Voxel, 8 }, { CellShape::Wedge, 6 }, { CellShape::Pyramid, 5 },
    { CellShape::PentagonalPrism, 10 }, { CellShape::HexagonalPrism, 12 } };
  for (const auto& shape : shapes)
  {
    std::vector<Index> corners(static_cast<size_t>(shape.second));
    std::iota(corners.begin(), corners.end(), Index(0));
    std::vector<Index> stream;
    const int nfaces = mp::StandardCellFaces(shape.first, corners.data(), stream);
    std::map<std::pair<Index, Index>, int> directed;
    size_t at = 0;
    for (int f = 0; f < nfaces; ++f)
    {
      const Index n = stream[at];
      for (Index k = 0; k < n; ++k)
      {
        ++directed[{ stream[at + 1 + k], stream[at + 1 + (k + 1) % n] }];
      }
      at += n + 1;
    }
    EXPECT_EQ(at, stream.size());
    for (const auto& e : directed)
    {
      EXPECT_EQ(e.second, 1);
      EXPECT_EQ(directed.count({ e.first.second, e.first.first }), 1u);
    }
  }
}

TEST(CellSplit, HexahedraOfAShuffledGridSplitConformingAndFillTheCube)
{
  for (unsigned seed = 1; seed <= 5; ++seed)
  {
    const HexGrid grid(4, seed);
    std::vector<Index> tets;
    std::vector<Index> stream;
    double volume = 0.0;
    for (const auto& cell : grid.Cells)
    {
      const size_t before = tets.size();
      const int nfaces = mp::StandardCellFaces(CellShape::Hexahedron, cell.data(), stream);
      ASSERT_EQ(
        mp::SplitPolyhedron(grid.X.data(), stream.data(), nfaces, true, tets), SplitStatus::Split);
      EXPECT_EQ(tets.size() - before, 24u); // 6 tetrahedra
      double cellVolume = 0.0;
      for (size_t t = before; t < tets.size(); t += 4)
      {
        cellVolume += TetVolume(grid.X, &tets[t]);
      }
      EXPECT_GT(cellVolume, 0.0);
      volume += cellVolume;
    }
    EXPECT_NEAR(volume, 1.0, 1e-13);
    // Conforming: every triangle is shared by two tetrahedra, or lies on the
    // cube's boundary.
    for (const auto& f : FaceCounts(tets))
    {
      ASSERT_LE(f.second, 2);
      if (f.second == 1)
      {
        bool onSide = false;
        for (int d = 0; d < 3 && !onSide; ++d)
        {
          for (double side : { 0.0, 1.0 })
          {
            onSide = onSide ||
              (grid.X[3 * f.first[0] + d] == side && grid.X[3 * f.first[1] + d] == side &&
                grid.X[3 * f.first[2] + d] == side);
          }
        }
        EXPECT_TRUE(onSide);
      }
    }
  }
}

TEST(CellSplit, EveryShapeIsFilledWhateverItsNumbering)
{
  // Unit-height prisms over a regular n-gon of circumradius 1, a wedge, a
  // pyramid and a voxel; their corners numbered at random.
  std::mt19937 random(7);
  const double pi = std::acos(-1.0);
  struct Case
  {
    CellShape Shape;
    std::vector<double> X; // in VTK corner order
    double Volume;
  };
  std::vector<Case> cases;
  for (int n : { 3, 4, 5, 6 })
  {
    Case c;
    c.Shape = n == 3 ? CellShape::Wedge
                     : (n == 4 ? CellShape::Hexahedron
                               : (n == 5 ? CellShape::PentagonalPrism : CellShape::HexagonalPrism));
    for (double z : { 0.0, 1.0 })
    {
      for (int k = 0; k < n; ++k)
      {
        c.X.insert(c.X.end(), { std::cos(2 * pi * k / n), std::sin(2 * pi * k / n), z });
      }
    }
    c.Volume = 0.5 * n * std::sin(2 * pi / n);
    cases.push_back(c);
  }
  cases.push_back({ CellShape::Pyramid, { 0, 0, 0, 2, 0, 0, 2, 3, 0, 0, 3, 0, 0.5, 1, 4 }, 8.0 });
  cases.push_back({ CellShape::Voxel,
    { 0, 0, 0, 2, 0, 0, 0, 3, 0, 2, 3, 0, 0, 0, 5, 2, 0, 5, 0, 3, 5, 2, 3, 5 }, 30.0 });
  for (const Case& c : cases)
  {
    const Index corners = static_cast<Index>(c.X.size() / 3);
    for (int trial = 0; trial < 20; ++trial)
    {
      std::vector<Index> ids(static_cast<size_t>(corners));
      std::iota(ids.begin(), ids.end(), Index(0));
      std::shuffle(ids.begin(), ids.end(), random);
      std::vector<double> x(c.X.size());
      for (Index k = 0; k < corners; ++k)
      {
        std::copy_n(&c.X[3 * k], 3, &x[3 * ids[k]]); // corner k is point ids[k]
      }
      std::vector<Index> stream;
      std::vector<Index> tets;
      const int nfaces = mp::StandardCellFaces(c.Shape, ids.data(), stream);
      ASSERT_EQ(
        mp::SplitPolyhedron(x.data(), stream.data(), nfaces, true, tets), SplitStatus::Split);
      double volume = 0.0;
      for (size_t t = 0; t < tets.size(); t += 4)
      {
        volume += TetVolume(x, &tets[t]);
      }
      EXPECT_NEAR(volume, c.Volume, 1e-13 * c.Volume);
      // A cone of the faces away from the lowest corner: corners - 3 (for
      // simplicial faces) up to the hexahedron's 6.
      EXPECT_GE(tets.size() / 4, static_cast<size_t>(c.Shape == CellShape::Pyramid ? 2 : 3));
    }
  }
}

TEST(CellSplit, PolyhedraFromFilesAreOrientedFirst)
{
  // A hexahedron given as a polyhedron whose faces run either way.
  const HexGrid grid(1, 3);
  std::vector<Index> stream;
  const int nfaces = mp::StandardCellFaces(CellShape::Hexahedron, grid.Cells[0].data(), stream);
  std::vector<Index> reference;
  ASSERT_EQ(
    mp::SplitPolyhedron(grid.X.data(), stream.data(), nfaces, true, reference), SplitStatus::Split);
  std::mt19937 random(11);
  for (int trial = 0; trial < 10; ++trial)
  {
    std::vector<Index> shuffled = stream;
    for (size_t at = 0; at < shuffled.size(); at += shuffled[at] + 1)
    {
      if (random() % 2)
      {
        std::reverse(shuffled.begin() + static_cast<std::ptrdiff_t>(at + 1),
          shuffled.begin() + static_cast<std::ptrdiff_t>(at + 1 + shuffled[at]));
      }
    }
    std::vector<Index> tets;
    ASSERT_EQ(
      mp::SplitPolyhedron(grid.X.data(), shuffled.data(), nfaces, false, tets), SplitStatus::Split);
    EXPECT_EQ(tets.size(), reference.size());
    double volume = 0.0;
    for (size_t t = 0; t < tets.size(); t += 4)
    {
      volume += TetVolume(grid.X, &tets[t]);
    }
    EXPECT_NEAR(volume, 1.0, 1e-14);
  }
  // One face missing: the faces do not close.
  std::vector<Index> open(stream.begin(), stream.begin() + 5 * 5);
  std::vector<Index> tets;
  EXPECT_EQ(
    mp::SplitPolyhedron(grid.X.data(), open.data(), 5, false, tets), SplitStatus::OpenFaces);
  EXPECT_TRUE(tets.empty());
}

TEST(CellSplit, NonConvexCellsAreConedFromACornerThatSeesThemOrRefused)
{
  // An L-shaped prism: from its reflex corner the cone tiles it; from the
  // far corner of a leg it would fold, so another corner is taken.
  const double l[6][2] = { { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
  for (int lowest : { 3, 1, 4 })
  {
    // Number the points so that bottom corner `lowest` is point 0.
    std::vector<Index> id(12);
    for (int k = 0; k < 12; ++k)
    {
      id[k] = (k - lowest + 12) % 12;
    }
    std::vector<double> x(36);
    for (int k = 0; k < 12; ++k)
    {
      x[3 * id[k]] = l[k % 6][0];
      x[3 * id[k] + 1] = l[k % 6][1];
      x[3 * id[k] + 2] = k < 6 ? 0.0 : 1.0;
    }
    std::vector<Index> stream;
    const int nfaces = mp::StandardCellFaces(CellShape::HexagonalPrism, id.data(), stream);
    std::vector<Index> tets;
    ASSERT_EQ(mp::SplitPolyhedron(x.data(), stream.data(), nfaces, true, tets), SplitStatus::Split);
    double volume = 0.0;
    for (size_t t = 0; t < tets.size(); t += 4)
    {
      volume += TetVolume(x, &tets[t]);
    }
    EXPECT_NEAR(volume, 3.0, 1e-14) << "lowest corner " << lowest;
    if (lowest != 3)
    {
      continue; // coned from another corner: its faces are split from it
    }
    // From the lowest corner, the faces' triangles are those of the face
    // rule: every tetrahedron face on the cell's boundary is one of the
    // fans of the cell's faces.
    std::map<std::array<Index, 3>, int> fans;
    for (size_t at = 0; at < stream.size(); at += stream[at] + 1)
    {
      const Index* v = &stream[at + 1];
      const int n = static_cast<int>(stream[at]);
      const int m = static_cast<int>(std::min_element(v, v + n) - v);
      for (int i = 1; i + 1 < n; ++i)
      {
        std::array<Index, 3> f = { v[m], v[(m + i) % n], v[(m + i + 1) % n] };
        std::sort(f.begin(), f.end());
        fans[f] = 1;
      }
    }
    for (const auto& f : FaceCounts(tets))
    {
      if (f.second == 1)
      {
        EXPECT_EQ(fans.count(f.first), 1u);
      }
    }
  }
  // A U-shaped prism: no corner sees both arms' far sides.
  const double u[8][2] = { { 0, 0 }, { 3, 0 }, { 3, 3 }, { 2, 3 }, { 2, 1 }, { 1, 1 }, { 1, 3 },
    { 0, 3 } };
  std::vector<double> x;
  for (double z : { 0.0, 1.0 })
  {
    for (const auto& p : u)
    {
      x.insert(x.end(), { p[0], p[1], z });
    }
  }
  std::vector<Index> stream = { 8, 7, 6, 5, 4, 3, 2, 1, 0, 8, 8, 9, 10, 11, 12, 13, 14, 15 };
  for (int k = 0; k < 8; ++k)
  {
    const int l2 = (k + 1) % 8;
    stream.insert(stream.end(), { 4, k, l2, 8 + l2, 8 + k });
  }
  std::vector<Index> tets;
  EXPECT_EQ(
    mp::SplitPolyhedron(x.data(), stream.data(), 10, true, tets), SplitStatus::NotStarShaped);
  EXPECT_TRUE(tets.empty());
}

TEST(CellSplit, PolygonsFanOrFallBackToEars)
{
  // A convex pentagon in a tilted plane, and an arrow-shaped (non-convex)
  // hexagon whose lowest corner cannot fan it.
  const double pi = std::acos(-1.0);
  std::vector<double> x;
  for (int k = 0; k < 5; ++k)
  {
    const double u = std::cos(2 * pi * k / 5);
    const double v = std::sin(2 * pi * k / 5);
    x.insert(x.end(), { u, 0.6 * v, 0.8 * v }); // the plane y = 0.75 z
  }
  const Index pentagon[5] = { 3, 4, 0, 1, 2 };
  std::vector<Index> triangles;
  ASSERT_TRUE(mp::SplitPolygon(x.data(), pentagon, 5, triangles));
  EXPECT_EQ(triangles.size(), 9u);
  EXPECT_EQ(*std::min_element(triangles.begin(), triangles.end()), 0);
  EXPECT_EQ(std::count(triangles.begin(), triangles.end(), Index(0)), 3); // the fan from 0
  double area = 0.0;
  for (size_t t = 0; t < triangles.size(); t += 3)
  {
    area += TriangleArea(x, &triangles[t]);
  }
  EXPECT_NEAR(area, 2.5 * std::sin(2 * pi / 5), 1e-14);

  // An arrow with a notch at (2, 1): its tip (4, 3) is point 0, and the fan
  // from the tip crosses the notch.
  const double arrow[6][2] = { { 0, 0 }, { 4, 0 }, { 4, 3 }, { 2, 1 }, { 0, 3 }, { -1, 1 } };
  std::vector<double> y;
  for (const auto& p : arrow)
  {
    y.insert(y.end(), { p[0], p[1], 0.0 });
  }
  const Index loop[6] = { 4, 5, 0, 1, 2, 3 }; // corner k of the arrow is point (k + 4) % 6
  std::vector<double> z(18);
  for (int k = 0; k < 6; ++k)
  {
    std::copy_n(&y[3 * k], 3, &z[3 * loop[k]]);
  }
  triangles.clear();
  ASSERT_TRUE(mp::SplitPolygon(z.data(), loop, 6, triangles));
  EXPECT_EQ(triangles.size(), 12u);
  double shoelace = 0.0;
  for (int k = 0; k < 6; ++k)
  {
    shoelace += arrow[k][0] * arrow[(k + 1) % 6][1] - arrow[(k + 1) % 6][0] * arrow[k][1];
  }
  area = 0.0;
  for (size_t t = 0; t < triangles.size(); t += 3)
  {
    const double o =
      mp::Orient2D(&z[3 * triangles[t]], &z[3 * triangles[t + 1]], &z[3 * triangles[t + 2]]);
    EXPECT_GT(o * shoelace, 0.0); // every ear has the polygon's orientation
    area += TriangleArea(z, &triangles[t]);
  }
  EXPECT_NEAR(area, 0.5 * std::fabs(shoelace), 1e-14);

  // A non-convex quadrilateral: the diagonal through the lowest corner
  // would leave it; the other one is taken.
  const double dart[4][3] = { { 0, 0, 0 }, { 2, 1, 0 }, { 4, 0, 0 }, { 2, 3, 0 } };
  std::vector<double> w(&dart[0][0], &dart[0][0] + 12);
  const Index quad[4] = { 0, 1, 2, 3 }; // reflex corner 1; the diagonal 0-2 lies outside
  triangles.clear();
  ASSERT_TRUE(mp::SplitPolygon(w.data(), quad, 4, triangles));
  ASSERT_EQ(triangles.size(), 6u);
  area = TriangleArea(w, &triangles[0]) + TriangleArea(w, &triangles[3]);
  EXPECT_NEAR(area, 4.0, 1e-14);

  // A figure eight cannot be cut into ears.
  const double eight[4][3] = { { 0, 0, 0 }, { 1, 1, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
  std::vector<double> e(&eight[0][0], &eight[0][0] + 12);
  triangles.clear();
  EXPECT_FALSE(mp::SplitPolygon(e.data(), quad, 4, triangles));
  EXPECT_TRUE(triangles.empty());
}

TEST(CellSplit, CoplanarSubfacesOfARefinementInterfaceAreTolerated)
{
  // A unit cube whose bottom face is split into four quadrilaterals (the
  // coarse side of a refinement interface, as OpenFOAM writes it), the
  // face's centre lifted or lowered by rounding-size amounts; the lowest
  // point is a corner of that face, so the cone's tetrahedra over the other
  // sub-faces are slivers signed by rounding.
  for (double lift : { 0.0, 1e-15, -1e-15, 3e-16 })
  {
    std::vector<double> x = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, // 0-3 bottom corners
      0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1,                         // 4-7 top corners
      0.5, 0, 0, 1, 0.5, 0, 0.5, 1, 0, 0, 0.5, 0,                 // 8-11 bottom edge midpoints
      0.5, 0.5, lift };                                           // 12 bottom centre
    const std::vector<Index> stream = { 4, 0, 11, 12, 8, 4, 8, 12, 9, 1, 4, 12, 10, 2, 9, 4, 11, 3,
      10, 12,              // the bottom, four quadrilaterals
      4, 4, 5, 6, 7,       // the top
      5, 0, 8, 1, 5, 4,    // y = 0, with the hanging midpoint 8
      5, 1, 9, 2, 6, 5,    // x = 1
      5, 2, 10, 3, 7, 6,   // y = 1
      5, 3, 11, 0, 4, 7 }; // x = 0
    std::vector<Index> tets;
    ASSERT_EQ(mp::SplitPolyhedron(x.data(), stream.data(), 9, false, tets), SplitStatus::Split)
      << "lift " << lift;
    double volume = 0.0;
    for (size_t t = 0; t < tets.size(); t += 4)
    {
      volume += TetVolume(x, &tets[t]);
    }
    EXPECT_NEAR(volume, 1.0, 1e-14);
  }
}
