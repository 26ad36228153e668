// SPDX-License-Identifier: BSD-3-Clause
// 3D: the vertex graph's last cut, which leaves the clipped vertices in place
// (Dead) instead of moving the others down, gives Decompose the same piece
// bit for bit: the same tetrahedra (corners, volumes), moments, origin and
// faces, as the compacted graph.
#include "Geometry/TetrahedronClipping.h"
#include "Geometry/TetrahedronIntersector.h"

#include "TetrahedronPairs.h"

#include <gtest/gtest.h>

#include <random>

using mp::TetrahedronIntersector;
using mp::clipping::VertexGraph;
using mptest::PreparedPair;
using mptest::RandomPair;
using mptest::SameBits;

namespace
{
/// b clipped by every plane of a that cuts it, in face order, the last cut
/// compacted or not; false when a clip fails.
bool ClipAll(const TetrahedronIntersector::Cell& a, const TetrahedronIntersector::Cell& b,
  const double (&sides)[4][4], bool lastInPlace, VertexGraph& graph)
{
  graph.SetTetrahedron(b, sides);
  int cutting[4];
  int n = 0;
  for (int k = 0; k < 4; ++k)
    if (sides[k][0] < 0.0 || sides[k][1] < 0.0 || sides[k][2] < 0.0 || sides[k][3] < 0.0)
      cutting[n++] = k;
  for (int i = 0; i < n && graph.NumberOfVertices > 0; ++i)
  {
    const int k = cutting[i];
    if (!graph.Clip(a.Normal[k], a.X[(k + 1) % 4], 1u << k, sides[k], lastInPlace && i + 1 == n))
      return false;
  }
  return true;
}
} // namespace

TEST(VertexGraph, LastCutInPlaceDecomposesAsTheCompactedGraph)
{
  std::mt19937 rng(11);
  int inPlace = 0;
  int pieces = 0;
  for (int pair = 0; pair < 20000; ++pair)
  {
    double t[4][3];
    double s[4][3];
    RandomPair(rng, 0.8, t, s);
    TetrahedronIntersector::Cell a;
    TetrahedronIntersector::Cell b;
    if (!PreparedPair(t, s, a, b))
      continue;
    double sides[4][4];
    mp::clipping::FaceSides(a, b, sides);
    VertexGraph compacted;
    VertexGraph kept;
    const bool clipped = ClipAll(a, b, sides, false, compacted);
    ASSERT_EQ(ClipAll(a, b, sides, true, kept), clipped) << pair;
    if (!clipped || compacted.NumberOfVertices == 0)
      continue;
    inPlace += kept.Dead != 0;
    for (int shift : { 0, 4 })
    {
      TetrahedronIntersector::Piece p;
      TetrahedronIntersector::Piece q;
      ASSERT_TRUE(compacted.Decompose(shift, 1e-30, p)) << pair;
      ASSERT_TRUE(kept.Decompose(shift, 1e-30, q)) << pair;
      ASSERT_EQ(p.NumberOfTetrahedra, q.NumberOfTetrahedra) << pair;
      ASSERT_EQ(p.TouchedFaces, q.TouchedFaces) << pair;
      ASSERT_EQ(p.SourceFaces, q.SourceFaces) << pair;
      for (int t = 0; t < p.NumberOfTetrahedra; ++t)
      {
        ASSERT_TRUE(SameBits(p.Volume[t], q.Volume[t])) << pair;
        for (int k = 0; k < 4; ++k)
          for (int c = 0; c < 3; ++c)
            ASSERT_TRUE(SameBits(p.Points[p.Corner[t][k]][c], q.Points[q.Corner[t][k]][c])) << pair;
      }
      ASSERT_TRUE(SameBits(p.M[0][0], q.M[0][0])) << pair;
      if (!(p.M[0][0] > 0.0)) // the other moments and the origin are set only then
        continue;
      ++pieces;
      for (int c = 0; c < 3; ++c)
        ASSERT_TRUE(SameBits(p.Origin[c], q.Origin[c])) << pair;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
          ASSERT_TRUE(SameBits(p.M[r][c], q.M[r][c])) << pair;
    }
  }
  EXPECT_GT(inPlace, 1000); // last cuts that left vertices in place
  EXPECT_GT(pieces, 2000);
}
