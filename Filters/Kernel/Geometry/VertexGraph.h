// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file VertexGraph.h
 * @brief The fast clipper: the part of one tetrahedron inside another as a
 *        convex polyhedron whose vertices each have three neighbours
 *        (private to TetrahedronIntersector and its tests).
 *
 * The graph and its general cut by a plane (Clip, Cut) are here. Its
 * members come in three files, one per concern, all included by this one:
 * this file (the graph and Clip), VertexGraphTables.h (the first two cuts
 * from tables of the topologies they make) and VertexGraphFaces.h (walking
 * the faces, and the decomposition into tetrahedra with their moments).
 * The corners' sides come from FaceSides.h; when the graph cannot go on,
 * the intersector falls back to ClipByPlane.h.
 */
#ifndef MeshProjection_Kernel_VertexGraph_h
#define MeshProjection_Kernel_VertexGraph_h

#include "Geometry/Lanes.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Mesh/Vec3.h"

#include <algorithm>
#include <cstring>

namespace mp
{
namespace clipping
{
/// The faces of a vertex graph of at most V vertices, in the order
/// VertexGraph::WalkFaces finds them: each a cycle of vertices.
template <int V>
struct FaceCycles
{
  int NumberOfFaces = 0;
  signed char Size[V / 2 + 2]; ///< three links per vertex: V / 2 + 2 faces
  signed char Vertex[3 * V];   ///< the cycles one after the other
};

/// The point a + u (b - a), coordinate by coordinate (x and y as two
/// lanes: the same operations).
inline void CrossingPoint(const double* a, const double* b, double u, double* x)
{
  const Doubles2 ab = LoadLanes(a);
  const Doubles2 xy = ab + u * (LoadLanes(b) - ab);
  std::memcpy(x, &xy, sizeof xy);
  x[2] = a[2] + u * (b[2] - a[2]);
}

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
  /// Bit v: vertex v (below NumberOfVertices) is no longer part of the
  /// graph, left in place (with On 0) by a last cut that did not compact
  /// (Clip's `last`): only Decompose takes such a graph. 0 otherwise.
  unsigned long long Dead = 0;
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
  static constexpr int TetrahedronNext[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 },
    { 0, 2, 1 } };
  static constexpr int TetrahedronBack[4][3] = { { 0, 0, 0 }, { 0, 2, 1 }, { 1, 2, 1 },
    { 2, 2, 1 } };

  /// Per plane k of the clipping cell, bit v: corner v of the clipped cell
  /// lies on it (sides[k][v] == 0, as SideBits::Zero has them).
  static void ZeroRows(const double (&sides)[4][4], unsigned (&zero)[4])
  {
    for (int k = 0; k < 4; ++k)
    {
      zero[k] = 0;
      for (int v = 0; v < 4; ++v)
      {
        zero[k] |= (sides[k][v] == 0.0 ? 1u : 0u) << v;
      }
    }
  }

  /// The bits SetTetrahedron gives the corners: each one's faces of the
  /// cell, and the clipping planes it lies on (zero: ZeroRows).
  static void CornerBits(const unsigned (&zero)[4], unsigned (&on)[4])
  {
    // The rows' 4 x 4 bits transposed: packed 4 apart, corner v's column
    // (bits v, v + 4, v + 8, v + 12) is gathered to bits 12-15 by one
    // product (its partial products never meet below bit 16: no carries).
    // Mostly no corner lies on a plane: then only the faces.
    const unsigned packed = zero[0] | zero[1] << 4 | zero[2] << 8 | zero[3] << 12;
    for (int v = 0; v < 4; ++v)
    {
      const unsigned planes =
        packed == 0 ? 0u : ((((packed >> v) & 0x1111u) * 0x1248u) >> 12) & 15u;
      on[v] = ((15u & ~(1u << v)) << 4) | planes;
    }
  }

  /// The clipped cell itself (zero: ZeroRows of the sides).
  void SetTetrahedron(const TetrahedronIntersector::Cell& c, const unsigned (&zero)[4])
  {
    this->NumberOfVertices = 4;
    this->Dead = 0;
    this->Faces = nullptr;
    unsigned on[4];
    CornerBits(zero, on);
    for (int v = 0; v < 4; ++v)
    {
      this->On[v] = on[v];
      std::copy(c.X[v], c.X[v] + 3, this->X[v]);
      std::copy(TetrahedronNext[v], TetrahedronNext[v] + 3, this->Next[v]);
      std::copy(TetrahedronBack[v], TetrahedronBack[v] + 3, this->Back[v]);
      this->Original[v] = v;
    }
  }

  void SetTetrahedron(const TetrahedronIntersector::Cell& c, const double (&sides)[4][4])
  {
    unsigned zero[4];
    ZeroRows(sides, zero);
    this->SetTetrahedron(c, zero);
  }

  // The first two cuts, from tables (VertexGraphTables.h).

  /// What one cut of a graph of the tables makes, for one pattern of its
  /// vertices inside and outside (none on the plane): the vertices (a kept
  /// one, or the crossing on the link from a kept one to a clipped one), in
  /// Cut's order, their links and the faces.
  struct TableCut;

  /// The tetrahedron the tables are made on (Cut's topology depends on the
  /// signs of the distances only).
  static TetrahedronIntersector::Cell ReferenceTetrahedron();

  /// The cut of `before` at distances d (+1 or -1) as `cut` records it:
  /// Cut's own result, its vertices named in Cut's order (the kept
  /// vertices, then the crossings by kept vertex and link).
  static void MakeCut(const VertexGraph& before, const double* d, unsigned bit, TableCut& cut);

  /// The graph `cut` makes of the vertices x, on, original (the graph
  /// before it) at distances d from plane `bit`: the crossings computed by
  /// Cut's expression.
  void SetCut(const TableCut& cut, const double (*x)[3], const unsigned* on, const int* original,
    const double* d, unsigned bit);

  /// The cuts of a tetrahedron by one plane, for the 16 patterns of its
  /// corners (bit v: corner v outside; 0 and 15 unused).
  static const TableCut* TetrahedronCuts();

  /**
   * SetTetrahedron and then Clip by plane `k` (bit 1 << k, sides[k] the
   * corners' distances, zero their ZeroRows), in one step from the table of cuts: the same
   * vertices, in the same order, with the same links and bits, and the
   * crossings computed by the same expression. Returns the pattern of
   * corners outside (bit v: corner v), 0 with nothing set when a corner
   * lies on the plane (or its side is NaN) or none is clipped or kept.
   */
  unsigned SetClippedTetrahedron(const TetrahedronIntersector::Cell& c, const double (&sides)[4][4],
    const unsigned (&zero)[4], int k);
  /// The same with ZeroRows of the sides.
  unsigned SetClippedTetrahedron(
    const TetrahedronIntersector::Cell& c, const double (&sides)[4][4], int k)
  {
    unsigned zero[4];
    ZeroRows(sides, zero);
    return this->SetClippedTetrahedron(c, sides, zero, k);
  }

  /// SecondCuts()[64 * first + pattern]: the cuts of the table of first
  /// cuts' graphs (`first` a pattern of TetrahedronCuts), for every pattern
  /// of their 4 or 6 vertices (bit v: vertex v outside).
  static const TableCut* SecondCuts();

  /**
   * Clip of the graph SetClippedTetrahedron made with pattern `first`, from
   * the table of second cuts: the same graph as Clip (vertices, order,
   * links, bits; crossings by the same expression). False, with nothing
   * changed, when a vertex lies on the plane or its distance is NaN (then
   * Clip does it).
   */
  bool ClipSecond(unsigned first, const double* normal, const double* origin, unsigned bit,
    const double sides[4]);

  /// Keeps the part on the inner side of plane `bit`; false when it cannot
  /// (capacity, or a face walk that does not come back): then the caller
  /// falls back to splitting tetrahedra. The `last` cut before Decompose
  /// leaves the clipped vertices in place, as Dead (moving the others down
  /// would give Decompose the same graph, numbered without gaps).
  bool Clip(const double* normal, const double* origin, unsigned bit, const double sides[4],
    bool last = false)
  {
    const int n = this->NumberOfVertices;
    double d[MaxVertices];
    bool anyInside = false;
    unsigned long long clipped = 0; // Cut's: bit v, d[v] < 0
    for (int v = 0; v < n; ++v)
    {
      d[v] = this->Distance(v, normal, origin, bit, sides);
      anyInside |= d[v] > 0.0;
      clipped |= static_cast<unsigned long long>(d[v] < 0.0) << v;
      this->On[v] |= d[v] == 0.0 ? bit : 0u;
    }
    if (!anyInside)
    {
      this->NumberOfVertices = 0; // no volume left
      return true;
    }
    if (clipped == 0)
    {
      return true;
    }
    return this->Cut(d, clipped, bit, last);
  }

  /// Vertex v's distance from the plane as Clip takes it: a corner's exact
  /// side, 0 on the plane, else from the plane's normal.
  double Distance(
    int v, const double* normal, const double* origin, unsigned bit, const double sides[4]) const
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

  /// Clip's cut for distances d with vertices on both sides (`last`: Clip's).
  bool Cut(const double* d, unsigned bit, bool last = false)
  {
    unsigned long long clipped = 0;
    for (int v = 0; v < this->NumberOfVertices; ++v)
    {
      clipped |= static_cast<unsigned long long>(d[v] < 0.0) << v;
    }
    return this->Cut(d, clipped, bit, last);
  }

  /// The same with the clipped vertices as bits (bit v: d[v] < 0).
  bool Cut(const double* d, unsigned long long clipped, unsigned bit, bool last)
  {
    this->Faces = nullptr; // a new graph
    const int n = this->NumberOfVertices;
    // New vertices on the edges from kept to clipped vertices, found from
    // bit masks (n <= 48 < 64): the clipped vertices, each kept vertex's
    // links to them, the kept vertices with any. Only the crossings are
    // then visited, in the same order as a loop over vertices and links
    // (whose two tests per link depend on the data and were among the most
    // mispredicted branches of a 3D run). A link's id is below 48 or -1
    // (bit 63 of the mask, never set).
    unsigned links[MaxVertices];
    const unsigned long long from = this->CrossedLinks(clipped, links);
    int total = n;
    for (unsigned long long kept = from; kept != 0; kept &= kept - 1)
    {
      const int v = __builtin_ctzll(kept);
      for (unsigned l = links[v]; l != 0; l &= l - 1)
      {
        const int j = __builtin_ctz(l);
        const int q = this->Next[v][j];
        if (total == MaxVertices)
        {
          return false;
        }
        const int w = total++;
        CrossingPoint(this->X[v], this->X[q], d[v] / (d[v] - d[q]), this->X[w]);
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
    if (last)
    {
      for (unsigned long long dead = clipped; dead != 0; dead &= dead - 1)
      {
        this->On[__builtin_ctzll(dead)] = 0; // on nothing: out of the piece's bits
      }
      this->Dead = clipped;
      this->NumberOfVertices = total;
      return true;
    }
    return this->Compact(total, clipped);
  }

  /**
   * Of the clipped vertices (bits), the links of kept vertices to them:
   * links[v] bit j for link j of kept vertex v, and the kept vertices with
   * any (returned). Found from the clipped vertices' own links (mostly far
   * fewer than the kept ones), each the way back by Back; links[v] is set
   * for those vertices only.
   */
  unsigned long long CrossedLinks(unsigned long long clipped, unsigned (&links)[MaxVertices]) const
  {
    unsigned long long from = 0;
    for (unsigned long long out = clipped; out != 0; out &= out - 1)
    {
      const int q = __builtin_ctzll(out);
      for (int j = 0; j < 3; ++j)
      {
        const int v = this->Next[q][j];
        // A link's id is below 48 or -1 (bit 63 of the mask, never set).
        const unsigned long long bit = 1ull << (v & 63);
        if ((~clipped & bit) != 0 && v >= 0)
        {
          const unsigned slot = 1u << this->Back[q][j]; // of q in v
          links[v] = (from & bit) != 0 ? links[v] | slot : slot;
          from |= bit;
        }
      }
    }
    return from;
  }

  /**
   * Drops the clipped vertices (bits) of the `total`, moving the others
   * down in order and renumbering their links; false when a kept vertex
   * links to a clipped one or to none (inconsistent signs). Without a
   * branch per link (the checks are gathered) or per kept vertex.
   */
  bool Compact(int total, unsigned long long clipped)
  {
    // map[v + 1]: the new index of v, -1 for a clipped one (and for a link
    // to none, -1 itself: map[0]).
    int map[MaxVertices + 1];
    map[0] = -1;
    int m = 0;
    for (int v = 0; v < total; ++v)
    {
      const int keep = static_cast<int>(((clipped >> v) & 1u) ^ 1u);
      map[v + 1] = keep * (m + 1) - 1;
      m += keep;
    }
    int broken = 0;
    auto relink = [&](int v, int to) {
      for (int j = 0; j < 3; ++j)
      {
        const int y = map[this->Next[v][j] + 1];
        broken |= y;
        this->Next[to][j] = static_cast<signed char>(y);
        this->Back[to][j] = this->Back[v][j];
      }
    };
    // The vertices below the first clipped one stay where they are: only
    // their links change. (clipped != 0: Cut has vertices on both sides.)
    const unsigned long long all = total == 64 ? ~0ull : (1ull << total) - 1;
    const unsigned long long stay = (clipped & (0ull - clipped)) - 1;
    for (int v = 0; (stay >> v) & 1u; ++v)
    {
      relink(v, v);
    }
    for (unsigned long long kept = all & ~clipped & ~stay; kept != 0; kept &= kept - 1)
    {
      const int v = __builtin_ctzll(kept);
      const int to = map[v + 1];
      relink(v, to);
      this->X[to][0] = this->X[v][0];
      this->X[to][1] = this->X[v][1];
      this->X[to][2] = this->X[v][2];
      this->On[to] = this->On[v];
      this->Original[to] = this->Original[v];
    }
    if (broken < 0)
    {
      return false;
    }
    this->NumberOfVertices = m;
    this->Dead = 0;
    return true;
  }
  int Beyond[MaxVertices];     ///< per new vertex (index - n): the clipped end of its edge
  int BeyondBack[MaxVertices]; ///< per new vertex: the slot of its kept end in Beyond

  // The faces (VertexGraphFaces.h).

  /**
   * The faces, walked from the links: from each vertex and link not yet
   * walked, in order, the face to the left of that link, its vertices from
   * there; visit(cycle, size, holdsVertex0, commonBits) for each, stopping
   * when it returns false. False when a walk does not close, or a visit
   * said so.
   */
  template <class Visit>
  bool WalkFaces(Visit&& visit) const;
  /// WalkFaces with the links' bits in W words (1 for up to 21 vertices, or 3).
  template <int W, class Visit>
  bool WalkFacesIn(Visit& visit) const;

  /// The walked faces into `faces`; false when a walk does not close or
  /// they do not fit.
  template <int V>
  bool WalkFaces(FaceCycles<V>& faces) const;

  /**
   * The faces (the tables' when the graph is one of theirs, else walked):
   * the faces of positive area whose vertices all lie on target face k set
   * bit k of `touched` (target faces are the vertex bits from
   * `targetShift`), and the tetrahedra from the first vertex not Dead
   * (the apex) to the triangles of the faces not holding it go to the
   * piece. False when a walk does not
   * close or the piece has no room.
   */
  bool Decompose(int targetShift, double minArea2, TetrahedronIntersector::Piece& piece) const;
};
} // namespace clipping
} // namespace mp

// The members defined apart, one concern each.
#include "Geometry/VertexGraphFaces.h"
#include "Geometry/VertexGraphTables.h"

#endif
