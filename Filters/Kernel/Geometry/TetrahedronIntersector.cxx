// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/TetrahedronIntersector.h"

#include "Geometry/IntersectionPieces.h"
#include "Geometry/Predicates.h"
#include "Geometry/TetrahedronClipping.h"
#include "Mesh/Vec3.h"

#include <algorithm>
#include <cmath>

namespace mp
{
using namespace clipping;

namespace
{
using TetCell = TetrahedronIntersector::Cell;
using TetPiece = TetrahedronIntersector::Piece;
constexpr int MaxTetrahedra = TetrahedronIntersector::MaxTetrahedra;

/**
 * The two cells' face planes against each other's corners: exact[k][v] the
 * side of source corner v w.r.t. target face plane k (positive inside),
 * with an exact sign, so that corners shared by the meshes land exactly on
 * the planes; exactS the reverse (target corners, source planes); their
 * sign bits, and the planes each cell reaches beyond.
 */
struct FacePlaneSides
{
  double Exact[4][4];
  double ExactS[4][4];
  SideBits Bits;        ///< of Exact
  SideBits BitsS;       ///< of ExactS
  unsigned Beyond = 0;  ///< target planes the source reaches beyond
  unsigned BeyondS = 0; ///< source planes the target reaches beyond
};

/// Separating face planes (of either cell): cheap early rejection. Any
/// target face plane with all source corners on or outside it (or the
/// reverse) separates the cells: true then (at most a shared face, edge or
/// vertex: no volume).
inline bool Separated(const TetCell& t, const TetCell& s, FacePlaneSides& p)
{
  const double size = PairExtent(t, s);
  FaceSides(t, s, size, p.Exact, p.Bits);
  FaceSides(s, t, size, p.ExactS, p.BitsS);
  // Per plane, as bits of the rows packed 4 apart: any corner beyond it,
  // all corners on or beyond it.
  p.Beyond = NonZeroRows(PackRows(p.Bits.Negative));
  p.BeyondS = NonZeroRows(PackRows(p.BitsS.Negative));
  return (FullRows(PackRows(p.Bits.NotPositive)) | FullRows(PackRows(p.BitsS.NotPositive))) != 0;
}

/**
 * The planes that cut, in the order of how many of the clipped cell's
 * corners they cut off, most first: the graphs the later clips work on
 * are then smallest (less time per pair than in face order; fewest
 * first takes the most).
 * The order: key (corners outside) * 4 + 3 - p, sorted down; ties keep
 * face order. The cutting planes (1-3 corners outside: 4 would have
 * separated the cells) come first, with keys of 4 and more; the others
 * (keys below 4) after them are not used. Read from a table made at
 * compile time for every pattern of counts (a sort per pair, even a
 * branch-free one, was a visible part of its work).
 */
struct CuttingOrders
{
  /// By the four planes' counts of corners outside (2 bits each, plane p
  /// at bits 2p): the planes in cutting order, 2 bits each.
  unsigned char Order[256];
  constexpr CuttingOrders()
    : Order{}
  {
    for (unsigned counts = 0; counts < 256; ++counts)
    {
      unsigned key[4] = {};
      for (unsigned p = 0; p < 4; ++p)
      {
        key[p] = (((counts >> (2 * p)) & 3u) << 2) | (3u - p);
      }
      // Sorted down by a network of five compare-exchanges.
      const int network[5][2] = { { 0, 1 }, { 2, 3 }, { 0, 2 }, { 1, 3 }, { 1, 2 } };
      for (const auto& ab : network)
      {
        if (key[ab[0]] < key[ab[1]])
        {
          const unsigned swap = key[ab[0]];
          key[ab[0]] = key[ab[1]];
          key[ab[1]] = swap;
        }
      }
      unsigned order = 0;
      for (unsigned i = 0; i < 4; ++i)
      {
        order |= (3u - (key[i] & 3u)) << (2 * i);
      }
      this->Order[counts] = static_cast<unsigned char>(order);
    }
  }
};

inline void CuttingOrder(const unsigned (&negative)[4], int planes[4])
{
  // (Counts of at most 3: 4 would have separated the cells.)
  static constexpr CuttingOrders orders;
  unsigned counts = 0;
  for (int p = 0; p < 4; ++p)
  {
    counts |= CountBits4(negative[p]) << (2 * p);
  }
  const unsigned order = orders.Order[counts];
  for (int i = 0; i < 4; ++i)
  {
    planes[i] = static_cast<int>((order >> (2 * i)) & 3u);
  }
}

/// One cell clipped by the other's planes.
struct Clip
{
  const TetCell& Clipped;
  const TetCell& Clipping;
  const double (&Sides)[4][4]; ///< the clipping planes against the clipped cell's corners
  const unsigned (&Zero)[4];   ///< of Sides, per plane: the corners on it (SideBits::Zero)
  unsigned Cut;                ///< the clipping planes that cut the clipped cell
  int TargetShift;             ///< 4 when the target is clipped (its faces in bits 4-7)
  double MinArea2;
};

/**
 * The clipped cell kept as a polyhedron (a vertex graph) while the planes
 * cut it, in `planes` order (the first two from the tables of cuts when
 * no vertex lies on them: the same graph as clipping, with less work; a
 * corner on the first plane leaves both to Clip), then cut into
 * tetrahedra. False when rounding left the graph inconsistent (or
 * `asGraph` is false): the splitting clipper takes over.
 */
inline bool ClipAsGraph(const Clip& c, const int (&planes)[4], bool asGraph, TetPiece& piece)
{
  VertexGraph graph;
  const int cutting = static_cast<int>(CountBits4(c.Cut));
  int i = 0;
  const unsigned first = asGraph && i < cutting
    ? graph.SetClippedTetrahedron(c.Clipped, c.Sides, c.Zero, planes[0])
    : 0u;
  if (first)
  {
    ++i;
  }
  else
  {
    graph.SetTetrahedron(c.Clipped, c.Zero);
  }
  bool second = first != 0;
  bool clippedAsGraph = asGraph;
  for (; i < cutting && graph.NumberOfVertices > 0 && clippedAsGraph; ++i)
  {
    const int k = planes[i];
    const double* normal = c.Clipping.Normal[k];
    const double* origin = c.Clipping.X[(k + 1) % 4];
    if (!second || !graph.ClipSecond(first, normal, origin, 1u << k, c.Sides[k]))
    {
      clippedAsGraph = graph.Clip(normal, origin, 1u << k, c.Sides[k], i + 1 == cutting);
    }
    second = false;
  }
  return clippedAsGraph && graph.Decompose(c.TargetShift, c.MinArea2, piece);
}

/// The split tetrahedra as the piece (four points each), with the target
/// faces they have a face of positive area on.
inline void PieceFromSplits(const Clip& clip, const ClipTet* tets, int n, TetPiece& piece)
{
  // Faces of the piece of positive area lying on a target plane.
  for (int i = 0; i < n; ++i)
  {
    const ClipTet& c = tets[i];
    std::copy(&c.X[0][0], &c.X[0][0] + 12, &piece.Points[4 * i][0]);
    for (int k = 0; k < 4; ++k)
    {
      piece.Corner[i][k] = 4 * i + k;
    }
    piece.Volume[i] = c.Volume / 6.0;
    for (int f = 0; f < 4; ++f)
    {
      const int a = (f + 1) % 4;
      const int b = (f + 2) % 4;
      const int d = (f + 3) % 4;
      const unsigned common =
        ((c.OnPlane[a] & c.OnPlane[b] & c.OnPlane[d]) >> clip.TargetShift) & 15u;
      if (common & ~piece.TouchedFaces)
      {
        Vec u, v, w;
        Sub(c.X[b], c.X[a], u);
        Sub(c.X[d], c.X[a], v);
        Cross(u, v, w);
        if (Dot(w, w) > clip.MinArea2)
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
    any |= tets[i].OnPlane[0] | tets[i].OnPlane[1] | tets[i].OnPlane[2] | tets[i].OnPlane[3];
  }
  piece.SourceFaces = (any >> (4 - clip.TargetShift)) & 15u;
}

/// The reference clipper: every plane splits every tetrahedron of the
/// piece into at most three. Slower, with no capacity limit. (The piece's
/// moments are left to the caller.)
inline void ClipBySplitting(const Clip& clip, TetPiece& piece)
{
  ClipTet buffers[2][MaxTetrahedra]; // ~18 kB on the stack, no allocation
  ClipTet* current = buffers[0];
  ClipTet* next = buffers[1];
  int n = 1;
  for (int v = 0; v < 4; ++v)
  {
    std::copy(clip.Clipped.X[v], clip.Clipped.X[v] + 3, current[0].X[v]);
    current[0].OnPlane[v] = (15u & ~(1u << v)) << 4;
    current[0].Original[v] = v;
    for (int k = 0; k < 4; ++k) // corners exactly on planes
    {
      current[0].OnPlane[v] |= (clip.Sides[k][v] == 0.0 ? 1u : 0u) << k;
    }
  }
  current[0].Volume = 6.0 * clip.Clipped.Measure;
  for (int k = 0; k < 4 && n > 0; ++k)
  {
    if (!(clip.Cut & (1u << k)))
    {
      continue; // the whole cell is inside this plane
    }
    int m = 0;
    for (int i = 0; i < n; ++i)
    {
      ClipByPlane(current[i], clip.Clipping.Normal[k], clip.Clipping.X[(k + 1) % 4], 1u << k,
        clip.Sides[k], next, m);
    }
    std::swap(current, next);
    n = m;
  }
  PieceFromSplits(clip, current, n, piece);
}

/**
 * Which source cell starts the target neighbour across each touched face.
 * Touched faces the source does not reach beyond (bits: a loop over
 * them, not a mispredicted test per face): the cap lies in a face of the
 * source, the one whose three corners are on the plane (the source is on
 * the inner side of it); else no face of positive area after all.
 */
inline void SetSeedFaces(const FacePlaneSides& p, TetPiece& piece)
{
  const unsigned(&onPlane)[4] = p.Bits.Zero; // per target plane: source corners on it
  for (int k = 0; k < 4; ++k)
  {
    piece.SeedFace[k] = -1;
  }
  for (unsigned lying = piece.TouchedFaces & ~p.Beyond & 15u; lying != 0; lying &= lying - 1)
  {
    const int k = __builtin_ctz(lying);
    if (CountBits4(onPlane[k]) == 3)
    {
      piece.SeedFace[k] = __builtin_ctz(15u & ~onPlane[k]);
    }
    else
    {
      piece.TouchedFaces &= ~(1u << k);
    }
  }
}
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
    const double side = Orient3D(cell.X[(k + 1) % 4], cell.X[(k + 2) % 4], cell.X[(k + 3) % 4], q);
    if (k % 2 == 0 ? side > 0.0 : side < 0.0)
    {
      return k;
    }
  }
  return -1;
}

bool TetrahedronIntersector::Prepare(const MeshView& mesh, Index id, Cell& cell)
{
  const CellCorners ids = mesh.Cell(id);
  cell.Id = id;
  for (int k = 0; k < 4; ++k)
  {
    const double* x = mesh.Point(ids[k]);
    cell.Points[k] = ids[k];
    cell.Face[k] = k;
    cell.X[k][0] = x[0]; // (std::copy of 3 doubles was a memmove call)
    cell.X[k][1] = x[1];
    cell.X[k][2] = x[2];
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
  for (int v = 0; v < 4; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      cell.ByAxis[a][v] = cell.X[v][a];
    }
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
    cell.SideBound[k] = 64.0 * RoundingUnit *
      (std::max({ std::fabs(u[0]), std::fabs(u[1]), std::fabs(u[2]) }) *
        std::max({ std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2]) }));
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

bool TetrahedronIntersector::Apart(const Cell& t, const Cell& s)
{
  double size = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    if (t.Box[2 * c + 1] < s.Box[2 * c] || s.Box[2 * c + 1] < t.Box[2 * c])
    {
      return true;
    }
    size = std::max(
      size, std::max(t.Box[2 * c + 1], s.Box[2 * c + 1]) - std::min(t.Box[2 * c], s.Box[2 * c]));
  }
  // FaceSides' filter, the same bound: a side below -bound is negative.
  auto outside = [size](const Cell& c, const Cell& other) {
    for (int k = 0; k < 4; ++k)
    {
      const double* a = c.X[(k + 1) % 4];
      const double bound = c.SideBound[k] * size;
      bool all = true;
      for (int v = 0; v < 4; ++v)
      {
        const double* x = other.X[v];
        const double d = c.Normal[k][0] * (x[0] - a[0]) + c.Normal[k][1] * (x[1] - a[1]) +
          c.Normal[k][2] * (x[2] - a[2]);
        all &= d < -bound;
      }
      if (all)
      {
        return true;
      }
    }
    return false;
  };
  return outside(t, s) || outside(s, t);
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
  FacePlaneSides p;
  if (Separated(t, s, p))
  {
    return false; // at most a shared face, edge or vertex: no volume
  }
  // The intersection is the source clipped by the target planes it reaches
  // beyond, or the target clipped by the source planes: clip the cell that
  // fewer planes cut (the work grows fast with the number of planes).
  // Vertex bits 0-3: the clipping cell's planes the vertex lies on; bits
  // 4-7: the clipped cell's own faces (face k opposite corner k).
  const bool clipTarget = CountBits4(p.BeyondS) < CountBits4(p.Beyond);
  // A face of the piece "has positive area" above 1e-12 of the smaller
  // cell's typical face (like the 1e-13 for volumes below): rounding leaves
  // caps of ~1e-32 where the cells only touch, e.g. at a shared corner.
  // (Compared as the squared norm of twice the area vector.)
  const double minArea = 2e-12 * std::min(t.FaceScale, s.FaceScale);
  const Clip clip{ clipTarget ? t : s, clipTarget ? s : t, clipTarget ? p.ExactS : p.Exact,
    clipTarget ? p.BitsS.Zero : p.Bits.Zero, clipTarget ? p.BeyondS : p.Beyond, clipTarget ? 4 : 0,
    minArea * minArea };
  int planes[4];
  CuttingOrder(clipTarget ? p.BitsS.Negative : p.Bits.Negative, planes);
  if (!ClipAsGraph(clip, planes, asGraph, piece))
  {
    ClipBySplitting(clip, piece);
    SumMoments(piece);
  }
  SetSeedFaces(p, piece);
  // Rounding in the clipping can leave slivers of relative size ~1e-16
  // where the cells only touch; below 1e-13 of the smaller cell a piece is
  // taken as touching (its contribution would be below the tolerances of
  // the projection anyway), the same way for every search.
  return piece.NumberOfTetrahedra > 0 &&
    piece.M[0][0] > 1e-13 * std::min(t.Measure, s.Measure); // the volume
}

double TetrahedronIntersector::Measure(const Piece& piece)
{
  // The volumes' sum, as the moments summed them (the graph and the
  // splitting clipper both set it whenever there are tetrahedra).
  return piece.NumberOfTetrahedra > 0 ? piece.M[0][0] : 0.0;
}

void TetrahedronIntersector::SumMoments(Piece& piece)
{
  // Moments up to order 2 of the piece relative to one of its vertices (a
  // local origin inside both cells keeps affine functions of size 1 over
  // the piece, so that thin cells cannot make them cancel).
  piece.M[0][0] = 0.0;
  if (piece.NumberOfTetrahedra == 0)
  {
    return;
  }
  const double* o = piece.Points[piece.Corner[0][0]];
  std::copy(o, o + 3, piece.Origin);
  MomentSums sums;
  for (int n = 0; n < piece.NumberOfTetrahedra; ++n)
  {
    const double v = piece.Volume[n]; // signed: rounding may leave a sliver negative
    if (v == 0.0)
    {
      continue;
    }
    double p[4][3];
    for (int a = 0; a < 4; ++a)
    {
      Sub(piece.Points[piece.Corner[n][a]], piece.Origin, p[a]);
    }
    const double* corners[4] = { p[0], p[1], p[2], p[3] };
    AddTetrahedronMoments(v, corners, sums);
  }
  SetMoments(sums, piece);
}

void TetrahedronIntersector::AppendPiece(
  const Piece& p, Index target, Index source, IntersectionPieces& pieces)
{
  for (int i = 0; i < p.NumberOfTetrahedra; ++i)
  {
    const double v = p.Volume[i];
    if (!(v > 0.0))
    {
      continue;
    }
    for (int k = 0; k < 4; ++k)
    {
      const double* x = p.Points[p.Corner[i][k]];
      pieces.Points.insert(pieces.Points.end(), x, x + 3);
    }
    pieces.Offsets.push_back(pieces.Offsets.back() + 4);
    pieces.TargetCell.push_back(target);
    pieces.SourceCell.push_back(source);
    pieces.Measure.push_back(v);
  }
}
} // namespace mp
