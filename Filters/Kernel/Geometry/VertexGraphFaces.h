// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file VertexGraphFaces.h
 * @brief VertexGraph's faces, and the piece they make: the tetrahedra from
 *        vertex 0 to the faces' triangles, with their moments (part of
 *        VertexGraph.h, which includes it: include that).
 *
 * The faces are never stored while clipping: they follow from the links
 * (the face to the left of a -> b goes on at b), so they are walked once
 * the clip is done, or read from the tables when the graph is one of
 * theirs. Decompose then fans them from vertex 0 into tetrahedra and sums
 * their moments (PieceMoments.h), and notes which target faces the piece
 * touches with positive area.
 */
#ifndef MeshProjection_Kernel_VertexGraphFaces_h
#define MeshProjection_Kernel_VertexGraphFaces_h

#include "Geometry/PieceMoments.h"
#include "Geometry/VertexGraph.h"
#include "Mesh/Vec3.h"

#include <algorithm>

namespace mp
{
namespace clipping
{
template <class Visit>
inline bool VertexGraph::WalkFaces(Visit&& visit) const
{
  // The links not yet walked as bits (link j of vertex v: bit 3v + j),
  // the next face started at the lowest: the order of a loop over
  // vertices and links, without its mispredicted tests per link.
  static_assert(3 * MaxVertices <= 192, "three words of link bits");
  const int n = this->NumberOfVertices;
  unsigned long long open[3];
  for (int w = 0; w < 3; ++w)
  {
    const int in = std::min(64, std::max(0, 3 * n - 64 * w));
    open[w] = in == 64 ? ~0ull : (1ull << in) - 1;
  }
  int cycle[MaxVertices];
  for (int word = 0;;)
  {
    while (word < 3 && open[word] == 0)
    {
      ++word;
    }
    if (word == 3)
    {
      break;
    }
    const int start = 64 * word + __builtin_ctzll(open[word]);
    int size = 0;
    int a = start / 3;
    int slot = start % 3;
    bool holdsApex = false;
    unsigned common = 0xFFu;
    for (int at = start;;)
    {
      const unsigned long long bit = 1ull << (at & 63);
      if (size == MaxVertices || !(open[at >> 6] & bit))
      {
        return false;
      }
      open[at >> 6] &= ~bit;
      cycle[size++] = a;
      holdsApex |= a == 0;
      common &= this->On[a];
      const int b = this->Next[a][slot];
      const int back = this->Back[a][slot];
      slot = back == 2 ? 0 : back + 1;
      a = b;
      at = 3 * a + slot;
      if (at == start)
      {
        break;
      }
      if (a < 0 || a >= n)
      {
        return false; // not a link of the graph
      }
    }
    if (!visit(cycle, size, holdsApex, common))
    {
      return false;
    }
  }
  return true;
}

template <int V>
inline bool VertexGraph::WalkFaces(FaceCycles<V>& faces) const
{
  faces.NumberOfFaces = 0;
  int used = 0;
  return this->WalkFaces([&](const int* cycle, int size, bool, unsigned) {
    if (faces.NumberOfFaces == V / 2 + 2 || used + size > 3 * V)
    {
      return false;
    }
    faces.Size[faces.NumberOfFaces++] = static_cast<signed char>(size);
    for (int i = 0; i < size; ++i)
    {
      faces.Vertex[used++] = static_cast<signed char>(cycle[i]);
    }
    return true;
  });
}

inline bool VertexGraph::Decompose(
  int targetShift, double minArea2, TetrahedronIntersector::Piece& piece) const
{
  piece.NumberOfTetrahedra = 0;
  piece.TouchedFaces = 0;
  piece.SourceFaces = 0;
  piece.M[0][0] = 0.0;
  const int n = this->NumberOfVertices;
  if (n == 0)
  {
    return true;
  }
  // The moments about vertex 0, summed tetrahedron by tetrahedron as
  // TetrahedronIntersector::SumMoments does (the same operations: vertex
  // 0's offset is zero), from the edges the volumes take anyway.
  std::copy(this->X[0], this->X[0] + 3, piece.Origin);
  double m0 = 0.0;
  double m1[3] = { 0.0, 0.0, 0.0 };
  double m2[3][3] = { { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 0.0 }, { 0.0, 0.0, 0.0 } };
  unsigned any = 0;
  for (int v = 0; v < n; ++v)
  {
    any |= this->On[v];
  }
  piece.SourceFaces = (any >> (4 - targetShift)) & 15u; // the other cell's bits
  auto face = [&](const auto* cycle, int size, bool holdsApex, unsigned common) {
    const unsigned target = (common >> targetShift) & 15u;
    if (size < 3 || (holdsApex && !(target & ~piece.TouchedFaces)))
    {
      return true;
    }
    // Only a face on a target face not yet known touched needs its area.
    const bool needArea = (target & ~piece.TouchedFaces) != 0;
    Vec area = { 0.0, 0.0, 0.0 };
    for (int i = 1; i + 1 < size; ++i)
    {
      const double* corners[4] = { this->X[0], this->X[cycle[0]], this->X[cycle[i]],
        this->X[cycle[i + 1]] };
      if (needArea)
      {
        Vec e, f, g;
        Sub(corners[2], corners[1], e);
        Sub(corners[3], corners[1], f);
        Cross(e, f, g);
        for (int c = 0; c < 3; ++c)
        {
          area[c] += g[c];
        }
      }
      if (holdsApex)
      {
        continue;
      }
      Vec p[3]; // corners 1-3 about corner 0
      for (int k = 0; k < 3; ++k)
      {
        Sub(corners[k + 1], corners[0], p[k]);
      }
      Vec normal;
      Cross(p[1], p[2], normal);
      const double six = Dot(p[0], normal); // SixVolume
      if (six == 0.0)
      {
        continue;
      }
      if (piece.NumberOfTetrahedra == TetrahedronIntersector::MaxTetrahedra)
      {
        return false;
      }
      const int t = piece.NumberOfTetrahedra++;
      piece.Corner[t][0] = 0;
      piece.Corner[t][1] = cycle[0];
      piece.Corner[t][2] = cycle[i];
      piece.Corner[t][3] = cycle[i + 1];
      piece.Volume[t] = six / 6.0;
      AddTetrahedronMoments(piece.Volume[t], p, m0, m1, m2);
    }
    if (needArea && Dot(area, area) > minArea2)
    {
      piece.TouchedFaces |= target;
    }
    return true;
  };
  if (const TableFaces* faces = this->Faces)
  {
    // A graph of the tables: its faces as a walk finds them.
    const signed char* cycle = faces->Vertex;
    for (int f = 0; f < faces->NumberOfFaces; cycle += faces->Size[f++])
    {
      bool holdsApex = false;
      unsigned common = 0xFFu;
      for (int i = 0; i < faces->Size[f]; ++i)
      {
        holdsApex |= cycle[i] == 0;
        common &= this->On[cycle[i]];
      }
      if (!face(cycle, faces->Size[f], holdsApex, common))
      {
        return false;
      }
    }
  }
  else if (!this->WalkFaces(face))
  {
    return false;
  }
  // The tetrahedra's corners: the vertices, one contiguous block.
  std::copy(&this->X[0][0], &this->X[0][0] + 3 * n, &piece.Points[0][0]);
  SetMoments(m0, m1, m2, piece);
  return true;
}
} // namespace clipping
} // namespace mp

#endif
