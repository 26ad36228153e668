// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file VertexGraphFaces.h
 * @brief VertexGraph's faces, and the piece they make: the tetrahedra from
 *        its first vertex to the faces' triangles, with their moments (part of
 *        VertexGraph.h, which includes it: include that).
 *
 * The faces are never stored while clipping: they follow from the links
 * (the face to the left of a -> b goes on at b), so they are walked once
 * the clip is done, or read from the tables when the graph is one of
 * theirs. Decompose then fans them from the first vertex (the apex: 0, or
 * after a last cut that left vertices Dead the first one not) into
 * tetrahedra and sums
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
  // Most graphs have at most 21 vertices: their links' bits fit one word.
  return this->NumberOfVertices <= 21 ? this->WalkFacesIn<1>(visit) : this->WalkFacesIn<3>(visit);
}

template <int W, class Visit>
inline bool VertexGraph::WalkFacesIn(Visit& visit) const
{
  // The links not yet walked as bits (link j of vertex v: bit 3v + j),
  // the next face started at the lowest: the order of a loop over
  // vertices and links, without its mispredicted tests per link.
  static_assert(W == 1 || W == 3, "one word of link bits, or all three");
  static_assert(3 * MaxVertices <= 192, "three words of link bits");
  const int n = this->NumberOfVertices;
  const signed char* next = &this->Next[0][0]; // by link 3v + j
  const signed char* back = &this->Back[0][0];
  unsigned long long open[W];
  for (int w = 0; w < W; ++w)
  {
    const int in = std::min(64, std::max(0, 3 * n - 64 * w));
    open[w] = in == 64 ? ~0ull : (1ull << in) - 1;
  }
  for (unsigned long long dead = this->Dead; dead != 0; dead &= dead - 1)
  {
    // Their links are never walked (no vertex of the graph links to them).
    const int v = __builtin_ctzll(dead);
    if (W == 1)
    {
      open[0] &= ~(7ull << (3 * v));
      continue;
    }
    for (int at = 3 * v; at < 3 * v + 3; ++at)
    {
      open[at >> 6] &= ~(1ull << (at & 63));
    }
  }
  const int apex = __builtin_ctzll(~this->Dead); // the first vertex of the graph
  // Each step takes a link still open: a walk has at most 3n.
  int cycle[3 * MaxVertices];
  for (int word = 0;;)
  {
    while (word < W && open[word] == 0)
    {
      ++word;
    }
    if (word == W)
    {
      break;
    }
    const int start = 64 * word + __builtin_ctzll(open[word]);
    int size = 0;
    int a = start / 3;
    // A face holds the apex (the first vertex) when it has one of its
    // links, the lowest: then the face starts there.
    const bool holdsApex = a == apex;
    unsigned common = 0xFFu;
    for (int at = start;;)
    {
      unsigned long long& bits = open[W == 1 ? 0 : at >> 6];
      const unsigned long long bit = 1ull << (at & 63);
      if (!(bits & bit))
      {
        return false;
      }
      bits &= ~bit;
      cycle[size++] = a;
      common &= this->On[a];
      const int b = next[at];
      if (static_cast<unsigned>(b) >= static_cast<unsigned>(n))
      {
        return false; // not a link of the graph
      }
      // The face goes on at b from the link after the one back to a.
      const int slot = back[at] == 2 ? 0 : back[at] + 1;
      a = b;
      at = 3 * b + slot;
      if (at == start)
      {
        break;
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
  // The vertices about the apex, the first vertex (0 but after a last
  // cut, Dead): the edges of the fans' tetrahedra, for their volumes here
  // and their moments after the walk.
  const int apex = __builtin_ctzll(~this->Dead);
  std::copy(this->X[apex], this->X[apex] + 3, piece.Origin);
  double about0[MaxVertices][3];
  unsigned any = 0;
  for (int v = 0; v < n; ++v)
  {
    Sub(this->X[v], this->X[apex], about0[v]);
    any |= this->On[v]; // (0 for Dead vertices)
  }
  piece.SourceFaces = (any >> (4 - targetShift)) & 15u; // the other cell's bits
  // Always inlined, at both calls: called, its captures lived in memory.
  auto face = [&](const auto* cycle, int size, bool holdsApex, unsigned common)
    __attribute__((always_inline))
  {
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
      if (needArea)
      {
        Vec e, f, g;
        Sub(this->X[cycle[i]], this->X[cycle[0]], e);
        Sub(this->X[cycle[i + 1]], this->X[cycle[0]], f);
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
      Vec normal;
      Cross(about0[cycle[i]], about0[cycle[i + 1]], normal);
      const double six = Dot(about0[cycle[0]], normal); // SixVolume
      if (six == 0.0)
      {
        continue;
      }
      if (piece.NumberOfTetrahedra == TetrahedronIntersector::MaxTetrahedra)
      {
        return false;
      }
      const int t = piece.NumberOfTetrahedra++;
      piece.Corner[t][0] = apex;
      piece.Corner[t][1] = cycle[0];
      piece.Corner[t][2] = cycle[i];
      piece.Corner[t][3] = cycle[i + 1];
      piece.Volume[t] = six / 6.0;
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
      // (Every face of the tables has at least three vertices: MakeCut.)
      const int size = faces->Size[f];
      unsigned common = this->On[cycle[0]] & this->On[cycle[1]] & this->On[cycle[2]];
      for (int i = 3; i < size; ++i)
      {
        common &= this->On[cycle[i]];
      }
      // As walked: a face holding the apex (0 here) starts at it.
      if (!face(cycle, size, cycle[0] == 0, common))
      {
        return false;
      }
    }
  }
  else if (!this->WalkFaces(face))
  {
    return false;
  }
  // The tetrahedra's corners: the vertices, one contiguous block (Dead
  // ones too: no tetrahedron names them).
  std::copy(&this->X[0][0], &this->X[0][0] + 3 * n, &piece.Points[0][0]);
  // The moments about the apex, summed tetrahedron by tetrahedron as
  // TetrahedronIntersector::SumMoments does (the same operations: the
  // apex's offset is zero). After the walk, apart from it: within it they
  // left the walk too few registers.
  MomentSums sums;
  for (int t = 0; t < piece.NumberOfTetrahedra; ++t)
  {
    const int(&corner)[4] = piece.Corner[t];
    const double* p[3] = { about0[corner[1]], about0[corner[2]], about0[corner[3]] };
    AddTetrahedronMoments(piece.Volume[t], p, sums);
  }
  SetMoments(sums, piece);
  return true;
}
} // namespace clipping
} // namespace mp

#endif
