// SPDX-License-Identifier: BSD-3-Clause
#include "TetrahedronIntersector.h"

#include "MortarBlocks.h"
#include "MortarProjector.h"

#include "Predicates.h"

#include <algorithm>
#include <cmath>

namespace mp
{
namespace
{
using Vec = double[3];

inline void Sub(const double* a, const double* b, double* r)
{
  r[0] = a[0] - b[0];
  r[1] = a[1] - b[1];
  r[2] = a[2] - b[2];
}
inline void Cross(const double* a, const double* b, double* r)
{
  r[0] = a[1] * b[2] - a[2] * b[1];
  r[1] = a[2] * b[0] - a[0] * b[2];
  r[2] = a[0] * b[1] - a[1] * b[0];
}
inline double Dot(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
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
void ClipByPlane(const ClipTet& t, const double* normal, const double* origin, unsigned bit,
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
  // Fast path: the precomputed normal, with a forward error bound (about
  // 42 eps |u| |v| |x - a| for the rounded differences, cross and dot
  // products; 64 eps to spare). Only near-coplanar points go exact.
  const double* a = c.X[(k + 1) % 4];
  const double w[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
  const double d = c.Normal[k][0] * w[0] + c.Normal[k][1] * w[1] + c.Normal[k][2] * w[2];
  const double size = std::max({ std::fabs(w[0]), std::fabs(w[1]), std::fabs(w[2]) });
  constexpr double eps = 1.1102230246251565e-16;
  if (std::fabs(d) > 64.0 * eps * c.NormalScale[k] * size)
  {
    return d;
  }
  const double o = Orient3D(a, c.X[(k + 2) % 4], c.X[(k + 3) % 4], x);
  return (k % 2) ? o : -o;
}

/**
 * sides[k][v] = FaceSide(c, k, x[v]) for the four faces of `c` and four
 * points, with the filters of all sixteen evaluated first, without branches,
 * and the exact path taken only for the undecided ones.
 */
inline void FaceSides(
  const TetrahedronIntersector::Cell& c, const double (&x)[4][3], double (&sides)[4][4])
{
  constexpr double eps = 1.1102230246251565e-16;
  bool decided = true;
  for (int k = 0; k < 4; ++k)
  {
    const double* a = c.X[(k + 1) % 4];
    const double bound = 64.0 * eps * c.NormalScale[k];
    for (int v = 0; v < 4; ++v)
    {
      const double w0 = x[v][0] - a[0];
      const double w1 = x[v][1] - a[1];
      const double w2 = x[v][2] - a[2];
      const double d = c.Normal[k][0] * w0 + c.Normal[k][1] * w1 + c.Normal[k][2] * w2;
      const double size = std::max(std::max(std::fabs(w0), std::fabs(w1)), std::fabs(w2));
      sides[k][v] = d;
      decided &= std::fabs(d) > bound * size;
    }
  }
  if (decided)
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
  int NumberOfVertices = 0;
  double X[MaxVertices][3];
  int Next[MaxVertices][3];
  unsigned On[MaxVertices];
  int Original[MaxVertices]; ///< corner of the clipped cell, or -1

  void SetTetrahedron(const TetrahedronIntersector::Cell& c, const double (&sides)[4][4])
  {
    static const int next[4][3] = { { 1, 2, 3 }, { 0, 3, 2 }, { 0, 1, 3 }, { 0, 2, 1 } };
    this->NumberOfVertices = 4;
    for (int v = 0; v < 4; ++v)
    {
      std::copy(c.X[v], c.X[v] + 3, this->X[v]);
      std::copy(next[v], next[v] + 3, this->Next[v]);
      this->On[v] = (15u & ~(1u << v)) << 4;
      for (int k = 0; k < 4; ++k)
      {
        this->On[v] |= (sides[k][v] == 0.0 ? 1u : 0u) << k;
      }
      this->Original[v] = v;
    }
  }

  int SlotOf(int v, int neighbor) const
  {
    return this->Next[v][0] == neighbor ? 0 : (this->Next[v][1] == neighbor ? 1 : 2);
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
      if (this->Original[v] >= 0)
      {
        d[v] = sides[this->Original[v]];
      }
      else if (this->On[v] & bit)
      {
        d[v] = 0.0;
      }
      else
      {
        Vec r;
        Sub(this->X[v], origin, r);
        d[v] = Dot(normal, r);
      }
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
    // New vertices on the edges from kept to clipped vertices.
    int total = n;
    for (int v = 0; v < n; ++v)
    {
      if (d[v] < 0.0)
      {
        continue;
      }
      for (int j = 0; j < 3; ++j)
      {
        const int q = this->Next[v][j];
        if (q >= n || d[q] >= 0.0)
        {
          continue;
        }
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
        this->Next[w][0] = v;
        this->Next[w][1] = -1;
        this->Next[w][2] = -1;
        this->Beyond[w - n] = q;
        this->Next[v][j] = w;
      }
    }
    // Link each new vertex w (on the edge kept v -> clipped q) to the next
    // new vertex around the face to the left of v -> q: walk that face
    // through the clipped vertices (whose links are still the old ones).
    for (int w = n; w < total; ++w)
    {
      int previous = this->Next[w][0];
      int current = this->Beyond[w - n];
      for (int steps = 0;; ++steps)
      {
        if (steps > MaxVertices)
        {
          return false;
        }
        const int next = this->Next[current][(this->SlotOf(current, previous) + 1) % 3];
        if (d[next] < 0.0)
        {
          previous = current;
          current = next;
          continue;
        }
        // next is kept: the edge next -> current carries a new vertex, in
        // the slot of next that pointed to current.
        int found = -1;
        for (int j = 0; j < 3; ++j)
        {
          const int x = this->Next[next][j];
          if (x >= n && this->Beyond[x - n] == current)
          {
            found = x;
          }
        }
        if (found < 0)
        {
          return false;
        }
        this->Next[w][1] = found;
        this->Next[found][2] = w;
        break;
      }
    }
    // Compact: drop the clipped vertices.
    int map[MaxVertices];
    int m = 0;
    for (int v = 0; v < total; ++v)
    {
      map[v] = (v < n && d[v] < 0.0) ? -1 : m++;
    }
    for (int v = 0; v < total; ++v)
    {
      const int to = map[v];
      if (to < 0)
      {
        continue;
      }
      for (int j = 0; j < 3; ++j)
      {
        const int x = this->Next[v][j];
        if (x < 0 || map[x] < 0)
        {
          return false;
        }
        this->Next[to][j] = map[x];
      }
      if (to != v)
      {
        std::copy(this->X[v], this->X[v] + 3, this->X[to]);
        this->On[to] = this->On[v];
        this->Original[to] = this->Original[v];
      }
    }
    this->NumberOfVertices = m;
    return true;
  }
  int Beyond[MaxVertices]; ///< per new vertex (index - n): the clipped end of its edge

  /**
   * The faces, walked from the links: the faces of positive area whose
   * vertices all lie on target face k set bit k of `touched` (target faces
   * are the vertex bits from `targetShift`), and the tetrahedra from vertex
   * 0 to the triangles of the faces not holding it go to the piece. False
   * when a walk does not close or the piece has no room.
   */
  bool Decompose(int targetShift, double minArea2, TetrahedronIntersector::Piece& piece) const
  {
    piece.NumberOfTetrahedra = 0;
    piece.TouchedFaces = 0;
    piece.SourceFaces = 0;
    const int n = this->NumberOfVertices;
    if (n == 0)
    {
      return true;
    }
    unsigned any = 0;
    for (int v = 0; v < n; ++v)
    {
      any |= this->On[v];
    }
    piece.SourceFaces = (any >> (4 - targetShift)) & 15u; // the other cell's bits
    bool visited[MaxVertices][3] = {};
    int cycle[MaxVertices];
    for (int v = 0; v < n; ++v)
    {
      for (int j = 0; j < 3; ++j)
      {
        if (visited[v][j])
        {
          continue;
        }
        int size = 0;
        int a = v;
        int slot = j;
        bool holdsApex = false;
        unsigned common = 0xFFu;
        do
        {
          if (size == MaxVertices || visited[a][slot])
          {
            return false;
          }
          visited[a][slot] = true;
          cycle[size++] = a;
          holdsApex |= a == 0;
          common &= this->On[a];
          const int b = this->Next[a][slot];
          slot = (this->SlotOf(b, a) + 1) % 3;
          a = b;
        } while (a != v || slot != j);
        const unsigned target = (common >> targetShift) & 15u;
        if (size < 3 || (holdsApex && !(target & ~piece.TouchedFaces)))
        {
          continue;
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
          const double six = SixVolume(corners[0], corners[1], corners[2], corners[3]);
          if (six == 0.0)
          {
            continue;
          }
          if (piece.NumberOfTetrahedra == TetrahedronIntersector::MaxTetrahedra)
          {
            return false;
          }
          const int t = piece.NumberOfTetrahedra++;
          for (int k = 0; k < 4; ++k)
          {
            std::copy(corners[k], corners[k] + 3, piece.X[t][k]);
          }
          piece.Volume[t] = six / 6.0;
        }
        if (needArea && Dot(area, area) > minArea2)
        {
          piece.TouchedFaces |= target;
        }
      }
    }
    return true;
  }
};
} // namespace

void TetrahedronIntersector::Center(const Cell& cell, double q[3])
{
  for (int d = 0; d < 3; ++d)
  {
    q[d] = 0.25 * (cell.X[0][d] + cell.X[1][d] + cell.X[2][d] + cell.X[3][d]);
  }
}

int TetrahedronIntersector::Locate(const Cell& cell, const double* q, int first)
{
  for (int i = 0; i < 4; ++i)
  {
    const int k = (first + i) % 4;
    // Corners k+1, k+2, k+3 turn so that corner k is on the positive side
    // for odd k and on the negative side for even k (the cell is positive).
    const double side =
      Orient3D(cell.X[(k + 1) % 4], cell.X[(k + 2) % 4], cell.X[(k + 3) % 4], q);
    if (k % 2 == 0 ? side > 0.0 : side < 0.0)
    {
      return k;
    }
  }
  return -1;
}

bool TetrahedronIntersector::Prepare(const MeshView& mesh, Index id, Cell& cell)
{
  const Index* ids = mesh.Cell(id);
  cell.Id = id;
  for (int k = 0; k < 4; ++k)
  {
    const double* x = mesh.Point(ids[k]);
    cell.Points[k] = ids[k];
    cell.Face[k] = k;
    std::copy(x, x + 3, cell.X[k]);
  }
  double six = Orient3D(cell.X[0], cell.X[1], cell.X[2], cell.X[3]);
  if (!(six != 0.0) || !std::isfinite(six))
  {
    return false;
  }
  if (six < 0.0) // negatively oriented: swap corners 2 and 3 (and their faces)
  {
    std::swap(cell.Points[2], cell.Points[3]);
    std::swap(cell.Face[2], cell.Face[3]);
    for (int c = 0; c < 3; ++c)
    {
      std::swap(cell.X[2][c], cell.X[3][c]);
    }
    six = -six;
  }
  cell.Measure = six / 6.0;
  cell.FaceScale = std::pow(cell.Measure, 2.0 / 3.0);
  for (int c = 0; c < 3; ++c)
  {
    cell.Box[2 * c] = std::min({ cell.X[0][c], cell.X[1][c], cell.X[2][c], cell.X[3][c] });
    cell.Box[2 * c + 1] = std::max({ cell.X[0][c], cell.X[1][c], cell.X[2][c], cell.X[3][c] });
  }
  // Inward normals of the faces: the same orientation rule as FaceSide, so
  // that clipping and the exact classification never disagree on a side.
  for (int k = 0; k < 4; ++k)
  {
    const double* a = cell.X[(k + 1) % 4];
    const double* b = cell.X[(k + 2) % 4];
    const double* c = cell.X[(k + 3) % 4];
    Vec u, v;
    Sub(b, a, u);
    Sub(c, a, v);
    Cross(u, v, cell.Normal[k]);
    cell.NormalScale[k] = std::max({ std::fabs(u[0]), std::fabs(u[1]), std::fabs(u[2]) }) *
      std::max({ std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]) });
    if (k % 2 == 0)
    {
      for (double& n : cell.Normal[k])
      {
        n = -n;
      }
    }
  }
  // Rows of J^-1 for J = [X1 - X0, X2 - X0, X3 - X0]: (e2 x e3, e3 x e1, e1 x e2) / det.
  Vec e[3];
  for (int k = 0; k < 3; ++k)
  {
    Sub(cell.X[k + 1], cell.X[0], e[k]);
  }
  Cross(e[1], e[2], cell.Inverse[0]);
  Cross(e[2], e[0], cell.Inverse[1]);
  Cross(e[0], e[1], cell.Inverse[2]);
  for (auto& row : cell.Inverse)
  {
    for (double& x : row)
    {
      x /= six;
    }
  }
  return std::isfinite(cell.Inverse[0][0] + cell.Inverse[1][1] + cell.Inverse[2][2]);
}

void TetrahedronIntersector::Bounds(const Cell& cell, double box[6])
{
  std::copy(cell.Box, cell.Box + 6, box);
}

bool TetrahedronIntersector::Intersect(const Cell& t, const Cell& s, Piece& piece)
{
  return IntersectCells(t, s, piece, true);
}

bool TetrahedronIntersector::IntersectBySplitting(const Cell& t, const Cell& s, Piece& piece)
{
  return IntersectCells(t, s, piece, false);
}

bool TetrahedronIntersector::IntersectCells(
  const Cell& t, const Cell& s, Piece& piece, bool asGraph)
{
  piece.NumberOfTetrahedra = 0;
  piece.TouchedFaces = 0;
  for (int c = 0; c < 3; ++c)
  {
    if (t.Box[2 * c + 1] < s.Box[2 * c] || s.Box[2 * c + 1] < t.Box[2 * c])
    {
      return false;
    }
  }
  // Separating face planes (of either cell): cheap early rejection. Also
  // note which target planes the source reaches beyond.
  // exact[k][v]: the side of source corner v w.r.t. target face plane k
  // (positive inside), with an exact sign, so that corners shared by the
  // meshes land exactly on the planes. Any target face plane with all
  // source corners on or outside it (or the reverse) separates the cells.
  double exact[4][4];
  double exactS[4][4]; // the reverse: target corner v w.r.t. source face plane k
  unsigned beyond = 0;
  unsigned beyondS = 0;
  unsigned onPlane[4] = { 0, 0, 0, 0 }; // per target plane: source corners on it
  FaceSides(t, s.X, exact);
  FaceSides(s, t.X, exactS);
  for (int k = 0; k < 4; ++k)
  {
    int off = 0;
    int offS = 0;
    for (int v = 0; v < 4; ++v)
    {
      off += exact[k][v] <= 0.0;
      beyond |= (exact[k][v] < 0.0 ? 1u : 0u) << k;
      onPlane[k] |= (exact[k][v] == 0.0 ? 1u : 0u) << v;
      offS += exactS[k][v] <= 0.0;
      beyondS |= (exactS[k][v] < 0.0 ? 1u : 0u) << k;
    }
    if (off == 4 || offS == 4)
    {
      return false; // at most a shared face, edge or vertex: no volume
    }
  }

  // The intersection is the source clipped by the target planes it reaches
  // beyond, or the target clipped by the source planes: clip the cell that
  // fewer planes cut (the work grows fast with the number of planes).
  // Vertex bits 0-3: the clipping cell's planes the vertex lies on; bits
  // 4-7: the clipped cell's own faces (face k opposite corner k).
  auto count = [](unsigned bits) { return (bits & 1u) + ((bits >> 1) & 1u) + ((bits >> 2) & 1u) + ((bits >> 3) & 1u); };
  const bool clipTarget = count(beyondS) < count(beyond);
  const Cell& clipped = clipTarget ? t : s;
  const Cell& clipping = clipTarget ? s : t;
  const double(&sides)[4][4] = clipTarget ? exactS : exact;
  const unsigned cut = clipTarget ? beyondS : beyond;

  const int targetShift = clipTarget ? 4 : 0;
  // A face of the piece "has positive area" above 1e-12 of the smaller
  // cell's typical face (like the 1e-13 for volumes below): rounding leaves
  // caps of ~1e-32 where the cells only touch, e.g. at a shared corner.
  // (Compared as the squared norm of twice the area vector.)
  const double minArea = 2e-12 * std::min(t.FaceScale, s.FaceScale);
  const double minArea2 = minArea * minArea;
  VertexGraph graph;
  graph.SetTetrahedron(clipped, sides);
  bool clippedAsGraph = asGraph;
  for (int k = 0; k < 4 && graph.NumberOfVertices > 0 && clippedAsGraph; ++k)
  {
    if (cut & (1u << k))
    {
      clippedAsGraph =
        graph.Clip(clipping.Normal[k], clipping.X[(k + 1) % 4], 1u << k, sides[k]);
    }
  }
  clippedAsGraph = clippedAsGraph && graph.Decompose(targetShift, minArea2, piece);
  if (!clippedAsGraph)
  {
    // The reference clipper: every plane splits every tetrahedron of the
    // piece into at most three. Slower, with no capacity limit.
    ClipTet buffers[2][MaxTetrahedra]; // ~18 kB on the stack, no allocation
    ClipTet* current = buffers[0];
    ClipTet* next = buffers[1];
    int n = 1;
    for (int v = 0; v < 4; ++v)
    {
      std::copy(clipped.X[v], clipped.X[v] + 3, current[0].X[v]);
      current[0].OnPlane[v] = (15u & ~(1u << v)) << 4;
      current[0].Original[v] = v;
      for (int k = 0; k < 4; ++k) // corners exactly on planes
      {
        current[0].OnPlane[v] |= (sides[k][v] == 0.0 ? 1u : 0u) << k;
      }
    }
    current[0].Volume = 6.0 * clipped.Measure;
    for (int k = 0; k < 4 && n > 0; ++k)
    {
      if (!(cut & (1u << k)))
      {
        continue; // the whole cell is inside this plane
      }
      int m = 0;
      for (int i = 0; i < n; ++i)
      {
        ClipByPlane(
          current[i], clipping.Normal[k], clipping.X[(k + 1) % 4], 1u << k, sides[k], next, m);
      }
      std::swap(current, next);
      n = m;
    }

    // Faces of the piece of positive area lying on a target plane.
    for (int i = 0; i < n; ++i)
    {
      const ClipTet& c = current[i];
      std::copy(&c.X[0][0], &c.X[0][0] + 12, &piece.X[i][0][0]);
      piece.Volume[i] = c.Volume / 6.0;
      for (int f = 0; f < 4; ++f)
      {
        const int a = (f + 1) % 4;
        const int b = (f + 2) % 4;
        const int d = (f + 3) % 4;
        const unsigned common =
          ((c.OnPlane[a] & c.OnPlane[b] & c.OnPlane[d]) >> targetShift) & 15u;
        if (common & ~piece.TouchedFaces)
        {
          Vec u, v, w;
          Sub(c.X[b], c.X[a], u);
          Sub(c.X[d], c.X[a], v);
          Cross(u, v, w);
          if (Dot(w, w) > minArea2)
          {
            piece.TouchedFaces |= common;
          }
        }
      }
    }
    piece.NumberOfTetrahedra = n;
    unsigned any = 0;
    for (int i = 0; i < n; ++i)
    {
      any |= current[i].OnPlane[0] | current[i].OnPlane[1] | current[i].OnPlane[2] |
        current[i].OnPlane[3];
    }
    piece.SourceFaces = (any >> (4 - targetShift)) & 15u;
  }
  for (int k = 0; k < 4; ++k)
  {
    piece.SeedFace[k] = -1;
    if ((piece.TouchedFaces & (1u << k)) && !(beyond & (1u << k)))
    {
      // The cap lies in a face of the source: the one whose three corners
      // are on the plane (the source is on the inner side of it).
      for (int f = 0; f < 4; ++f)
      {
        if (onPlane[k] == (15u & ~(1u << f)))
        {
          piece.SeedFace[k] = f;
        }
      }
      if (piece.SeedFace[k] < 0)
      {
        piece.TouchedFaces &= ~(1u << k); // no face of positive area after all
      }
    }
  }
  // Rounding in the clipping can leave slivers of relative size ~1e-16
  // where the cells only touch; below 1e-13 of the smaller cell a piece is
  // taken as touching (its contribution would be below the tolerances of
  // the projection anyway), the same way for every search.
  return piece.NumberOfTetrahedra > 0 &&
    Measure(piece) > 1e-13 * std::min(t.Measure, s.Measure);
}

double TetrahedronIntersector::Measure(const Piece& piece)
{
  double volume = 0.0;
  for (int i = 0; i < piece.NumberOfTetrahedra; ++i)
  {
    volume += piece.Volume[i];
  }
  return volume;
}

namespace
{
/**
 * The piece's moments and both cells' barycentric functions (affine in
 * coordinates relative to one of the piece's vertices), handed to
 * use(lt, ls, M), M the moment matrix of MortarBlocks.h. Returns the volume (0 for a piece without interior).
 */
template <class Use>
double IntegratePiece(const TetrahedronIntersector::Piece& piece,
  const TetrahedronIntersector::Cell& t, const TetrahedronIntersector::Cell& s, const Use& use)
{
  using Cell = TetrahedronIntersector::Cell;
  // Moments up to order 2 of the piece relative to one of its vertices (a
  // local origin inside both cells keeps the barycentric functions below of
  // size 1 over the piece): on a tetrahedron of volume V, integral of x_i =
  // V mean(x_i) and of x_i x_j = V/20 (sum_a x_ai x_aj + sum_a x_ai sum_a x_aj).
  if (piece.NumberOfTetrahedra == 0)
  {
    return 0.0;
  }
  const double* o = piece.X[0][0];
  double m0 = 0.0;
  double m1[3] = { 0, 0, 0 };
  double m2[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
  for (int n = 0; n < piece.NumberOfTetrahedra; ++n)
  {
    double p[4][3];
    for (int a = 0; a < 4; ++a)
    {
      Sub(piece.X[n][a], o, p[a]);
    }
    const double v = piece.Volume[n]; // signed: rounding may leave a sliver negative
    if (v == 0.0)
    {
      continue;
    }
    double sum[3];
    for (int i = 0; i < 3; ++i)
    {
      sum[i] = p[0][i] + p[1][i] + p[2][i] + p[3][i];
    }
    m0 += v;
    for (int i = 0; i < 3; ++i)
    {
      m1[i] += v * sum[i] / 4.0;
      for (int j = i; j < 3; ++j)
      {
        const double sq = p[0][i] * p[0][j] + p[1][i] * p[1][j] + p[2][i] * p[2][j] + p[3][i] * p[3][j];
        m2[i][j] += v / 20.0 * (sq + sum[i] * sum[j]);
      }
    }
  }
  if (!(m0 > 0.0))
  {
    return 0.0;
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < i; ++j)
    {
      m2[i][j] = m2[j][i];
    }
  }
  // Barycentric coordinates as affine functions c + g . x of the local
  // coordinates, for the target and the source.
  double lt[4][4];
  double ls[4][4];
  for (int side = 0; side < 2; ++side)
  {
    const Cell& c = side == 0 ? t : s;
    double(&l)[4][4] = side == 0 ? lt : ls;
    double shift[3];
    Sub(o, c.X[0], shift);
    for (int r = 0; r < 3; ++r)
    {
      l[r + 1][0] = Dot(c.Inverse[r], shift);
      for (int i = 0; i < 3; ++i)
      {
        l[r + 1][i + 1] = c.Inverse[r][i];
      }
    }
    for (int k = 0; k < 4; ++k)
    {
      l[0][k] = (k == 0 ? 1.0 : 0.0) - l[1][k] - l[2][k] - l[3][k];
    }
  }
  // The moment matrix (see MortarBlocks.h).
  double M[4][4];
  M[0][0] = m0;
  for (int i = 0; i < 3; ++i)
  {
    M[0][i + 1] = M[i + 1][0] = m1[i];
    for (int j = 0; j < 3; ++j)
    {
      M[i + 1][j + 1] = m2[i][j];
    }
  }
  use(lt, ls, M);
  return m0;
}
} // namespace

double TetrahedronIntersector::Integrate(
  const Piece& piece, const Cell& t, const Cell& s, double Mts[4][4], double Mtt[4][4])
{
  return IntegratePiece(piece, t, s, [&](const auto& lt, const auto& ls, const auto& M) {
    AddMortarBlocks<4>(lt, ls, M, Mts, Mtt);
  });
}

double TetrahedronIntersector::IntegrateField(const Piece& piece, const Cell& t, const Cell& s,
  double (&moments)[4][4], const double* const (&u)[4], int components, double* const (&rhs)[4])
{
  return IntegratePiece(piece, t, s, [&](const auto& lt, const auto& ls, const auto& M) {
    double d[3];
    Sub(piece.X[0][0], t.X[0], d);
    AddShiftedMoments<4>(M, d, moments);
    AddFieldBlock<4>(lt, ls, M, u, components, rhs);
  });
}

double TetrahedronIntersector::IntegrateMixed(
  const Piece& piece, const Cell& t, const Cell& s, double Mts[4][4], double (&moments)[4][4])
{
  return IntegratePiece(piece, t, s, [&](const auto& lt, const auto& ls, const auto& M) {
    double d[3];
    Sub(piece.X[0][0], t.X[0], d);
    AddShiftedMoments<4>(M, d, moments);
    AddMixedBlock<4>(lt, ls, M, Mts);
  });
}

void TetrahedronIntersector::TargetMass(
  const Cell& t, const double (&moments)[4][4], double (&Mtt)[4][4])
{
  TargetMassFromMoments<4>(t.Inverse, moments, t.Measure, Mtt);
}

void TetrahedronIntersector::Append(
  const Piece& p, Index target, Index source, double, IntersectionPieces& pieces)
{
  for (int i = 0; i < p.NumberOfTetrahedra; ++i)
  {
    const auto& x = p.X[i];
    const double v = p.Volume[i];
    if (!(v > 0.0))
    {
      continue;
    }
    pieces.Points.insert(pieces.Points.end(), &x[0][0], &x[0][0] + 12);
    pieces.Offsets.push_back(pieces.Offsets.back() + 4);
    pieces.TargetCell.push_back(target);
    pieces.SourceCell.push_back(source);
    pieces.Measure.push_back(v);
  }
}
} // namespace mp
