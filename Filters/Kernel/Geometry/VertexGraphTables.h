// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file VertexGraphTables.h
 * @brief VertexGraph's first two cuts from tables of the topologies they
 *        make (part of VertexGraph.h, which includes it: include that).
 *
 * Which vertices a cut keeps, which crossings it makes and how they link
 * depends on the signs of the vertices' distances only. A tetrahedron has
 * 16 patterns of signs, the graphs of its first cuts at most 64 each, so
 * the first two cuts of every pair (most pairs need no more) are read from
 * tables made once by Cut itself on a reference tetrahedron: the same
 * vertices in the same order, the same links and bits, the crossings by
 * the same expression, without Cut's search for links and walks around
 * faces. A vertex on the plane (or a NaN distance) leaves the cut to Clip.
 */
#ifndef MeshProjection_Kernel_VertexGraphTables_h
#define MeshProjection_Kernel_VertexGraphTables_h

#include "Geometry/VertexGraph.h"

#include <algorithm>
#include <cassert>
#include <cstring>

namespace mp
{
namespace clipping
{
struct VertexGraph::TableCut
{
  bool Valid = false; ///< Cut made it, in at most 12 vertices (all do: at most 10; a guard)
  int NumberOfVertices = 0;
  int NumberKept = 0;           ///< the first ones are the kept vertices, the others crossings
  signed char From[12][2] = {}; ///< kept vertex, and clipped one (-1: the kept vertex itself)
  /// Links, all 12 rows (unused ones zero): copied whole, without a loop.
  signed char Next[12][3] = {};
  signed char Back[12][3] = {};
  TableFaces Faces;
  bool HasFaces = false;
};

inline TetrahedronIntersector::Cell VertexGraph::ReferenceTetrahedron()
{
  TetrahedronIntersector::Cell c;
  for (int v = 0; v < 4; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      c.X[v][a] = a + 1 == v ? 1.0 : 0.0;
    }
  }
  return c;
}

inline void VertexGraph::MakeCut(
  const VertexGraph& before, const double* d, unsigned bit, TableCut& cut)
{
  VertexGraph after = before;
  if (!after.Cut(d, bit) || after.NumberOfVertices > 12)
  {
    return;
  }
  const int n = before.NumberOfVertices;
  int r = 0;
  for (int v = 0; v < n; ++v)
  {
    if (d[v] > 0.0)
    {
      cut.From[r][0] = static_cast<signed char>(v);
      cut.From[r++][1] = -1;
    }
  }
  for (int v = 0; v < n; ++v)
  {
    for (int j = 0; j < 3 && d[v] > 0.0; ++j)
    {
      if (d[before.Next[v][j]] < 0.0)
      {
        cut.From[r][0] = static_cast<signed char>(v);
        cut.From[r++][1] = static_cast<signed char>(before.Next[v][j]);
      }
    }
  }
  cut.NumberOfVertices = after.NumberOfVertices;
  for (int w = 0; w < after.NumberOfVertices; ++w)
  {
    cut.NumberKept += cut.From[w][1] < 0;
    std::copy(after.Next[w], after.Next[w] + 3, cut.Next[w]);
    std::copy(after.Back[w], after.Back[w] + 3, cut.Back[w]);
  }
  cut.HasFaces = after.WalkFaces(cut.Faces);
  for (int f = 0; f < cut.Faces.NumberOfFaces; ++f)
  {
    // Decompose reads three vertices of every face of the tables (all
    // have them: a guard).
    cut.HasFaces &= cut.Faces.Size[f] >= 3;
  }
  cut.Valid = true;
}

inline void VertexGraph::SetCut(const TableCut& cut, const double (*x)[3], const unsigned* on,
  const int* original, const double* d, unsigned bit)
{
  this->NumberOfVertices = cut.NumberOfVertices;
  this->Dead = 0;
  this->Faces = cut.HasFaces ? &cut.Faces : nullptr;
  // The kept vertices come first, then the crossings: two loops without
  // a branch per vertex (one on the data, often mispredicted).
  // Original of fixed size (as a loop over the crossings it was a memset
  // call), the kept ones' set below.
  std::fill(this->Original + 0, this->Original + 12, -1);
  for (int r = 0; r < cut.NumberKept; ++r)
  {
    const int v = cut.From[r][0];
    this->X[r][0] = x[v][0];
    this->X[r][1] = x[v][1];
    this->X[r][2] = x[v][2];
    this->On[r] = on[v];
    this->Original[r] = original[v];
  }
  for (int r = cut.NumberKept; r < cut.NumberOfVertices; ++r)
  {
    const int v = cut.From[r][0];
    const int q = cut.From[r][1];
    CrossingPoint(x[v], x[q], d[v] / (d[v] - d[q]), this->X[r]);
    this->On[r] = (on[v] & on[q]) | bit;
  }
  // memcpy of a constant size is a few moves; std::copy, a memmove, was
  // a call.
  std::memcpy(this->Next, cut.Next, sizeof cut.Next);
  std::memcpy(this->Back, cut.Back, sizeof cut.Back);
}

inline const VertexGraph::TableCut* VertexGraph::TetrahedronCuts()
{
  struct Table
  {
    TableCut Cut[16];
    Table()
    {
      const double unit[4][4] = {};
      VertexGraph tetrahedron;
      tetrahedron.SetTetrahedron(ReferenceTetrahedron(), unit);
      for (unsigned pattern = 1; pattern < 15; ++pattern)
      {
        double d[4];
        for (int v = 0; v < 4; ++v)
        {
          d[v] = (pattern >> v) & 1u ? -1.0 : 1.0;
        }
        MakeCut(tetrahedron, d, 1u, this->Cut[pattern]);
      }
    }
  };
  static const Table table;
  return table.Cut;
}

inline unsigned VertexGraph::SetClippedTetrahedron(const TetrahedronIntersector::Cell& c,
  const double (&sides)[4][4], const unsigned (&zero)[4], int k)
{
  const double* d = sides[k];
  unsigned pattern = 0;
  bool onPlane = false;
  for (int v = 0; v < 4; ++v)
  {
    pattern |= (d[v] < 0.0 ? 1u : 0u) << v;
    onPlane |= !((d[v] < 0.0) | (d[v] > 0.0)); // on it, or NaN: Clip decides (bitwise: no branch)
  }
  const TableCut& cut = TetrahedronCuts()[pattern];
  if (onPlane || !cut.Valid) // (also none clipped or none kept)
  {
    return 0;
  }
  unsigned on[4];
  CornerBits(zero, on);
  static constexpr int corners[4] = { 0, 1, 2, 3 };
  this->SetCut(cut, c.X, on, corners, d, 1u << k);
  return pattern;
}

inline const VertexGraph::TableCut* VertexGraph::SecondCuts()
{
  struct Table
  {
    TableCut Cut[16 * 64];
    Table()
    {
      const TetrahedronIntersector::Cell c = ReferenceTetrahedron();
      for (unsigned first = 1; first < 15; ++first)
      {
        double sides[4][4] = {};
        for (int v = 0; v < 4; ++v)
        {
          sides[0][v] = (first >> v) & 1u ? -1.0 : 1.0;
        }
        VertexGraph one;
        one.SetClippedTetrahedron(c, sides, 0);
        const int n = one.NumberOfVertices;
        for (unsigned pattern = 1; pattern + 1 < (1u << n); ++pattern)
        {
          double d[MaxVertices];
          for (int v = 0; v < n; ++v)
          {
            d[v] = (pattern >> v) & 1u ? -1.0 : 1.0;
          }
          MakeCut(one, d, 2u, this->Cut[64 * first + pattern]);
        }
      }
    }
  };
  static const Table table;
  return table.Cut;
}

inline bool VertexGraph::ClipSecond(
  unsigned first, const double* normal, const double* origin, unsigned bit, const double sides[4])
{
  const int n = this->NumberOfVertices;
  assert(n <= 6); // a first cut's graph
  double d[6];
  unsigned pattern = 0;
  bool onPlane = false;
  for (int v = 0; v < n; ++v)
  {
    d[v] = this->Distance(v, normal, origin, bit, sides);
    pattern |= (d[v] < 0.0 ? 1u : 0u) << v;
    onPlane |= !((d[v] < 0.0) | (d[v] > 0.0)); // on it, or NaN: Clip decides (bitwise: no branch)
  }
  if (onPlane)
  {
    return false;
  }
  if (pattern == 0)
  {
    return true; // all inside
  }
  if (pattern + 1 == (1u << n))
  {
    this->NumberOfVertices = 0; // no volume left
    return true;
  }
  const TableCut& cut = SecondCuts()[64 * first + pattern];
  if (!cut.Valid)
  {
    return false;
  }
  // The graph before the cut, aside (the cut overwrites it).
  // All six rows, whatever n (4 or 6): copies of fixed size are moves,
  // of n rows they were three memcpy calls.
  double x[6][3];
  unsigned on[6];
  int original[6];
  std::memcpy(x, this->X, sizeof x);
  std::memcpy(on, this->On, sizeof on);
  std::memcpy(original, this->Original, sizeof original);
  this->SetCut(cut, x, on, original, d, bit);
  return true;
}
} // namespace clipping
} // namespace mp

#endif
