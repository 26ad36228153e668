// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/Predicates.h"
#include "Geometry/TriangleIntersector.h"
#include "Transfer/MortarAssembler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using mp::TriangleIntersector;

namespace
{
struct Pair
{
  std::vector<double> Points;
  std::vector<mp::Index> Cells{ 0, 1, 2, 3, 4, 5 };
  TriangleIntersector::Cell T;
  TriangleIntersector::Cell S;
  TriangleIntersector::Piece Piece;
  bool Met = false;

  Pair(const double t[3][2], const double s[3][2])
  {
    for (int k = 0; k < 3; ++k)
      Points.insert(Points.end(), { t[k][0], t[k][1], 0.0 });
    for (int k = 0; k < 3; ++k)
      Points.insert(Points.end(), { s[k][0], s[k][1], 0.0 });
    mp::MeshView v;
    v.Points = Points.data();
    v.NumberOfPoints = 6;
    v.Connectivity = Cells.data();
    v.NumberOfCells = 2;
    EXPECT_TRUE(TriangleIntersector::Prepare(v, 0, T));
    EXPECT_TRUE(TriangleIntersector::Prepare(v, 1, S));
    Met = TriangleIntersector::Intersect(T, S, Piece);
  }
  double Area() const { return TriangleIntersector::Measure(Piece); }
};

// An independent oracle: Sutherland-Hodgman clipping in the floating-point
// type R (long double here; binary128 for nearly collinear edges below).
template <class R>
R ClipAreaIn(const double t[3][2], const double s[3][2])
{
  using P = std::pair<R, R>;
  std::vector<P> poly = { { t[0][0], t[0][1] }, { t[1][0], t[1][1] }, { t[2][0], t[2][1] } };
  auto cross = [](P a, P b, P c) {
    return (b.first - a.first) * (c.second - a.second) -
      (b.second - a.second) * (c.first - a.first);
  };
  P sp[3] = { { s[0][0], s[0][1] }, { s[1][0], s[1][1] }, { s[2][0], s[2][1] } };
  if (cross(sp[0], sp[1], sp[2]) < 0)
    std::swap(sp[1], sp[2]);
  for (int e = 0; e < 3 && !poly.empty(); ++e)
  {
    const P a = sp[e];
    const P b = sp[(e + 1) % 3];
    std::vector<P> out;
    for (size_t i = 0; i < poly.size(); ++i)
    {
      const P p = poly[i];
      const P q = poly[(i + 1) % poly.size()];
      const R dp = cross(a, b, p);
      const R dq = cross(a, b, q);
      if (dp >= 0)
        out.push_back(p);
      if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0))
      {
        const R u = dp / (dp - dq);
        out.push_back({ p.first + u * (q.first - p.first), p.second + u * (q.second - p.second) });
      }
    }
    poly = out;
  }
  R twice = 0;
  for (size_t i = 0; i < poly.size(); ++i)
  {
    const P p = poly[i];
    const P q = poly[(i + 1) % poly.size()];
    twice += p.first * q.second - p.second * q.first;
  }
  return (twice < 0 ? -twice : twice) / 2;
}

long double ClipArea(const double t[3][2], const double s[3][2])
{
  return ClipAreaIn<long double>(t, s);
}

double TriangleArea(const double t[3][2])
{
  return 0.5 *
    std::fabs(
      (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[1][1] - t[0][1]) * (t[2][0] - t[0][0]));
}
} // namespace

TEST(TriangleIntersector, IdenticalTriangles)
{
  const double t[3][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 } };
  Pair p(t, t);
  ASSERT_TRUE(p.Met);
  EXPECT_EQ(p.Piece.NumberOfVertices, 3);
  EXPECT_DOUBLE_EQ(p.Area(), 0.5);
  EXPECT_EQ(p.Piece.TouchedFaces, 7u);
}

TEST(TriangleIntersector, ClockwiseInputIsReordered)
{
  const double t[3][2] = { { 0, 0 }, { 0, 1 }, { 1, 0 } };
  Pair p(t, t);
  EXPECT_EQ(p.T.Points[1], 2);
  EXPECT_EQ(p.T.Points[2], 1);
  EXPECT_EQ(p.T.Face[1], 2);
  EXPECT_DOUBLE_EQ(p.Area(), 0.5);
}

TEST(TriangleIntersector, DisjointTouchingAndSharedEdge)
{
  const double t[3][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 } };
  const double far[3][2] = { { 2, 2 }, { 3, 2 }, { 2, 3 } };
  EXPECT_FALSE(Pair(t, far).Met);
  // Separated, although the bounding boxes overlap.
  const double across[3][2] = { { 1, 1 }, { 0.6, 1 }, { 1, 0.6 } };
  EXPECT_FALSE(Pair(t, across).Met);

  const double vertex[3][2] = { { 1, 0 }, { 2, 0 }, { 2, 1 } };
  Pair pv(t, vertex);
  ASSERT_TRUE(pv.Met);
  EXPECT_EQ(pv.Piece.NumberOfVertices, 1);
  EXPECT_EQ(pv.Area(), 0.0);
  // Corner 1 of the target touches: faces 0 and 2 (those containing corner 1).
  EXPECT_EQ(pv.Piece.TouchedFaces, 5u);

  // The neighbour across the hypotenuse (target face 0, opposite corner 0).
  const double edge[3][2] = { { 1, 0 }, { 1, 1 }, { 0, 1 } };
  Pair pe(t, edge);
  ASSERT_TRUE(pe.Met);
  EXPECT_EQ(pe.Piece.NumberOfVertices, 2);
  EXPECT_EQ(pe.Area(), 0.0);
  EXPECT_EQ(pe.Piece.TouchedFaces, 7u); // corners 1 and 2 touch: all faces meet
  // A source corner in the middle of target edge 0 touches face 0 only.
  const double mid[3][2] = { { 0.5, 0.5 }, { 1, 0.5 }, { 0.5, 1 } };
  Pair pm(t, mid);
  ASSERT_TRUE(pm.Met);
  EXPECT_EQ(pm.Piece.NumberOfVertices, 1);
  EXPECT_EQ(pm.Piece.TouchedFaces, 1u);
}

TEST(TriangleIntersector, HandComputedPolygons)
{
  const double t[3][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 } };
  const double shifted[3][2] = { { 0.25, 0.25 }, { 1.25, 0.25 }, { 0.25, 1.25 } };
  Pair p(t, shifted);
  EXPECT_EQ(p.Piece.NumberOfVertices, 3);
  EXPECT_NEAR(p.Area(), 0.125, 1e-16);
  // Star of David: a hexagon of area 2/3 of the triangle.
  const double up[3][2] = { { 0, 0 }, { 3, 0 }, { 1.5, 3 } };
  const double down[3][2] = { { 0, 2 }, { 1.5, -1 }, { 3, 2 } };
  Pair star(up, down);
  EXPECT_EQ(star.Piece.NumberOfVertices, 6);
  EXPECT_NEAR(star.Area(), 4.5 * 2.0 / 3.0, 1e-14);
  // Contained triangle: the inner one.
  const double big[3][2] = { { -1, -1 }, { 3, -1 }, { -1, 3 } };
  EXPECT_DOUBLE_EQ(Pair(t, big).Area(), 0.5);
  EXPECT_DOUBLE_EQ(Pair(big, t).Area(), 0.5);
}

// The pair of triangles on which the original PANG intersection code failed
// (McCoid & Gander, ACM TOMS 2022; ../shared/data/pang-triangle-failure).
// They share a corner and overlap in a thin sliver.
TEST(TriangleIntersector, PangFailurePair)
{
  const double p[3][2] = { { -2.1343467936640161, 0.63382959352026025 },
    { -1.2945925149894781, 0.62248366578973591 }, { -1.7744113806857911, 1.3289335774535278 } };
  const double s[3][2] = { { -0.4548382363149403, 0.61113773805921157 },
    { -1.4144759677075658, 2.0240375613867956 }, { -2.1343467936640161, 0.63382959352026025 } };
  Pair a(p, s);
  Pair b(s, p);
  ASSERT_TRUE(a.Met);
  ASSERT_TRUE(b.Met);
  const double expected = static_cast<double>(ClipArea(p, s));
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(a.Area(), expected, 1e-14 * TriangleArea(p));
  EXPECT_NEAR(b.Area(), expected, 1e-14 * TriangleArea(p));
  EXPECT_LE(a.Area(), std::min(TriangleArea(p), TriangleArea(s)) * (1 + 1e-15));
  // The polygon is convex and counterclockwise.
  for (int i = 0; i < a.Piece.NumberOfVertices; ++i)
  {
    const double* u = a.Piece.X[i];
    const double* v = a.Piece.X[(i + 1) % a.Piece.NumberOfVertices];
    const double* w = a.Piece.X[(i + 2) % a.Piece.NumberOfVertices];
    EXPECT_GE((v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0]), -1e-15);
  }
}

TEST(TriangleIntersector, RandomPairsMatchClipping)
{
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int met = 0;
  for (int n = 0; n < 20000; ++n)
  {
    double t[3][2];
    double s[3][2];
    for (auto& x : t)
      x[0] = u(rng), x[1] = u(rng);
    for (auto& x : s)
      x[0] = 0.5 * u(rng), x[1] = 0.5 * u(rng);
    // Every fourth case: snap source corners onto target corners or edges.
    if (n % 4 == 0)
    {
      const int k = n % 3;
      const double w = (n % 8 == 0) ? 0.0 : 0.5;
      s[0][0] = (1 - w) * t[k][0] + w * t[(k + 1) % 3][0];
      s[0][1] = (1 - w) * t[k][1] + w * t[(k + 1) % 3][1];
    }
    if (TriangleArea(t) < 1e-6 || TriangleArea(s) < 1e-6)
      continue;
    Pair p(t, s);
    const long double expected = ClipArea(t, s);
    met += p.Met;
    if (!p.Met)
    {
      EXPECT_LT(expected, 1e-15) << n;
      continue;
    }
    EXPECT_NEAR(p.Area(), static_cast<double>(expected), 1e-13) << n;
    // Symmetry: the same polygon measure when the roles are swapped.
    EXPECT_NEAR(Pair(s, t).Area(), p.Area(), 1e-14) << n;
  }
  EXPECT_GT(met, 5000);
}

namespace
{
// Twice the signed area of the turn u -> v -> w.
double Turn(const double* u, const double* v, const double* w)
{
  return (v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0]);
}

// The piece is a convex counterclockwise polygon of distinct vertices: no
// turn clockwise beyond rounding (`scale`: the cells' size), and its area
// (a fan from vertex 0, which misordered vertices would cross) matches the
// clipping oracle's.
void ExpectConvexPiece(const Pair& p, long double expected, double scale, const std::string& what)
{
  const auto& piece = p.Piece;
  const int n = piece.NumberOfVertices;
  for (int i = 0; i < n; ++i)
  {
    const double* u = piece.X[i];
    const double* v = piece.X[(i + 1) % n];
    const double* w = piece.X[(i + 2) % n];
    EXPECT_FALSE(u[0] == v[0] && u[1] == v[1]) << what << ": vertex " << i << " repeated";
    if (n >= 3)
    {
      EXPECT_GE(Turn(u, v, w), -1e-15 * scale * scale) << what << ": turn at vertex " << i;
    }
  }
  EXPECT_NEAR(p.Area(), static_cast<double>(expected), 1e-14 * scale * scale) << what;
}
} // namespace

// Most pairs are in general position (no corner on a line of the other
// cell): their vertices are ordered by the edges they lie on rather than
// sorted. Pieces of every vertex count, from both roles, in random
// positions and rotations, are convex, counterclockwise, without repeated
// vertices and of the oracle's area.
TEST(TriangleIntersector, GeneralPositionPiecesAreConvexPolygons)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int counts[7] = {};
  for (int n = 0; n < 20000; ++n)
  {
    double t[3][2];
    double s[3][2];
    for (auto& x : t)
      x[0] = u(rng), x[1] = u(rng);
    // Half the pairs: a source of similar size near the target's center
    // (hexagons, pentagons); else smaller (contained, one corner inside).
    const double size = n % 2 ? 1.0 : 0.4;
    for (auto& x : s)
      x[0] = size * u(rng), x[1] = size * u(rng);
    if (TriangleArea(t) < 1e-4 || TriangleArea(s) < 1e-4)
      continue;
    for (int roles = 0; roles < 2; ++roles)
    {
      Pair p = roles ? Pair(s, t) : Pair(t, s);
      if (!p.Met)
      {
        EXPECT_LT(ClipArea(t, s), 1e-15) << n;
        continue;
      }
      ++counts[std::min(p.Piece.NumberOfVertices, 6)];
      ExpectConvexPiece(p, ClipArea(t, s), 1.0, "pair " + std::to_string(n));
    }
  }
  for (int v = 3; v <= 6; ++v)
  {
    EXPECT_GT(counts[v], 100) << v << " vertices";
  }
}

namespace
{
// Whether segment a-b meets the closed counterclockwise triangle c, for a
// segment and triangle in general position (no corner on a line of the
// other: the exact orientations are not zero; false `general` else).
bool SegmentMeets(const double* a, const double* b, const double (&c)[3][2], bool& general)
{
  bool inside[2] = { true, true };
  bool crosses = false;
  for (int k = 0; k < 3; ++k)
  {
    const double* p = c[(k + 1) % 3];
    const double* q = c[(k + 2) % 3];
    const double oa = mp::Orient2D(p, q, a);
    const double ob = mp::Orient2D(p, q, b);
    const double op = mp::Orient2D(a, b, p);
    const double oq = mp::Orient2D(a, b, q);
    general = general && oa != 0 && ob != 0 && op != 0 && oq != 0;
    inside[0] = inside[0] && oa > 0;
    inside[1] = inside[1] && ob > 0;
    crosses = crosses || ((oa > 0) != (ob > 0) && (op > 0) != (oq > 0));
  }
  return inside[0] || inside[1] || crosses;
}
} // namespace

// The faces a piece reports (the front passes its seeds on by them) are
// exactly the edges of each cell that meet the other closed cell: checked
// edge by edge on random pairs in general position (the route that keeps
// vertices by the line they arrive along), both roles.
TEST(TriangleIntersector, TouchedFacesAreTheEdgesMeetingTheOtherCell)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int n = 0; n < 20000; ++n)
  {
    double t[3][2];
    double s[3][2];
    for (auto& x : t)
      x[0] = u(rng), x[1] = u(rng);
    const double size = n % 2 ? 1.0 : 0.4;
    for (auto& x : s)
      x[0] = size * u(rng), x[1] = size * u(rng);
    if (TriangleArea(t) < 1e-4 || TriangleArea(s) < 1e-4)
      continue;
    Pair p(t, s);
    bool general = true;
    unsigned touched = 0;
    unsigned sourceFaces = 0;
    for (int k = 0; k < 3; ++k)
    {
      touched |=
        static_cast<unsigned>(SegmentMeets(p.T.X[(k + 1) % 3], p.T.X[(k + 2) % 3], p.S.X, general))
        << k;
      sourceFaces |=
        static_cast<unsigned>(SegmentMeets(p.S.X[(k + 1) % 3], p.S.X[(k + 2) % 3], p.T.X, general))
        << k;
    }
    if (!general)
      continue;
    ++checked;
    EXPECT_EQ(p.Met, touched != 0 || sourceFaces != 0) << n;
    EXPECT_EQ(p.Piece.TouchedFaces, p.Met ? touched : 0u) << n;
    EXPECT_EQ(p.Piece.SourceFaces, p.Met ? sourceFaces : 0u) << n;
  }
  EXPECT_GT(checked, 15000);
}

// A source edge passing at a tiny distance from a target corner, on either
// side: two crossings (or a crossing and the corner) nearly coincide and
// round onto each other. The piece keeps the right order and no repeated
// vertex, for distances from 1e-8 down to subnormal.
TEST(TriangleIntersector, NearlyCoincidentCrossings)
{
  const double t[3][2] = { { 0.1, 0.2 }, { 1.3, 0.1 }, { 0.3, 1.1 } };
  const double distances[] = { 1e-8, 1e-12, 1e-15, 1e-16, 1e-17, 1e-20, 1e-300, 4e-320 };
  int checked = 0;
  for (int corner = 0; corner < 3; ++corner)
  {
    const double* c = t[corner];
    const double* a = t[(corner + 1) % 3];
    const double* b = t[(corner + 2) % 3];
    // The direction from the corner into the triangle (toward the mean of
    // the other corners) and a unit normal to the cutting line.
    double d[2] = { 0.5 * (a[0] + b[0]) - c[0], 0.5 * (a[1] + b[1]) - c[1] };
    const double length = std::hypot(d[0], d[1]);
    d[0] /= length;
    d[1] /= length;
    for (double distance : distances)
    {
      for (int side = -1; side <= 1; side += 2)
      {
        // The cutting line passes at signed distance side * distance from
        // the corner, across the corner's direction; the source lies on the
        // far side of it (the triangle's body), reaching well beyond.
        const double m[2] = { c[0] + side * distance * d[0], c[1] + side * distance * d[1] };
        const double e[2] = { -d[1], d[0] };
        const double s[3][2] = { { m[0] + 3 * e[0], m[1] + 3 * e[1] },
          { m[0] - 3 * e[0], m[1] - 3 * e[1] }, { m[0] + 3 * d[0], m[1] + 3 * d[1] } };
        for (int roles = 0; roles < 2; ++roles)
        {
          Pair p = roles ? Pair(s, t) : Pair(t, s);
          char what[96];
          std::snprintf(what, sizeof what, "corner %d, distance %g%s", corner, side * distance,
            roles ? ", roles swapped" : "");
          ASSERT_TRUE(p.Met) << what;
          ExpectConvexPiece(p, ClipArea(t, s), 1.0, what);
          EXPECT_GE(p.Piece.NumberOfVertices, 3) << what;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 3 * 8 * 2 * 2);
}

// Corners of the source put on lines of the target's edges (rounded there,
// then moved a few ulps): edges nearly collinear with the target's, at
// distances of about 1e-17 of their length, and crossings of those lines.
// The signs of the orientations are exact, but the filter's rounded
// determinants are far off in size here; the crossings are placed with
// exactly recomputed ones (Crossing), and every piece has the area of the
// exact clipping to rounding (with the rounded ones, a few of these pieces
// would be off by percents).
TEST(TriangleIntersector, NearlyCollinearEdgesCrossAtTheirExactPlace)
{
#if !defined(__SIZEOF_FLOAT128__)
  GTEST_SKIP() << "no binary128 type for the oracle";
#else
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto pick = [&rng](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  int checked = 0;
  int nearlyCollinear = 0;
  for (int n = 0; n < 40000; ++n)
  {
    double t[3][2];
    double s[3][2];
    for (auto& x : t)
      x[0] = unit(rng), x[1] = unit(rng);
    for (auto& x : s)
      x[0] = unit(rng), x[1] = unit(rng);
    // Source corners onto target edge lines or corners: in half the pairs
    // two onto one line (a source edge along a target edge), the third
    // often onto the opposite target corner; else one to three anywhere.
    const bool alongEdge = n % 2 == 0;
    const int line = pick(3);
    const int moved = alongEdge ? 2 + pick(2) : 1 + pick(3);
    for (int m = 0; m < moved; ++m)
    {
      const int j = alongEdge ? m : pick(3);
      const int k = alongEdge && m < 2 ? line : pick(3);
      const double* a = t[(k + 1) % 3];
      const double* b = t[(k + 2) % 3];
      if (alongEdge ? m == 2 : pick(4) == 0)
      {
        s[j][0] = t[k][0];
        s[j][1] = t[k][1];
      }
      else
      {
        const double w = 2.0 * unit(rng) - 0.5; // beyond the ends too
        s[j][0] = a[0] + w * (b[0] - a[0]);
        s[j][1] = a[1] + w * (b[1] - a[1]);
      }
      for (int step = pick(4); step > 0; --step)
      {
        double& x = s[j][pick(2)];
        x = std::nextafter(x, pick(2) ? 2.0 : -1.0);
      }
    }
    if (TriangleArea(t) < 1e-3 || TriangleArea(s) < 1e-3)
      continue;
    double extent = 0.0;
    for (int d = 0; d < 2; ++d)
    {
      double lo = t[0][d];
      double hi = t[0][d];
      for (int k = 0; k < 3; ++k)
      {
        lo = std::min({ lo, t[k][d], s[k][d] });
        hi = std::max({ hi, t[k][d], s[k][d] });
      }
      extent = std::max(extent, hi - lo);
    }
    bool collinear = false;
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
      {
        const double o = Turn(t[(k + 1) % 3], t[(k + 2) % 3], s[j]);
        collinear |= o != 0.0 && std::fabs(o) < 1e-14 * extent * extent;
      }
    nearlyCollinear += collinear;
    // The oracle in binary128 (113-bit significands): the differences of
    // double coordinates of similar size are exact in it and their products
    // nearly so, so its orientations are accurate to about 2^-110 of their
    // scale, far below the tiny determinants of nearly collinear points
    // that the long double oracle cannot resolve.
    const double expected = static_cast<double>(ClipAreaIn<__float128>(t, s));
    for (int roles = 0; roles < 2; ++roles)
    {
      Pair p = roles ? Pair(s, t) : Pair(t, s);
      const double area = p.Met ? p.Area() : 0.0;
      ASSERT_NEAR(area, expected, 1e-13 * extent * extent)
        << "pair " << n << (roles ? ", roles swapped" : "") << ", vertices "
        << p.Piece.NumberOfVertices;
      ++checked;
    }
  }
  EXPECT_GT(checked, 40000);
  EXPECT_GT(nearlyCollinear, 10000);
#endif
}

// A small triangle (size h, near the origin) across an edge or a corner of
// a huge one (its other corners L = 20..1e15 h away). A crossing placed
// along the huge edge carries an error of about the rounding unit times its
// length, up to 10% of h at these ratios; placed along the shorter edge,
// from exact orientations, it is within rounding of h. Both roles, against
// clipping the small triangle by the huge one's lines in binary128 (exact
// differences at these ratios).
TEST(TriangleIntersector, TinyCellsAgainstHugeOnesKeepTheirArea)
{
#if !defined(__SIZEOF_FLOAT128__)
  GTEST_SKIP() << "no binary128 type for the oracle";
#else
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int met[2] = {};
  int checked = 0;
  for (int n = 0; n < 20000; ++n)
  {
    const double h = std::ldexp(1.0, -40 + static_cast<int>(rng() % 80));
    const double ratio = std::pow(10.0, 1.3 + 13.7 * unit(rng)); // 20 to 1e15
    const double L = ratio * h;
    double small[3][2];
    double huge[3][2];
    const double angle = 6.283185307179586 * unit(rng);
    const double cx = h * (unit(rng) - 0.5);
    const double cy = h * (unit(rng) - 0.5);
    const double ux = std::cos(angle);
    const double uy = std::sin(angle);
    // The huge triangle: an edge through a point within h of the origin
    // (n even) or a corner there (n odd), its other corners about L away.
    if (n % 2 == 0)
    {
      const double a = 0.2 + 0.8 * unit(rng);
      const double b = 0.2 + 0.8 * unit(rng);
      huge[0][0] = cx - a * L * ux, huge[0][1] = cy - a * L * uy;
      huge[1][0] = cx + b * L * ux, huge[1][1] = cy + b * L * uy;
      huge[2][0] = cx - L * uy, huge[2][1] = cy + L * ux;
    }
    else
    {
      const double opening = 0.2 + 2.5 * unit(rng);
      huge[0][0] = cx, huge[0][1] = cy;
      huge[1][0] = cx + L * ux, huge[1][1] = cy + L * uy;
      huge[2][0] = cx + L * std::cos(angle + opening),
      huge[2][1] = cy + L * std::sin(angle + opening);
    }
    for (auto& x : small)
      x[0] = h * (unit(rng) - 0.5), x[1] = h * (unit(rng) - 0.5);
    const double expected = static_cast<double>(ClipAreaIn<__float128>(small, huge));
    if (TriangleArea(small) < 1e-3 * h * h)
      continue;
    met[n % 2] +=
      expected > 1e-3 * h * h && expected < std::min(TriangleArea(small), TriangleArea(huge));
    for (int roles = 0; roles < 2; ++roles)
    {
      Pair p = roles ? Pair(huge, small) : Pair(small, huge);
      const double got = p.Met ? p.Area() : 0.0;
      ASSERT_NEAR(got, expected, 1e-13 * h * h)
        << "pair " << n << (roles ? ", roles swapped" : "") << ", h " << h << ", L/h " << ratio;
      ++checked;
    }
  }
  for (int shape = 0; shape < 2; ++shape)
    EXPECT_GT(met[shape], 2000) << "shape " << shape; // partly covered: crossings made
  EXPECT_GT(checked, 35000);
#endif
}

TEST(TriangleIntersector, MortarEntriesOfIdenticalTriangles)
{
  // Integral of phi_i phi_j over a triangle of area A: A/12 (1 + delta_ij).
  const double t[3][2] = { { 0.3, 0.1 }, { 2.0, 0.4 }, { 0.7, 1.9 } };
  Pair p(t, t);
  double mts[3][3] = {};
  double mtt[3][3] = {};
  const double area = mp::AddPieceBlocks<TriangleIntersector, mp::P1Space<2>, mp::P1Space<2>>(
    p.Piece, p.T, p.S, mts, mtt);
  EXPECT_NEAR(area, TriangleArea(t), 1e-15);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
    {
      EXPECT_NEAR(mts[i][j], area / 12.0 * (1 + (i == j)), 1e-15);
      EXPECT_NEAR(mtt[i][j], area / 12.0 * (1 + (i == j)), 1e-15);
    }
}
