// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TetrahedronClipping.h
 * @brief The two clippers behind TetrahedronIntersector (private to it and
 *        to its tests).
 *
 * ClipByPlane splits a tetrahedron by a plane into at most three (the
 * reference clipper); VertexGraph keeps the clipped cell as a convex
 * polyhedron whose vertices each have three neighbours (the fast one), its
 * first two cuts from tables of the topologies they make. Both classify the
 * corners of the clipped cell with FaceSides, exactly signed.
 */
#ifndef MeshProjection_Kernel_TetrahedronClipping_h
#define MeshProjection_Kernel_TetrahedronClipping_h

#include "Geometry/Lanes.h"
#include "Geometry/Predicates.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Mesh/Vec3.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

namespace mp
{
namespace clipping
{
/// Six times the signed volume of (a, b, c, d).
inline double SixVolume(const double* a, const double* b, const double* c, const double* d)
{
  Vec u, v, w, n;
  Sub(b, a, u);
  Sub(c, a, v);
  Sub(d, a, w);
  Cross(v, w, n);
  return Dot(u, n);
}

/// A tetrahedron during clipping: each vertex knows the target planes it lies on.
struct ClipTet
{
  double X[4][3];
  unsigned OnPlane[4];
  int Original[4]; ///< corner of the source tetrahedron this vertex is, or -1
  double Volume;   ///< six times the volume, > 0 (orientation dropped)
};

/// Where the segment from p (inside, dp >= 0) to q (outside, dq < 0) crosses the plane.
inline void Crossing(const ClipTet& t, int p, int q, const double d[4], unsigned bit, double* x,
  unsigned& on, int& original)
{
  if (d[p] == 0.0)
  {
    std::copy(t.X[p], t.X[p] + 3, x);
    on = t.OnPlane[p] | bit;
    original = t.Original[p];
    return;
  }
  original = -1;
  const double u = d[p] / (d[p] - d[q]);
  for (int c = 0; c < 3; ++c)
  {
    x[c] = t.X[p][c] + u * (t.X[q][c] - t.X[p][c]);
  }
  on = (t.OnPlane[p] & t.OnPlane[q]) | bit;
}

/// A vertex under construction: position, planes it lies on, source corner.
struct Vertex
{
  double X[3];
  unsigned On;
  int Original;
};

inline void Emit(ClipTet* out, int& n, const Vertex& a, const Vertex& b, const Vertex& c,
  const Vertex& e)
{
  const double six = SixVolume(a.X, b.X, c.X, e.X);
  if (six == 0.0)
  {
    return; // collapsed by a vertex lying on the plane
  }
  ClipTet& t = out[n++];
  t.Volume = std::fabs(six);
  const Vertex* vs[4] = { &a, &b, &c, &e };
  for (int v = 0; v < 4; ++v)
  {
    std::copy(vs[v]->X, vs[v]->X + 3, t.X[v]);
    t.OnPlane[v] = vs[v]->On;
    t.Original[v] = vs[v]->Original;
  }
}

/**
 * Keeps the part of `t` where normal . (x - origin) >= 0, as at most three
 * tetrahedra appended to out. Vertices on the plane get `bit`. Corners of
 * the source tetrahedron use their exactly classified distances `exact`;
 * vertices already known to lie on the plane use 0.
 */
inline void ClipByPlane(const ClipTet& t, const double* normal, const double* origin, unsigned bit,
  const double exact[4], ClipTet* out, int& n)
{
  double d[4];
  int in[4];
  int outside[4];
  int nin = 0;
  int nout = 0;
  for (int v = 0; v < 4; ++v)
  {
    if (t.Original[v] >= 0)
    {
      d[v] = exact[t.Original[v]];
    }
    else if (t.OnPlane[v] & bit)
    {
      d[v] = 0.0;
    }
    else
    {
      Vec r;
      Sub(t.X[v], origin, r);
      d[v] = Dot(normal, r);
    }
    if (d[v] >= 0.0)
    {
      in[nin++] = v;
    }
    else
    {
      outside[nout++] = v;
    }
  }
  if (nout == 0)
  {
    ClipTet& c = out[n++];
    c = t;
    for (int v = 0; v < 4; ++v)
    {
      if (d[v] == 0.0)
      {
        c.OnPlane[v] |= bit;
      }
    }
    return;
  }
  if (nin == 0)
  {
    return;
  }
  auto corner = [&](int v) {
    Vertex x;
    std::copy(t.X[v], t.X[v] + 3, x.X);
    x.On = t.OnPlane[v] | (d[v] == 0.0 ? bit : 0u);
    x.Original = t.Original[v];
    return x;
  };
  auto cut = [&](int p, int q) {
    Vertex x;
    Crossing(t, p, q, d, bit, x.X, x.On, x.Original);
    return x;
  };
  if (nin == 1)
  {
    const int a = in[0];
    Emit(out, n, corner(a), cut(a, outside[0]), cut(a, outside[1]), cut(a, outside[2]));
    return;
  }
  // Two or three corners inside: a prism p0 p1 p2 / q0 q1 q2 between the
  // inside face (or edge) and the cut, split into three tetrahedra
  // (p0,p1,p2,q0), (p1,p2,q0,q1), (p2,q0,q1,q2).
  Vertex p[3];
  Vertex q[3];
  if (nin == 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      p[k] = corner(in[k]);
      q[k] = cut(in[k], outside[0]);
    }
  }
  else // two inside (a, b): the wedge (a, ac, ad) / (b, bc, bd)
  {
    p[0] = corner(in[0]);
    p[1] = cut(in[0], outside[0]);
    p[2] = cut(in[0], outside[1]);
    q[0] = corner(in[1]);
    q[1] = cut(in[1], outside[0]);
    q[2] = cut(in[1], outside[1]);
  }
  Emit(out, n, p[0], p[1], p[2], q[0]);
  Emit(out, n, p[1], p[2], q[0], q[1]);
  Emit(out, n, p[2], q[0], q[1], q[2]);
}

/// Positive when x is strictly inside the plane of face k of a prepared
/// (positively oriented) cell; exact sign. For a positive tetrahedron
/// (0,1,2,3), corner k lies on the positive side of (k+1, k+2, k+3) when k is odd.
inline double FaceSide(const TetrahedronIntersector::Cell& c, int k, const double* x)
{
  // Fast path: the precomputed normal, with a forward error bound (a
  // first-order count gives under 50 eps |u| |v| |x - a|, max-norms, for the
  // rounded differences, cross and dot products; 64 eps to spare). Only
  // near-coplanar points go exact.
  const double* a = c.X[(k + 1) % 4];
  const double w[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
  const double d = c.Normal[k][0] * w[0] + c.Normal[k][1] * w[1] + c.Normal[k][2] * w[2];
  const double size = std::max({ std::fabs(w[0]), std::fabs(w[1]), std::fabs(w[2]) });
    if (std::fabs(d) > 64.0 * RoundingUnit * c.NormalScale[k] * size)
  {
    return d;
  }
  const double o = Orient3D(a, c.X[(k + 2) % 4], c.X[(k + 3) % 4], x);
  return (k % 2) ? o : -o;
}

/**
 * sides[k][v] = FaceSide(c, k, x[v]) for the four faces of `c` and the four
 * corners of `other`, with the filters of all sixteen evaluated first,
 * without branches, and the exact path taken only for the undecided ones.
 * The filters bound |x - a| by the extent of the two cells' boxes together
 * (once per pair instead of per point): looser than FaceSide's own, so a
 * point this one leaves undecided is then classified by FaceSide, and the
 * signs and values are FaceSide's either way. (Looser still for cells of
 * very different sizes or shapes: more pairs then take that second pass.)
 */
inline void FaceSides(const TetrahedronIntersector::Cell& c, const TetrahedronIntersector::Cell& other,
  double (&sides)[4][4])
{
  const double(&x)[4][3] = other.X;
  double size = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    size = std::max(size,
      std::max(c.Box[2 * d + 1], other.Box[2 * d + 1]) - std::min(c.Box[2 * d], other.Box[2 * d]));
  }
  // The corners by coordinate, two per vector (Lanes.h): the same operations
  // in the same order as FaceSide's fast path, so the same values; a lane
  // is decided when its distance is beyond the bound on either side (a NaN
  // never is). Scalar, these 32 evaluations per pair were 11% of a 3D run.
  const double(&corner)[3][4] = other.ByAxis;
  Doubles2 x0[2], x1[2], x2[2];
  for (int h = 0; h < 2; ++h)
  {
    x0[h] = LoadLanes(&corner[0][2 * h]);
    x1[h] = LoadLanes(&corner[1][2 * h]);
    x2[h] = LoadLanes(&corner[2][2 * h]);
  }
  Mask2 decided = { -1, -1 };
  for (int k = 0; k < 4; ++k)
  {
    const double* a = c.X[(k + 1) % 4];
    const double* n = c.Normal[k];
    const double bound = 64.0 * RoundingUnit * c.NormalScale[k] * size;
    for (int h = 0; h < 2; ++h)
    {
      const Doubles2 d = n[0] * (x0[h] - a[0]) + n[1] * (x1[h] - a[1]) + n[2] * (x2[h] - a[2]);
      std::memcpy(&sides[k][2 * h], &d, sizeof d);
      decided &= (d > bound) | (d < -bound);
    }
  }
  if (decided[0] && decided[1])
  {
    return;
  }
  for (int k = 0; k < 4; ++k)
  {
    for (int v = 0; v < 4; ++v)
    {
      sides[k][v] = FaceSide(c, k, x[v]);
    }
  }
}

/// Of a table sides[k][v] (FaceSides'), per row k, bit v: the side is
/// negative, not positive, zero (a NaN is none of them).
struct SideBits
{
  unsigned Negative[4];
  unsigned NotPositive[4];
  unsigned Zero[4];
};

/// SideBits of a table, two lanes at a time (compared one by one, the
/// 48 comparisons and shifts were 4% of a 3D run).
inline void GetSideBits(const double (&sides)[4][4], SideBits& bits)
{
  for (int k = 0; k < 4; ++k)
  {
    const Doubles2 r0 = LoadLanes(&sides[k][0]);
    const Doubles2 r1 = LoadLanes(&sides[k][2]);
    bits.Negative[k] = LaneBits(r0 < 0.0) | LaneBits(r1 < 0.0) << 2;
    bits.NotPositive[k] = LaneBits(r0 <= 0.0) | LaneBits(r1 <= 0.0) << 2;
    bits.Zero[k] = LaneBits(r0 == 0.0) | LaneBits(r1 == 0.0) << 2;
  }
}

/// The number of bits set in a 4-bit pattern.
inline unsigned CountBits4(unsigned bits)
{
  static constexpr unsigned char count[16] = { 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4 };
  return count[bits & 15u];
}

/**
 * Adds a tetrahedron's moments about a point o to m0, m1, m2 (upper
 * triangle): `p` holds its corners minus o, all four, or three when the
 * fourth is o itself. On a tetrahedron of volume V, the integral of x_i is
 * V mean(x_i) and of x_i x_j V/20 (sum_a x_ai x_aj + sum_a x_ai sum_a x_aj).
 */
template <int N>
inline void AddTetrahedronMoments(
  double volume, const double (&p)[N][3], double& m0, double (&m1)[3], double (&m2)[3][3])
{
  static_assert(N == 3 || N == 4, "corners about o, without o itself");
  double sum[3];
  for (int i = 0; i < 3; ++i)
  {
    sum[i] = p[0][i];
    for (int a = 1; a < N; ++a)
    {
      sum[i] += p[a][i];
    }
  }
  m0 += volume;
  for (int i = 0; i < 3; ++i)
  {
    m1[i] += volume * sum[i] / 4.0;
    for (int j = i; j < 3; ++j)
    {
      double sq = p[0][i] * p[0][j];
      for (int a = 1; a < N; ++a)
      {
        sq += p[a][i] * p[a][j];
      }
      m2[i][j] += volume / 20.0 * (sq + sum[i] * sum[j]);
    }
  }
}

/// Stores summed moments in the piece: M unset unless the volume is positive.
inline void SetMoments(
  double m0, const double (&m1)[3], const double (&m2)[3][3], TetrahedronIntersector::Piece& piece)
{
  piece.M[0][0] = m0;
  if (!(m0 > 0.0))
  {
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    piece.M[0][a + 1] = piece.M[a + 1][0] = m1[a];
    for (int b = 0; b < 3; ++b)
    {
      piece.M[a + 1][b + 1] = b >= a ? m2[a][b] : m2[b][a];
    }
  }
}

/// The faces of a vertex graph of at most V vertices, in the order
/// VertexGraph::WalkFaces finds them: each a cycle of vertices.
template <int V>
struct FaceCycles
{
  int NumberOfFaces = 0;
  signed char Size[V / 2 + 2];  ///< three links per vertex: V / 2 + 2 faces
  signed char Vertex[3 * V];    ///< the cycles one after the other
};

/**
 * A convex polyhedron as a graph in which every vertex has three
 * neighbours, listed so that the face to the left of the directed edge
 * a -> b continues at b with Next[b][(slot of a in b) + 1 mod 3]; faces are
 * then counterclockwise seen from outside. A tetrahedron is such a graph,
 * and clipping keeps it one: each new vertex lies on an edge from a kept
 * vertex to a clipped one (even when the kept vertex is on the plane, where
 * the new vertex coincides with it: an edge of length zero, harmless for
 * volumes and moments), and links to the kept vertex and to the new vertices
 * before and after it around the cap. Every vertex is classified once per
 * plane, so the faces stay consistent with each other whatever the
 * rounding. This keeps a polyhedron of at most ~12 vertices instead of
 * splitting up to 27 tetrahedra per plane.
 *
 * Vertex bits 0-3: the clipping cell's planes the vertex lies on; bits 4-7:
 * the clipped cell's own faces (face k opposite corner k).
 */
struct VertexGraph
{
  static constexpr int MaxVertices = 48;
  /// The faces of the table's graphs (at most 12 vertices).
  using TableFaces = FaceCycles<12>;
  int NumberOfVertices = 0;
  /// The faces when the graph is one of the tables' (then Decompose need
  /// not walk them), else null.
  const TableFaces* Faces = nullptr;
  double X[MaxVertices][3];
  /// (Bytes: the tables' links are copied as fixed blocks of 36 bytes.)
  signed char Next[MaxVertices][3];
  /// Back[v][j]: the slot of v among the neighbours of Next[v][j], so that
  /// walks around faces never search for it.
  signed char Back[MaxVertices][3];
  unsigned On[MaxVertices];
  int Original[MaxVertices]; ///< corner of the clipped cell, or -1

  /// The links of a tetrahedron (0, 1, 2, 3), positively oriented.
  static constexpr int TetrahedronNext[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };
  static constexpr int TetrahedronBack[4][3] = { { 0, 0, 0 }, { 0, 2, 1 }, { 1, 2, 1 }, { 2, 2, 1 } };

  /// The bits SetTetrahedron gives corner v: the cell's faces through it,
  /// and the clipping planes it lies on.
  static unsigned CornerBits(int v, const double (&sides)[4][4])
  {
    unsigned on = (15u & ~(1u << v)) << 4;
    for (int k = 0; k < 4; ++k)
    {
      on |= (sides[k][v] == 0.0 ? 1u : 0u) << k;
    }
    return on;
  }

  void SetTetrahedron(const TetrahedronIntersector::Cell& c, const double (&sides)[4][4])
  {
    this->NumberOfVertices = 4;
    this->Faces = nullptr;
    for (int v = 0; v < 4; ++v)
    {
      std::copy(c.X[v], c.X[v] + 3, this->X[v]);
      std::copy(TetrahedronNext[v], TetrahedronNext[v] + 3, this->Next[v]);
      std::copy(TetrahedronBack[v], TetrahedronBack[v] + 3, this->Back[v]);
      this->On[v] = CornerBits(v, sides);
      this->Original[v] = v;
    }
  }

  /// What one cut of a graph of the tables makes, for one pattern of its
  /// vertices inside and outside (none on the plane): the vertices (a kept
  /// one, or the crossing on the link from a kept one to a clipped one), in
  /// Cut's order, their links and the faces.
  struct TableCut
  {
    bool Valid = false; ///< Cut made it, in at most 12 vertices (all do: at most 10; a guard)
    int NumberOfVertices = 0;
    int NumberKept = 0; ///< the first ones are the kept vertices, the others crossings
    signed char From[12][2] = {}; ///< kept vertex, and clipped one (-1: the kept vertex itself)
    /// Links, all 12 rows (unused ones zero): copied whole, without a loop.
    signed char Next[12][3] = {};
    signed char Back[12][3] = {};
    TableFaces Faces;
    bool HasFaces = false;
  };

  /// The tetrahedron the tables are made on (Cut's topology depends on the
  /// signs of the distances only).
  static TetrahedronIntersector::Cell ReferenceTetrahedron()
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

  /// The cut of `before` at distances d (+1 or -1) as `cut` records it:
  /// Cut's own result, its vertices named in Cut's order (the kept
  /// vertices, then the crossings by kept vertex and link).
  static void MakeCut(const VertexGraph& before, const double* d, unsigned bit, TableCut& cut)
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
    cut.Valid = true;
  }

  /// The graph `cut` makes of the vertices x, on, original (the graph
  /// before it) at distances d from plane `bit`: the crossings computed by
  /// Cut's expression.
  void SetCut(const TableCut& cut, const double (*x)[3], const unsigned* on, const int* original,
    const double* d, unsigned bit)
  {
    this->NumberOfVertices = cut.NumberOfVertices;
    this->Faces = cut.HasFaces ? &cut.Faces : nullptr;
    // The kept vertices come first, then the crossings: two loops without
    // a branch per vertex (one was mispredicted a fifth of the time).
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
      const double u = d[v] / (d[v] - d[q]);
      for (int a = 0; a < 3; ++a)
      {
        this->X[r][a] = x[v][a] + u * (x[q][a] - x[v][a]);
      }
      this->On[r] = (on[v] & on[q]) | bit;
    }
    // memcpy of a constant size is a few moves; std::copy, a memmove, was
    // a call.
    std::memcpy(this->Next, cut.Next, sizeof cut.Next);
    std::memcpy(this->Back, cut.Back, sizeof cut.Back);
  }

  /// The cuts of a tetrahedron by one plane, for the 16 patterns of its
  /// corners (bit v: corner v outside; 0 and 15 unused).
  static const TableCut* TetrahedronCuts()
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

  /**
   * SetTetrahedron and then Clip by plane `k` (bit 1 << k, sides[k] the
   * corners' distances), in one step from the table of cuts: the same
   * vertices, in the same order, with the same links and bits, and the
   * crossings computed by the same expression. Returns the pattern of
   * corners outside (bit v: corner v), 0 with nothing set when a corner
   * lies on the plane (or its side is NaN) or none is clipped or kept.
   */
  unsigned SetClippedTetrahedron(const TetrahedronIntersector::Cell& c, const double (&sides)[4][4], int k)
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
    for (int v = 0; v < 4; ++v)
    {
      on[v] = CornerBits(v, sides);
    }
    static constexpr int corners[4] = { 0, 1, 2, 3 };
    this->SetCut(cut, c.X, on, corners, d, 1u << k);
    return pattern;
  }

  /// SecondCuts()[64 * first + pattern]: the cuts of the table of first
  /// cuts' graphs (`first` a pattern of TetrahedronCuts), for every pattern
  /// of their 4 or 6 vertices (bit v: vertex v outside).
  static const TableCut* SecondCuts()
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

  /**
   * Clip of the graph SetClippedTetrahedron made with pattern `first`, from
   * the table of second cuts: the same graph as Clip (vertices, order,
   * links, bits; crossings by the same expression). False, with nothing
   * changed, when a vertex lies on the plane or its distance is NaN (then
   * Clip does it).
   */
  bool ClipSecond(unsigned first, const double* normal, const double* origin, unsigned bit, const double sides[4])
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

  /// Keeps the part on the inner side of plane `bit`; false when it cannot
  /// (capacity, or a face walk that does not come back): then the caller
  /// falls back to splitting tetrahedra.
  bool Clip(const double* normal, const double* origin, unsigned bit, const double sides[4])
  {
    const int n = this->NumberOfVertices;
    double d[MaxVertices];
    bool anyInside = false;
    bool anyOutside = false;
    for (int v = 0; v < n; ++v)
    {
      d[v] = this->Distance(v, normal, origin, bit, sides);
      anyInside |= d[v] > 0.0;
      anyOutside |= d[v] < 0.0;
      if (d[v] == 0.0)
      {
        this->On[v] |= bit;
      }
    }
    if (!anyInside)
    {
      this->NumberOfVertices = 0; // no volume left
      return true;
    }
    if (!anyOutside)
    {
      return true;
    }
    return this->Cut(d, bit);
  }

  /// Vertex v's distance from the plane as Clip takes it: a corner's exact
  /// side, 0 on the plane, else from the plane's normal.
  double Distance(int v, const double* normal, const double* origin, unsigned bit, const double sides[4]) const
  {
    if (this->Original[v] >= 0)
    {
      return sides[this->Original[v]];
    }
    if (this->On[v] & bit)
    {
      return 0.0;
    }
    Vec r;
    Sub(this->X[v], origin, r);
    return Dot(normal, r);
  }

  /// Clip's cut for distances d with vertices on both sides.
  bool Cut(const double* d, unsigned bit)
  {
    this->Faces = nullptr; // a new graph
    const int n = this->NumberOfVertices;
    // New vertices on the edges from kept to clipped vertices, found from
    // bit masks (n <= 48 < 64): the clipped vertices, each kept vertex's
    // links to them, the kept vertices with any. Only the crossings are
    // then visited, in the same order as a loop over vertices and links
    // (whose two tests per link were a tenth of all mispredicted branches
    // of a 3D run). A link's id is below 48 or -1 (bit 63 of the mask,
    // never set).
    unsigned long long clipped = 0;
    for (int v = 0; v < n; ++v)
    {
      clipped |= static_cast<unsigned long long>(d[v] < 0.0) << v;
    }
    unsigned links[MaxVertices];
    unsigned long long from = 0;
    for (int v = 0; v < n; ++v)
    {
      unsigned l = 0;
      for (int j = 0; j < 3; ++j)
      {
        l |= static_cast<unsigned>((clipped >> (this->Next[v][j] & 63)) & 1u) << j;
      }
      l *= static_cast<unsigned>(((clipped >> v) & 1u) ^ 1u); // kept vertices only
      links[v] = l;
      from |= static_cast<unsigned long long>(l != 0) << v;
    }
    int total = n;
    while (from != 0)
    {
      const int v = __builtin_ctzll(from);
      from &= from - 1;
      for (unsigned l = links[v]; l != 0; l &= l - 1)
      {
        const int j = __builtin_ctz(l);
        const int q = this->Next[v][j];
        if (total == MaxVertices)
        {
          return false;
        }
        const int w = total++;
        const double u = d[v] / (d[v] - d[q]);
        for (int c = 0; c < 3; ++c)
        {
          this->X[w][c] = this->X[v][c] + u * (this->X[q][c] - this->X[v][c]);
        }
        this->On[w] = (this->On[v] & this->On[q]) | bit;
        this->Original[w] = -1;
        this->Next[w][0] = static_cast<signed char>(v);
        this->Back[w][0] = static_cast<signed char>(j);
        this->Next[w][1] = -1;
        this->Next[w][2] = -1;
        this->Beyond[w - n] = q;
        this->BeyondBack[w - n] = this->Back[v][j]; // the slot of v in q
        this->Next[v][j] = static_cast<signed char>(w);
        this->Back[v][j] = 0;
      }
    }
    // Link each new vertex w (on the edge kept v -> clipped q) to the next
    // new vertex around the face to the left of v -> q: walk that face
    // through the clipped vertices (whose links are still the old ones).
    for (int w = n; w < total; ++w)
    {
      int current = this->Beyond[w - n];
      int slot = this->BeyondBack[w - n]; // of the vertex we came from, in current
      for (int steps = 0;; ++steps)
      {
        if (steps > MaxVertices)
        {
          return false;
        }
        // Clipped vertices keep their old links (and back slots).
        const int out = slot == 2 ? 0 : slot + 1;
        const int next = this->Next[current][out];
        const int back = this->Back[current][out]; // the slot of current in next
        if (next < 0 || next >= n)
        {
          return false; // not an old link: inconsistent signs (NaN distances)
        }
        if (d[next] < 0.0)
        {
          current = next;
          slot = back;
          continue;
        }
        // next is kept: the edge next -> current carries a new vertex, in
        // the slot of next that pointed to current.
        const int found = this->Next[next][back];
        if (found < n || this->Beyond[found - n] != current)
        {
          return false;
        }
        this->Next[w][1] = found;
        this->Back[w][1] = 2;
        this->Next[found][2] = w;
        this->Back[found][2] = 1;
        break;
      }
    }
    // Compact: drop the clipped vertices. Without a branch per link (the
    // checks are gathered) or per kept vertex (one moved onto itself is
    // harmless).
    int map[MaxVertices];
    int m = 0;
    for (int v = 0; v < total; ++v)
    {
      const int keep = static_cast<int>(((clipped >> v) & 1u) ^ 1u);
      map[v] = keep * (m + 1) - 1; // -1 for a clipped vertex
      m += keep;
    }
    bool broken = false;
    const unsigned long long all = total == 64 ? ~0ull : (1ull << total) - 1;
    for (unsigned long long kept = all & ~clipped; kept != 0; kept &= kept - 1)
    {
      const int v = __builtin_ctzll(kept);
      const int to = map[v];
      for (int j = 0; j < 3; ++j)
      {
        const int x = this->Next[v][j];
        const int y = map[x < 0 ? 0 : x];
        broken |= (x < 0) | (y < 0);
        this->Next[to][j] = static_cast<signed char>(y);
        this->Back[to][j] = this->Back[v][j];
      }
      this->X[to][0] = this->X[v][0];
      this->X[to][1] = this->X[v][1];
      this->X[to][2] = this->X[v][2];
      this->On[to] = this->On[v];
      this->Original[to] = this->Original[v];
    }
    if (broken)
    {
      return false;
    }
    this->NumberOfVertices = m;
    return true;
  }
  int Beyond[MaxVertices]; ///< per new vertex (index - n): the clipped end of its edge
  int BeyondBack[MaxVertices]; ///< per new vertex: the slot of its kept end in Beyond

  /**
   * The faces, walked from the links: from each vertex and link not yet
   * walked, in order, the face to the left of that link, its vertices from
   * there; visit(cycle, size, holdsVertex0, commonBits) for each, stopping
   * when it returns false. False when a walk does not close, or a visit
   * said so.
   */
  template <class Visit>
  bool WalkFaces(Visit&& visit) const
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

  /// The walked faces into `faces`; false when a walk does not close or
  /// they do not fit.
  template <int V>
  bool WalkFaces(FaceCycles<V>& faces) const
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

  /**
   * The faces (the tables' when the graph is one of theirs, else walked):
   * the faces of positive area whose vertices all lie on target face k set
   * bit k of `touched` (target faces are the vertex bits from
   * `targetShift`), and the tetrahedra from vertex 0 to the triangles of
   * the faces not holding it go to the piece. False when a walk does not
   * close or the piece has no room.
   */
  bool Decompose(int targetShift, double minArea2, TetrahedronIntersector::Piece& piece) const
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
};
} // namespace clipping
} // namespace mp

#endif
