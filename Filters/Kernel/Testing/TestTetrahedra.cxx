// SPDX-License-Identifier: BSD-3-Clause
// 3D: the tetrahedron intersector, the advancing front over tetrahedral
// meshes (== brute force), completeness of the pieces, exactness on linear
// fields and conservation.
#include "Geometry/Predicates.h"
#include "Geometry/TetrahedronClipping.h"
#include "Geometry/TetrahedronIntersector.h"
#include "SearchComparison.h"
#include "TetrahedronPairs.h"
#include "Transfer/MortarAssembler.h"
#include "Transfer/MortarOperator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <cstring>
#include <array>
#include <vector>
#include <cmath>
#include <random>
#include <tuple>

using mp::Index;
using mp::TetrahedronIntersector;
using mptest::PreparedPair;
using mptest::RandomPair;
using mptest::SameBits;
using mptest::TestMesh;
using mptest::TwoTetrahedra;

namespace
{
double PairVolume(const double t[4][3], const double s[4][3], unsigned* touched = nullptr)
{
  const TestMesh m = TwoTetrahedra(t, s);
  TetrahedronIntersector::Cell a;
  TetrahedronIntersector::Cell b;
  EXPECT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 0, a));
  EXPECT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 1, b));
  TetrahedronIntersector::Piece p;
  const bool met = TetrahedronIntersector::Intersect(a, b, p);
  if (touched)
    *touched = p.TouchedFaces;
  const double v = TetrahedronIntersector::Measure(p);
  EXPECT_EQ(met, v > 0.0);
  return met ? v : 0.0;
}

using Searches = mptest::SearchComparison<TetrahedronIntersector>;

double Linear3(double x, double y, double z)
{
  return 1.0 + 2.0 * x - 3.0 * y + 0.5 * z;
}
double Smooth3(double x, double y, double z)
{
  return std::sin(3 * x) * std::cos(2 * y) * std::exp(z);
}
} // namespace

TEST(Tetrahedra, IdenticalContainedAndDisjoint)
{
  const double t[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  unsigned touched = 0;
  EXPECT_NEAR(PairVolume(t, t, &touched), 1.0 / 6.0, 1e-16);
  EXPECT_EQ(touched, 15u); // every face shared: seeds go through the source's faces
  const double big[4][3] = { { -1, -1, -1 }, { 4, -1, -1 }, { -1, 4, -1 }, { -1, -1, 4 } };
  EXPECT_NEAR(PairVolume(t, big), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(PairVolume(big, t), 1.0 / 6.0, 1e-15);
  const double far[4][3] = { { 2, 2, 2 }, { 3, 2, 2 }, { 2, 3, 2 }, { 2, 2, 3 } };
  EXPECT_EQ(PairVolume(t, far), 0.0);
  // Sharing the face x + y + z = 1 only: no volume.
  const double across[4][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 1 } };
  EXPECT_EQ(PairVolume(t, across), 0.0);
}

TEST(Tetrahedra, HandComputedVolumes)
{
  // The corner tetrahedron shifted by (1/4, 1/4, 1/4) meets the original in
  // a tetrahedron of edge 1/4: volume (1/4)^3 / 6.
  const double t[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  const double s[4][3] = { { 0.25, 0.25, 0.25 }, { 1.25, 0.25, 0.25 }, { 0.25, 1.25, 0.25 },
    { 0.25, 0.25, 1.25 } };
  EXPECT_NEAR(PairVolume(t, s), 1.0 / 384.0, 1e-16);
  // Cut by the plane x = 1/2: the part x <= 1/2 of the corner tetrahedron
  // has volume 1/6 - (1/2)^3 / 6 = 7/48.
  const double half[4][3] = { { 0.5, -5, -5 }, { 0.5, 10, -5 }, { 0.5, -5, 10 }, { -10, 0, 0 } };
  EXPECT_NEAR(PairVolume(t, half), 7.0 / 48.0, 1e-15);
  EXPECT_NEAR(PairVolume(half, t), 7.0 / 48.0, 1e-15);
}

TEST(Tetrahedra, RandomPairsAreSymmetricAndBounded)
{
  std::mt19937 rng(3);
  int met = 0;
  for (int n = 0; n < 5000; ++n)
  {
    double t[4][3];
    double s[4][3];
    RandomPair(rng, 0.7, t, s);
    if (n % 3 == 0) // share a corner
      std::copy(t[0], t[0] + 3, s[0]);
    const TestMesh m = TwoTetrahedra(t, s);
    if (m.CellVolume(0) < 1e-4 || m.CellVolume(1) < 1e-4)
      continue;
    const double a = PairVolume(t, s);
    const double b = PairVolume(s, t);
    met += a > 0;
    EXPECT_NEAR(a, b, 1e-13) << n;
    EXPECT_LE(a, std::min(m.CellVolume(0), m.CellVolume(1)) * (1 + 1e-12)) << n;
  }
  EXPECT_GT(met, 1000);
}

// Apart (the search's screen for the locator's candidates) only for cells
// that do not meet: random pairs spread so that most miss, and pairs that
// face each other across a plane, mirrored through a face of t and moved
// either way by up to 4 steps of 2^-52, 2^-48 or 2^-44 (sides below, at
// and above the filter's bound).
TEST(Tetrahedra, ApartOnlyForCellsThatDoNotMeet)
{
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int apart = 0;
  int missedWithBoxesMeeting = 0;
  int screened = 0;
  int mirrored = 0;
  int mirroredApart = 0;
  int mirroredMet = 0;
  for (int n = 0; n < 20000; ++n)
  {
    double t[4][3];
    double s[4][3];
    RandomPair(rng, 1.0, t, s);
    if (n % 2 == 0)
    {
      // Mirrored through face k of t (corners k+1..k+3), then moved along
      // its normal by a few ulps of the coordinates, out or in.
      const int k = n % 8 / 2;
      const double* a = t[(k + 1) % 4];
      double e1[3];
      double e2[3];
      double normal[3];
      for (int c = 0; c < 3; ++c)
      {
        e1[c] = t[(k + 2) % 4][c] - a[c];
        e2[c] = t[(k + 3) % 4][c] - a[c];
      }
      normal[0] = e1[1] * e2[2] - e1[2] * e2[1];
      normal[1] = e1[2] * e2[0] - e1[0] * e2[2];
      normal[2] = e1[0] * e2[1] - e1[1] * e2[0];
      const double nn = normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2];
      // Steps of 2^-52, 2^-48 or 2^-44 (the filter's bound is about 2^-47
      // of these cells' size): sides on both sides of it.
      const int step = -52 + 4 * static_cast<int>(rng() % 3);
      const double shift = std::ldexp(static_cast<double>(static_cast<int>(rng() % 9) - 4), step);
      for (int v = 0; v < 4; ++v)
      {
        double w = 0.0;
        for (int c = 0; c < 3; ++c)
          w += (t[v][c] - a[c]) * normal[c];
        for (int c = 0; c < 3; ++c)
          s[v][c] = t[v][c] - 2.0 * w / nn * normal[c] + shift * normal[c] / std::sqrt(nn);
      }
      ++mirrored;
    }
    else
    {
      const double offset[3] = { 1.5 * u(rng), 1.5 * u(rng), 1.5 * u(rng) };
      for (auto& x : s)
        for (int c = 0; c < 3; ++c)
          x[c] += offset[c];
    }
    TetrahedronIntersector::Cell a;
    TetrahedronIntersector::Cell b;
    if (!PreparedPair(t, s, a, b))
      continue;
    TetrahedronIntersector::Piece p;
    const bool metAB = TetrahedronIntersector::Intersect(a, b, p);
    const bool metBA = TetrahedronIntersector::Intersect(b, a, p);
    const bool split = TetrahedronIntersector::IntersectBySplitting(a, b, p);
    const bool isApart = TetrahedronIntersector::Apart(a, b);
    ASSERT_EQ(isApart, TetrahedronIntersector::Apart(b, a)) << n;
    if (isApart)
    {
      ASSERT_FALSE(metAB || metBA || split) << "pair " << n << " meets but is called apart";
      ++apart;
    }
    if (n % 2 == 0)
    {
      mirroredApart += isApart;
      mirroredMet += metAB;
    }
    bool boxesMeet = true;
    for (int c = 0; c < 3; ++c)
      boxesMeet =
        boxesMeet && !(a.Box[2 * c + 1] < b.Box[2 * c] || b.Box[2 * c + 1] < a.Box[2 * c]);
    if (!metAB && boxesMeet && n % 2)
    {
      ++missedWithBoxesMeeting;
      screened += isApart;
    }
  }
  EXPECT_GT(mirrored, 5000);
  EXPECT_GT(apart, 5000);
  EXPECT_GT(mirroredApart, 500); // moved out beyond the bound
  EXPECT_GT(mirroredMet, 500);   // moved in enough to meet
  // Most shifted pairs that miss although their boxes meet are screened by
  // a face plane (the others are separated by edge directions only).
  EXPECT_GT(missedWithBoxesMeeting, 1000);
  EXPECT_GT(screened, missedWithBoxesMeeting / 2);
}

// The vertex-graph clipper (Intersect) against the splitting clipper
// (IntersectBySplitting) on random pairs, a third of them sharing a corner
// and a third sharing a face: same meeting decision, touched faces and seed
// faces, volumes and every mortar entry to rounding.
TEST(Tetrahedra, GraphClipperMatchesSplittingClipper)
{
  std::mt19937 rng(11);
  int met = 0;
  int wellShaped = 0;
  for (int n = 0; n < 5000; ++n)
  {
    double t[4][3];
    double s[4][3];
    RandomPair(rng, 0.8, t, s);
    if (n % 3 == 0) // share a corner
      std::copy(t[0], t[0] + 3, s[0]);
    if (n % 3 == 1) // share a face (the source on either side of it)
      for (int k = 0; k < 3; ++k)
        std::copy(t[k], t[k] + 3, s[k]);
    TetrahedronIntersector::Cell a;
    TetrahedronIntersector::Cell b;
    if (!PreparedPair(t, s, a, b))
      continue;
    const TestMesh m = TwoTetrahedra(t, s);
    TetrahedronIntersector::Piece graph;
    TetrahedronIntersector::Piece split;
    const bool g = TetrahedronIntersector::Intersect(a, b, graph);
    const bool sp = TetrahedronIntersector::IntersectBySplitting(a, b, split);
    ASSERT_EQ(g, sp) << n;
    if (!g)
      continue;
    ++met;
    EXPECT_EQ(graph.TouchedFaces, split.TouchedFaces) << n;
    EXPECT_EQ(graph.SourceFaces, split.SourceFaces) << n;
    for (int k = 0; k < 4; ++k)
      if (graph.TouchedFaces & (1u << k))
        EXPECT_EQ(graph.SeedFace[k], split.SeedFace[k]) << n;
    const double scale = std::min(m.CellVolume(0), m.CellVolume(1));
    EXPECT_NEAR(
      TetrahedronIntersector::Measure(graph), TetrahedronIntersector::Measure(split), 1e-12 * scale)
      << n;
    // The entries of flat cells are ill conditioned (barycentric gradients of
    // size 1/height, squared): compare them on well-shaped pairs.
    if (std::min(m.CellVolume(0), m.CellVolume(1)) < 1e-2)
      continue;
    ++wellShaped;
    double mtsG[4][4] = {}, mttG[4][4] = {}, mtsS[4][4] = {}, mttS[4][4] = {};
    mp::AddPieceBlocks<TetrahedronIntersector, mp::P1Space<3>, mp::P1Space<3>>(
      graph, a, b, mtsG, mttG);
    mp::AddPieceBlocks<TetrahedronIntersector, mp::P1Space<3>, mp::P1Space<3>>(
      split, a, b, mtsS, mttS);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
      {
        EXPECT_NEAR(mtsG[i][j], mtsS[i][j], 1e-12 * scale) << n;
        EXPECT_NEAR(mttG[i][j], mttS[i][j], 1e-12 * scale) << n;
      }
  }
  EXPECT_GT(met, 1500);
  EXPECT_GT(wellShaped, 500);
}

/// The same graph bit for bit (and, unless one comes from the tables and the
/// other from Clip, the same face list).
void ExpectSameGraph(const mp::clipping::VertexGraph& a, const mp::clipping::VertexGraph& b,
  int pair, bool sameFaces = true)
{
  ASSERT_EQ(a.NumberOfVertices, b.NumberOfVertices) << pair;
  if (sameFaces)
    ASSERT_EQ(a.Faces, b.Faces) << pair;
  for (int v = 0; v < a.NumberOfVertices; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_TRUE(SameBits(a.X[v][c], b.X[v][c])) << pair << " " << v;
      ASSERT_EQ(a.Next[v][c], b.Next[v][c]) << pair << " " << v;
      ASSERT_EQ(a.Back[v][c], b.Back[v][c]) << pair << " " << v;
    }
    ASSERT_EQ(a.On[v], b.On[v]) << pair << " " << v;
    ASSERT_EQ(a.Original[v], b.Original[v]) << pair << " " << v;
  }
}

// A graph from the tables is cut into the same tetrahedra, bit for bit, from
// the tables' faces as from a walk of its links (both target shifts).
void ExpectSameDecomposition(const mp::clipping::VertexGraph& graph, int pair)
{
  mp::clipping::VertexGraph walked = graph;
  walked.Faces = nullptr;
  for (int shift : { 0, 4 })
  {
    TetrahedronIntersector::Piece a;
    TetrahedronIntersector::Piece b;
    ASSERT_TRUE(graph.Decompose(shift, 1e-30, a)) << pair;
    ASSERT_TRUE(walked.Decompose(shift, 1e-30, b)) << pair;
    ASSERT_EQ(a.NumberOfTetrahedra, b.NumberOfTetrahedra) << pair;
    ASSERT_EQ(a.TouchedFaces, b.TouchedFaces) << pair;
    ASSERT_EQ(a.SourceFaces, b.SourceFaces) << pair;
    for (int t = 0; t < a.NumberOfTetrahedra; ++t)
    {
      ASSERT_TRUE(SameBits(a.Volume[t], b.Volume[t])) << pair;
      for (int k = 0; k < 4; ++k)
        ASSERT_EQ(a.Corner[t][k], b.Corner[t][k]) << pair;
    }
    ASSERT_TRUE(SameBits(a.M[0][0], b.M[0][0])) << pair;
    if (a.M[0][0] > 0.0) // the other moments are set only then
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
          ASSERT_TRUE(SameBits(a.M[r][c], b.M[r][c])) << pair;
  }
}

// A graph from the tables carries their faces: those a walk finds, in its order.
void ExpectTableFaces(const mp::clipping::VertexGraph& graph, int pair)
{
  ASSERT_NE(graph.Faces, nullptr) << pair;
  mp::clipping::FaceCycles<mp::clipping::VertexGraph::MaxVertices> walked;
  ASSERT_TRUE(graph.WalkFaces(walked)) << pair;
  ASSERT_EQ(graph.Faces->NumberOfFaces, walked.NumberOfFaces) << pair;
  for (int f = 0, at = 0; f < walked.NumberOfFaces; at += walked.Size[f++])
  {
    ASSERT_EQ(graph.Faces->Size[f], walked.Size[f]) << pair;
    for (int i = 0; i < walked.Size[f]; ++i)
      ASSERT_EQ(graph.Faces->Vertex[at + i], walked.Vertex[at + i]) << pair;
  }
  ExpectSameDecomposition(graph, pair);
}

// The first clip from the table of a tetrahedron's cuts against SetTetrahedron
// and Clip, and the second from the table of second cuts against Clip: bit
// for bit the same graph (vertices, order, links, bits, and the faces a walk
// finds) for every pattern of
// corners inside and outside, and refused when a vertex lies on the plane
// (shared corners).
TEST(Tetrahedra, TableCutIsTheClippedGraph)
{
  std::mt19937 rng(5);
  int patterns[16] = {};
  int refused = 0;
  int seconds = 0;
  int secondRefused = 0;
  int cutsBySize[10] = {};
  for (int n = 0; n < 20000; ++n)
  {
    double t[4][3];
    double s[4][3];
    RandomPair(rng, 0.8, t, s);
    if (n % 5 == 0) // a shared corner: on two of the planes
      std::copy(t[1], t[1] + 3, s[2]);
    const TestMesh m = TwoTetrahedra(t, s);
    if (m.CellVolume(0) < 1e-6 || m.CellVolume(1) < 1e-6)
      continue;
    TetrahedronIntersector::Cell a;
    TetrahedronIntersector::Cell b;
    ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 0, a));
    ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 1, b));
    double sides[4][4];
    mp::clipping::FaceSides(a, b, sides); // b's corners against a's planes
    for (int k = 0; k < 4; ++k)
    {
      mp::clipping::VertexGraph table;
      mp::clipping::VertexGraph clip;
      const unsigned cut = table.SetClippedTetrahedron(b, sides, k);
      unsigned pattern = 0;
      bool onPlane = false;
      for (int v = 0; v < 4; ++v)
      {
        pattern |= (sides[k][v] < 0.0 ? 1u : 0u) << v;
        onPlane |= sides[k][v] == 0.0;
      }
      ASSERT_EQ(cut, !onPlane && pattern != 0 && pattern != 15 ? pattern : 0u) << n;
      if (!cut)
      {
        refused += onPlane;
        continue;
      }
      ++patterns[pattern];
      clip.SetTetrahedron(b, sides);
      ASSERT_TRUE(clip.Clip(a.Normal[k], a.X[(k + 1) % 4], 1u << k, sides[k]));
      ExpectSameGraph(table, clip, n, false);
      ExpectTableFaces(table, n);
      // The second cut, by each other plane, from its table.
      for (int l = 0; l < 4; ++l)
      {
        if (l == k)
          continue;
        mp::clipping::VertexGraph second = table;
        mp::clipping::VertexGraph clipped = clip;
        if (!second.ClipSecond(cut, a.Normal[l], a.X[(l + 1) % 4], 1u << l, sides[l]))
        {
          ++secondRefused;
          ExpectSameGraph(second, table, n); // refused: nothing changed
          continue;
        }
        ++seconds;
        ASSERT_TRUE(clipped.Clip(a.Normal[l], a.X[(l + 1) % 4], 1u << l, sides[l]));
        cutsBySize[std::min(clipped.NumberOfVertices, 9)]++;
        ExpectSameGraph(second, clipped, n, false);
        if (second.NumberOfVertices > 0)
          ExpectTableFaces(second, n);
      }
    }
  }
  for (unsigned p = 1; p < 15; ++p)
    EXPECT_GT(patterns[p], 100) << "pattern " << p;
  EXPECT_GT(refused, 1000);
  EXPECT_GT(seconds, 50000);
  EXPECT_GT(secondRefused, 1000); // a shared corner on the second plane
  for (int size : { 0, 4, 6, 8 }) // three links per vertex: an even number
    EXPECT_GT(cutsBySize[size], 100) << size << " vertices";
}

// Every second cut the table holds was made by Cut (none refused): 14 for
// each of the 4 graphs of 4 vertices, 62 for each of the 10 of 6, at most
// 10 vertices each.
TEST(Tetrahedra, EverySecondCutIsInTheTable)
{
  const auto* firsts = mp::clipping::VertexGraph::TetrahedronCuts();
  const auto* seconds = mp::clipping::VertexGraph::SecondCuts();
  int valid = 0;
  for (unsigned first = 1; first < 15; ++first)
  {
    const int n = firsts[first].NumberOfVertices;
    ASSERT_TRUE(n == 4 || n == 6) << first;
    ASSERT_TRUE(firsts[first].HasFaces) << first;
    for (unsigned pattern = 1; pattern + 1 < (1u << n); ++pattern)
    {
      const auto& cut = seconds[64 * first + pattern];
      ASSERT_TRUE(cut.Valid && cut.HasFaces) << first << " " << pattern;
      EXPECT_LE(cut.NumberOfVertices, 10);
      ++valid;
    }
  }
  EXPECT_EQ(valid, 4 * 14 + 10 * 62);
}

// Distances that overflow make crossings of NaN coordinates: the tables
// refuse a NaN distance and Clip decides (a table's graph would differ from
// Clip's there). The unit
// tetrahedron with an infinite side, and a pair of cells of size 1e153.
TEST(Tetrahedra, NonFiniteDistancesGoToTheGeneralClip)
{
  TetrahedronIntersector::Cell unit;
  for (int v = 0; v < 4; ++v)
    for (int a = 0; a < 3; ++a)
      unit.X[v][a] = a + 1 == v ? 1.0 : 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double sides[4][4] = { { nan, -1.0, 1.0, 1.0 }, { 1.0, 1.0, 1.0, -1.0 } };
  mp::clipping::VertexGraph table;
  EXPECT_EQ(table.SetClippedTetrahedron(unit, sides, 0), 0u); // a NaN side: Clip decides
  sides[0][0] = inf;
  const unsigned first = table.SetClippedTetrahedron(unit, sides, 0);
  ASSERT_EQ(first, 2u);
  mp::clipping::VertexGraph clip;
  clip.SetTetrahedron(unit, sides);
  ASSERT_TRUE(clip.Clip(unit.X[0], unit.X[0], 1u, sides[0]));
  const double normal[3] = { 0.0, 0.0, -1.0 };
  const double origin[3] = { 0.0, 0.0, 0.7 };
  mp::clipping::VertexGraph second = table;
  EXPECT_FALSE(second.ClipSecond(first, normal, origin, 2u, sides[1]));
  ExpectSameGraph(second, table, 0);
  const bool a = second.Clip(normal, origin, 2u, sides[1]);
  const bool b = clip.Clip(normal, origin, 2u, sides[1]);
  EXPECT_EQ(a, b);
  if (a && b)
  {
    ASSERT_EQ(second.NumberOfVertices, clip.NumberOfVertices);
    for (int v = 0; v < clip.NumberOfVertices; ++v)
    {
      EXPECT_EQ(second.Next[v][0], clip.Next[v][0]) << v;
      EXPECT_EQ(second.On[v], clip.On[v]) << v;
    }
  }
  const double t[4][3] = { { -8.8659615903853301e151, 1.3737351861116777e153,
                             -6.2358063811403052e-11 },
    { 1.4933079294831653e153, 4.0822521445482421e153, -8.1515972878436932e-11 },
    { -4.342282072354494e153, -5.2625736710033753e153, -8.2984134185736339e-11 },
    { -7.1061873304633826e153, -8.584462237665525e152, 3.5913631141954964e-11 } };
  const double s[4][3] = { { 7.0703255122555918e147, 9.8378489921225355e147, -152.37318194429861 },
    { -2.3276872353371758e147, 5.2557225130186107e147, -327.62743472556309 },
    { -3.1255538271833361e147, 5.426499770920166e147, 0.40042535664874812 },
    { 5.4702413361866813e147, 9.7967594056295923e147, -229.08259151887157 } };
  // A pair with coordinates of 1e308: its NaN distances must stop Cut's
  // face walk before it reads outside its array (a crash at -O3); the
  // splitting clipper decides.
  const double u[4][3] = { { 0.60115844048958444, -0.089715186159807336, 0.41011851223159956 },
    { -0.48584992727037024, 0.5195063096477408, 0.52825141128000008 },
    { -1e308, 0.89766054637425619, 0.094802381003500802 },
    { -0.50018268323453863, 0.70732960362897757, 0.43421638639004745 } };
  const double w[4][3] = { { 0.39658726809896888, -0.49184495718289317, -0.73044769441539725 },
    { -0.45407268534160905, -0.34660860834319496, -0.78130087645533797 },
    { 0.75730376094773466, 0.49697217086228673, 0.50330873228990625 },
    { -0.63306918687697722, -0.53496511870158447, 1e308 } };
  {
    const TestMesh m = TwoTetrahedra(u, w);
    int prepared = 0;
    for (int roles = 0; roles < 2; ++roles)
    {
      TetrahedronIntersector::Cell x;
      TetrahedronIntersector::Cell y;
      if (!TetrahedronIntersector::Prepare(m.View(false), roles, x) ||
        !TetrahedronIntersector::Prepare(m.View(false), 1 - roles, y))
        continue;
      ++prepared;
      TetrahedronIntersector::Piece piece;
      TetrahedronIntersector::Intersect(x, y, piece); // must not crash (nor read out of bounds)
    }
    EXPECT_EQ(prepared, 2);
  }
  {
    const TestMesh m = TwoTetrahedra(t, s);
    for (int roles = 0; roles < 2; ++roles)
    {
      TetrahedronIntersector::Cell x;
      TetrahedronIntersector::Cell y;
      ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), roles, x));
      ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 1 - roles, y));
      TetrahedronIntersector::Piece piece;
      EXPECT_FALSE(TetrahedronIntersector::Intersect(x, y, piece)) << roles;
      EXPECT_FALSE(std::isnan(TetrahedronIntersector::Measure(piece))) << roles;
    }
  }
}

// The intersection volume of two tetrahedra in floating-point type R: `s`
// split by each face plane of `t` into at most three tetrahedra per
// tetrahedron (the reference clipper's construction, independent of the
// kernel's code), the planes and sides computed in R.
template <class R>
R SplitVolumeIn(const double t[4][3], const double s[4][3])
{
  using P = std::array<R, 3>;
  auto sub = [](const P& a, const P& b) { return P{ a[0] - b[0], a[1] - b[1], a[2] - b[2] }; };
  auto dot = [](const P& a, const P& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  auto cross = [](const P& a, const P& b) {
    return P{ a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
  };
  using Tet = std::array<P, 4>;
  std::vector<Tet> current(1);
  P x[4];
  for (int v = 0; v < 4; ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      current[0][v][c] = s[v][c];
      x[v][c] = t[v][c];
    }
  }
  for (int k = 0; k < 4; ++k)
  {
    const P& a = x[(k + 1) % 4];
    P n = cross(sub(x[(k + 2) % 4], a), sub(x[(k + 3) % 4], a));
    if (dot(n, sub(x[k], a)) < 0)
      n = P{ -n[0], -n[1], -n[2] };
    std::vector<Tet> next;
    for (const Tet& tet : current)
    {
      R d[4];
      int in[4], out[4], nin = 0, nout = 0;
      for (int v = 0; v < 4; ++v)
      {
        d[v] = dot(n, sub(tet[v], a));
        if (d[v] >= 0)
          in[nin++] = v;
        else
          out[nout++] = v;
      }
      if (nout == 0)
      {
        next.push_back(tet);
        continue;
      }
      if (nin == 0)
        continue;
      auto cut = [&](int p, int q) {
        const R u = d[p] / (d[p] - d[q]);
        P r;
        for (int c = 0; c < 3; ++c)
          r[c] = tet[p][c] + u * (tet[q][c] - tet[p][c]);
        return r;
      };
      if (nin == 1)
      {
        next.push_back({ tet[in[0]], cut(in[0], out[0]), cut(in[0], out[1]), cut(in[0], out[2]) });
        continue;
      }
      P p[3], q[3];
      if (nin == 3)
      {
        for (int j = 0; j < 3; ++j)
        {
          p[j] = tet[in[j]];
          q[j] = cut(in[j], out[0]);
        }
      }
      else
      {
        p[0] = tet[in[0]];
        p[1] = cut(in[0], out[0]);
        p[2] = cut(in[0], out[1]);
        q[0] = tet[in[1]];
        q[1] = cut(in[1], out[0]);
        q[2] = cut(in[1], out[1]);
      }
      next.push_back({ p[0], p[1], p[2], q[0] });
      next.push_back({ p[1], p[2], q[0], q[1] });
      next.push_back({ p[2], q[0], q[1], q[2] });
    }
    current.swap(next);
  }
  R volume = 0;
  for (const Tet& tet : current)
  {
    const R six = dot(sub(tet[1], tet[0]), cross(sub(tet[2], tet[0]), sub(tet[3], tet[0])));
    volume += (six < 0 ? -six : six) / 6;
  }
  return volume;
}

// Source edges nearly in a target face's plane (two source corners put on
// the plane, then moved off it by 2^-54 to 2^-38, so that the edge between
// them crosses it at a tiny angle; a third corner often onto another
// plane): the intersection volume against a binary128 oracle, both roles,
// to 1e-13 of the pair's extent cubed. Unlike the 2D crossings of nearly
// collinear edges, a crossing misplaced along an edge that lies nearly in
// the plane moves the piece's boundary only within that thin gap: the
// clipper, with its filtered face sides, is within 6e-17 here (and still
// within 7e-17 with rounded sides only, no exact fallback: the volume does
// not depend on where such a crossing falls; a 1e-9 relative error in the
// crossings fails it).
TEST(Tetrahedra, NearlyCoplanarEdgesKeepTheExactVolume)
{
#if !defined(__SIZEOF_FLOAT128__)
  GTEST_SKIP() << "no binary128 type for the oracle";
#else
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto pick = [&rng](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  int checked = 0;
  int nearlyCoplanar = 0;
  for (int n = 0; n < 20000; ++n)
  {
    double t[4][3];
    double s[4][3];
    for (auto& x : t)
      for (double& c : x)
        c = unit(rng);
    for (auto& x : s)
      for (double& c : x)
        c = unit(rng);
    // Two source corners onto the plane of target face k (barycentric
    // weights beyond the face too), a third often onto another face.
    const int k = pick(4);
    const int moved = 2 + pick(2);
    for (int j = 0; j < moved; ++j)
    {
      const int plane = j < 2 ? k : pick(4);
      const double* pa = t[(plane + 1) % 4];
      const double* pb = t[(plane + 2) % 4];
      const double* pc = t[(plane + 3) % 4];
      const double wb = 1.6 * unit(rng) - 0.3;
      const double wc = 1.6 * unit(rng) - 0.3;
      for (int d = 0; d < 3; ++d)
        s[j][d] = pa[d] + wb * (pb[d] - pa[d]) + wc * (pc[d] - pa[d]);
      // Off the plane by 2^-54 to 2^-38 (log-uniform): from within the
      // exact predicates' reach to beyond the filters' bounds.
      for (double& x : s[j])
        x += (pick(2) ? 1.0 : -1.0) * std::ldexp(unit(rng), -38 - pick(17));
    }
    const TestMesh m = TwoTetrahedra(t, s);
    if (m.CellVolume(0) < 1e-3 || m.CellVolume(1) < 1e-3)
      continue;
    double extent = 0.0;
    for (int d = 0; d < 3; ++d)
    {
      double lo = t[0][d], hi = t[0][d];
      for (int v = 0; v < 4; ++v)
      {
        lo = std::min({ lo, t[v][d], s[v][d] });
        hi = std::max({ hi, t[v][d], s[v][d] });
      }
      extent = std::max(extent, hi - lo);
    }
    bool coplanar = false;
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
      {
        const double o = mp::Orient3D(t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4], s[j]);
        coplanar |= o != 0.0 && std::fabs(o) < 1e-12 * extent * extent * extent;
      }
    nearlyCoplanar += coplanar;
    const double expected = static_cast<double>(SplitVolumeIn<__float128>(t, s));
    // Below the touching threshold the filter says no volume: compare above it.
    const double small = 1e-13 * std::min(m.CellVolume(0), m.CellVolume(1));
    for (int roles = 0; roles < 2; ++roles)
    {
      TetrahedronIntersector::Cell a;
      TetrahedronIntersector::Cell b;
      ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), roles, a));
      ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 1 - roles, b));
      TetrahedronIntersector::Piece piece;
      // Pieces below 1e-13 of the smaller cell count as touching: no volume.
      const double volume = TetrahedronIntersector::Intersect(a, b, piece)
        ? TetrahedronIntersector::Measure(piece)
        : 0.0;
      const double error = expected < small && volume == 0.0
        ? 0.0
        : std::fabs(volume - expected) / (extent * extent * extent);
      EXPECT_LE(error, 1e-13) << "pair " << n << (roles ? ", roles swapped" : "") << ": " << volume
                              << " against " << expected;
      ++checked;
    }
  }
  EXPECT_GT(checked, 20000);
  EXPECT_GT(nearlyCoplanar, 10000);
#endif
}

TEST(Tetrahedra, MortarEntriesOfIdenticalTetrahedra)
{
  const double t[4][3] = { { 0.1, 0, 0 }, { 1.3, 0.2, 0 }, { 0.2, 1.1, 0.1 }, { 0, 0.3, 0.9 } };
  const TestMesh m = TwoTetrahedra(t, t);
  TetrahedronIntersector::Cell a;
  TetrahedronIntersector::Cell b;
  ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 0, a));
  ASSERT_TRUE(TetrahedronIntersector::Prepare(m.View(false), 1, b));
  TetrahedronIntersector::Piece p;
  ASSERT_TRUE(TetrahedronIntersector::Intersect(a, b, p));
  double mts[4][4] = {};
  double mtt[4][4] = {};
  const double v =
    mp::AddPieceBlocks<TetrahedronIntersector, mp::P1Space<3>, mp::P1Space<3>>(p, a, b, mts, mtt);
  EXPECT_NEAR(v, m.CellVolume(0), 1e-15);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
    {
      EXPECT_NEAR(mts[i][j], v / 20.0 * (1 + (i == j)), 1e-15);
      EXPECT_NEAR(mtt[i][j], v / 20.0 * (1 + (i == j)), 1e-15);
    }
}

TEST(Tetrahedra, IdenticalAndNestedMeshes)
{
  const TestMesh a = mptest::CubeMesh(4, 3, 3, 0.15, 1);
  Searches same(a, a);
  same.ExpectSamePairs("identical");
  same.ExpectCompleteCover(a, "identical");

  // A target whose cells coincide with the inner cells of a larger source:
  // the seeds pass through the shared faces, so the whole target needs one
  // walk to start and no locator query (the source boundary is never met).
  const TestMesh inner = mptest::CubeMesh(4, 4, 4, 0.0, 1);
  TestMesh outer = mptest::CubeMesh(8, 8, 8, 0.0, 1, 2.0);
  mptest::Move3D(outer, 0, 0, 1, -0.5, -0.5, -0.5);
  Searches nested(inner, outer);
  nested.ExpectSamePairs("coinciding cells");
  nested.ExpectCompleteCover(inner, "coinciding cells");
  EXPECT_EQ(nested.FrontStats.SeedWalks, 1);
  EXPECT_EQ(nested.FrontStats.LocatorQueries, 0);
  EXPECT_EQ(nested.Front.Pairs.size(), size_t(inner.NumberOfCells()));

  // Unjittered 2x refinement: vertices on faces and edges of the coarse mesh.
  const TestMesh coarse = mptest::CubeMesh(2, 2, 2, 0.0, 2);
  const TestMesh fine = mptest::CubeMesh(4, 4, 4, 0.0, 3);
  Searches cf(coarse, fine);
  cf.ExpectSamePairs("coarse <- fine");
  cf.ExpectCompleteCover(coarse, "coarse <- fine");
  Searches fc(fine, coarse);
  fc.ExpectSamePairs("fine <- coarse");
  fc.ExpectCompleteCover(fine, "fine <- coarse");
}

TEST(Tetrahedra, RandomNonMatchingMeshes)
{
  std::mt19937 rng(5);
  for (int n = 0; n < 40; ++n)
  {
    const TestMesh a = mptest::CubeMesh(1 + n % 4, 2 + n % 3, 1 + n % 5, 0.15, rng());
    const TestMesh b = mptest::CubeMesh(2 + n % 5, 1 + n % 4, 2 + n % 3, 0.15, rng());
    Searches s(a, b);
    s.ExpectSamePairs("case " + std::to_string(n));
    s.ExpectCompleteCover(a, "case " + std::to_string(n));
    // Same domain: started by a walk, re-seeded among boundary cells only.
    EXPECT_EQ(s.FrontStats.FullLocatorQueries, 0) << "case " << n;
    if (HasFatalFailure())
      return;
  }
}

TEST(Tetrahedra, FailedSeedsAreRepairedByAWalk)
{
  // The benchmark's pair at 10^5 cells: a few seeds passed on through faces
  // do not meet their cell (3D seeds rest on face contacts above a rounding
  // threshold); a short walk from them finds one that does, so the whole
  // search asks no query among all source cells, and misses nothing.
  const TestMesh target = mptest::CubeMesh(26, 26, 26, 0.15, 7);
  const TestMesh source = mptest::CubeMesh(27, 26, 25, 0.15, 8);
  mptest::PairRecorder<TetrahedronIntersector> front;
  mp::SearchStatistics stats;
  mp::BoxGridLocator locator(source.View());
  mp::AdvancingFrontSearch<TetrahedronIntersector>(
    target.View(), source.View(), locator, front, stats);
  EXPECT_EQ(stats.FullLocatorQueries, 0);
  EXPECT_GT(stats.SeedWalks, 1); // the first seed, and at least one repair
  std::vector<double> covered(static_cast<size_t>(target.NumberOfCells()), 0.0);
  for (const auto& p : front.Pairs)
    covered[std::get<0>(p)] += std::get<2>(p);
  for (Index c = 0; c < target.NumberOfCells(); ++c)
  {
    ASSERT_NEAR(covered[c], target.CellVolume(c), 1e-12 * target.CellVolume(c)) << "cell " << c;
  }
}

TEST(Tetrahedra, SnappedVerticesRotatedAndScaled)
{
  // Two jittered meshes of the same lattice with about half of the source's
  // interior points moved exactly onto the target's (so vertices, edges and
  // faces coincide here and there, and the boundaries match), then both
  // rotated, scaled and translated alike (coinciding points stay so).
  std::mt19937 rng(31);
  for (int n = 0; n < 30; ++n)
  {
    TestMesh target = mptest::CubeMesh(3, 2 + n % 2, 3, 0.15, rng());
    TestMesh source = mptest::CubeMesh(3, 2 + n % 2, 3, 0.15, rng());
    for (size_t i = 0; i < source.Points.size(); i += 3)
    {
      if (rng() % 2)
      {
        std::copy(
          target.Points.begin() + i, target.Points.begin() + i + 3, source.Points.begin() + i);
      }
    }
    for (Index c = 0; c < source.NumberOfCells(); ++c)
    {
      ASSERT_GT(source.CellVolume(c), 0.0);
    }
    const double angle = 0.7 * n;
    const double tilt = 0.3 * n;
    const double scale = std::pow(10.0, (n % 7) - 3);
    for (TestMesh* m : { &target, &source })
    {
      mptest::Move3D(*m, angle, tilt, scale, 10.0 * scale * (n % 3), -2.0 * scale, 0.5 * scale);
    }
    target.Finish();
    source.Finish();
    Searches s(target, source);
    s.ExpectSamePairs("case " + std::to_string(n));
    s.ExpectCompleteCover(target, "case " + std::to_string(n));
    if (HasFatalFailure())
      return;
  }
}

TEST(Tetrahedra, RotatedPartialOverlaps)
{
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n = 0; n < 40; ++n)
  {
    const TestMesh a = mptest::CubeMesh(2 + n % 3, 3, 2, 0.15, rng());
    TestMesh b = mptest::CubeMesh(3, 2 + n % 4, 2, 0.15, rng());
    mptest::Move3D(
      b, 6.3 * u(rng), 3.1 * u(rng), 0.5 + u(rng), u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    Searches s(a, b);
    s.ExpectSamePairs("case " + std::to_string(n));
    if (HasFatalFailure())
      return;
  }
}

TEST(Tetrahedra, ProjectionIsExactOnLinearFieldsAndConservative)
{
  std::mt19937 rng(7);
  for (int n = 0; n < 8; ++n)
  {
    const TestMesh target = mptest::CubeMesh(3 + n % 2, 3, 4, 0.15, rng());
    const TestMesh source = mptest::CubeMesh(5, 4 + n % 3, 3, 0.15, rng());
    mp::BoxGridLocator locator(source.View());
    mp::MortarOperator projector;
    ASSERT_TRUE(projector.Build(target.View(), source.View(), &locator)) << projector.GetError();
    EXPECT_EQ(projector.GetNumberOfValid(), target.NumberOfPoints());
    EXPECT_NEAR(projector.GetCoveredMeasure(), 1.0, 1e-13);
    std::vector<double> ut(static_cast<size_t>(target.NumberOfPoints()));
    const auto lin = mptest::Sample3D(source, Linear3);
    projector.Apply(lin.data(), 1, ut.data(), std::nan(""));
    const auto exact = mptest::Sample3D(target, Linear3);
    for (Index i = 0; i < target.NumberOfPoints(); ++i)
      ASSERT_NEAR(ut[i], exact[i], 1e-12) << "case " << n << " point " << i;
    const auto smooth = mptest::Sample3D(source, Smooth3);
    projector.Apply(smooth.data(), 1, ut.data(), std::nan(""));
    const double is = source.Integral(smooth);
    EXPECT_NEAR(target.Integral(ut), is, 1e-13 * std::fabs(is));
  }
}

TEST(Tetrahedra, MixedDimensionsAreRejected)
{
  const TestMesh tets = mptest::CubeMesh(2, 2, 2, 0.1, 8);
  const TestMesh tris = mptest::GridMesh(3, 3, 0.1, 9);
  mp::BoxGridLocator locator(tris.View());
  mp::MortarOperator projector;
  EXPECT_FALSE(projector.Build(tets.View(), tris.View(), &locator));
  EXPECT_NE(projector.GetError().find("different dimensions"), std::string::npos);
}

TEST(Tetrahedra, TranslatedAndScaledMeshes)
{
  std::mt19937 rng(10);
  for (int n = 0; n < 6; ++n)
  {
    const TestMesh a = mptest::CubeMesh(2 + n % 2, 3, 2, 0.15, rng());
    const TestMesh b = mptest::CubeMesh(3, 2, 2 + n % 3, 0.15, rng());
    for (const auto& motion :
      { std::make_pair(1.0, 1e6), std::make_pair(1e-6, 0.0), std::make_pair(1e6, 0.0) })
    {
      TestMesh t = a;
      TestMesh s = b;
      mptest::Move3D(t, 0, 0, motion.first, motion.second, -motion.second, motion.second);
      mptest::Move3D(s, 0, 0, motion.first, motion.second, -motion.second, motion.second);
      Searches moved(t, s);
      const std::string what = "case " + std::to_string(n) + " scale " +
        std::to_string(motion.first) + " shift " + std::to_string(motion.second);
      moved.ExpectSamePairs(what);
      moved.ExpectCompleteCover(t, what, motion.second != 0.0 ? 1e-7 : 1e-12);
      Searches original(a, b);
      EXPECT_EQ(moved.Front.Pairs.size(), original.Front.Pairs.size()) << what;
      if (HasFatalFailure())
        return;
    }
  }
}
