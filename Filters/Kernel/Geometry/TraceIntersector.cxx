// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/TraceIntersector.h"

#include "Geometry/IntersectionPieces.h"
#include "Geometry/Moments.h"
#include "Geometry/Predicates.h"
#include "Geometry/Reach.h"
#include "Mesh/Vec3.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mp
{
namespace
{
/// Heights (distances) this small relative to the target cell count as zero.
constexpr double HeightTolerance = 1e-10;
/// Pieces smaller than this fraction of the target cell are rounding slivers.
constexpr double SliverFraction = 1e-13;

/// The largest extent of a box (xmin, xmax, ymin, ymax, zmin, zmax).
inline double Extent(const double box[6])
{
  return std::max({ box[1] - box[0], box[3] - box[2], box[5] - box[4] });
}

// A generic direction: a segment lying in a face's plane belongs to the cell
// this direction points into from it.
constexpr double Generic[3] = { 0.5772156649015329, 0.3183098861837907, 0.7071067811865476 };

/**
 * A tetrahedron's corners against a target facet's plane: each one's image
 * in the facet's frame and height over the plane (zero within the
 * tolerance), and which side counts as above.
 */
struct CornerHeights
{
  double UV[4][2];
  double H[4];
  bool Above[4];
  int Zeros = 0; ///< corners on the plane
  int Up = 0;    ///< corners above it
};

/// Every corner's image and height, from the mesh's own point: one value
/// per point and target facet, whichever tetrahedron asks.
inline void MeasureHeights(const SurfaceTraceIntersector::Cell& t,
  const SurfaceTraceIntersector::SourceCellType& s, double tolerance, CornerHeights& c)
{
  int apex = 0;
  for (int k = 0; k < 4; ++k)
  {
    SurfaceIntersector::ToFrame(t, s.X[k], c.UV[k], c.H[k]);
    if (std::fabs(c.H[k]) <= tolerance)
    {
      c.H[k] = 0.0;
      ++c.Zeros;
    }
    else
    {
      apex = k;
    }
  }
  // Zero counts as below the plane; but a face on the plane that is on the
  // source's boundary, with its tetrahedron below, is taken from below.
  const bool zeroAbove = c.Zeros == 3 && c.H[apex] < 0.0 && ((s.Boundary >> apex) & 1u);
  for (int k = 0; k < 4; ++k)
  {
    c.Above[k] = c.H[k] > 0.0 || (zeroAbove && c.H[k] == 0.0);
    c.Up += c.Above[k];
  }
}

/**
 * A tetrahedron that only touches the plane (in a vertex, an edge or a
 * face on the other side) meets the target when those points' box meets
 * the target's: the front must pass through it, to all its neighbours,
 * for the cells around an edge lying on the plane to be reached.
 */
inline bool Touches(const SurfaceTraceIntersector::Cell& t, const CornerHeights& c,
  SurfaceTraceIntersector::Piece& piece)
{
  double box[4] = { 0.0, -1.0, 0.0, -1.0 };
  for (int k = 0; k < 4; ++k)
  {
    if (c.H[k] != 0.0)
    {
      continue;
    }
    const bool first = box[1] < box[0];
    box[0] = first ? c.UV[k][0] : std::min(box[0], c.UV[k][0]);
    box[1] = first ? c.UV[k][0] : std::max(box[1], c.UV[k][0]);
    box[2] = first ? c.UV[k][1] : std::min(box[2], c.UV[k][1]);
    box[3] = first ? c.UV[k][1] : std::max(box[3], c.UV[k][1]);
  }
  if (box[1] < box[0] || box[1] < t.Box[0] || t.Box[1] < box[0] || box[3] < t.Box[2] ||
    t.Box[3] < box[2])
  {
    return false;
  }
  piece.SourceFaces = 15u;
  return true;
}

/// A tetrahedron's cross-section with the plane: the crossed edges (above,
/// below) in cyclic order, where each crosses, and the face each side of
/// the cross-section lies in.
struct CrossSection
{
  int M = 0; ///< 3 or 4 crossings
  int Edge[4][2];
  double C[4][2];
  int CycleFace[4];
};

/// The crossed edges (above, below) in cyclic order around the cross-section.
inline void CrossedEdges(const CornerHeights& c, CrossSection& x)
{
  const int n = c.Up;
  int up[3];
  int down[3];
  int nu = 0;
  int nd = 0;
  for (int k = 0; k < 4; ++k)
  {
    (c.Above[k] ? up[nu++] : down[nd++]) = k;
  }
  int m = 0;
  if (n == 1 || n == 3)
  {
    for (int k = 0; k < 3; ++k)
    {
      x.Edge[m][0] = n == 1 ? up[0] : up[k];
      x.Edge[m][1] = n == 1 ? down[k] : down[0];
      ++m;
    }
  }
  else
  {
    const int cycle[4][2] = { { up[0], down[0] }, { up[0], down[1] }, { up[1], down[1] },
      { up[1], down[0] } };
    for (m = 0; m < 4; ++m)
    {
      x.Edge[m][0] = cycle[m][0];
      x.Edge[m][1] = cycle[m][1];
    }
  }
  x.M = m;
}

/// Where each crossed edge meets the plane (the same bits in every
/// tetrahedron around the edge), and the face of each side.
inline void Crossings(
  const SurfaceTraceIntersector::SourceCellType& s, const CornerHeights& c, CrossSection& x)
{
  const int m = x.M;
  for (int e = 0; e < m; ++e)
  {
    const int i = x.Edge[e][0];
    const int j = x.Edge[e][1];
    if (c.H[j] == 0.0 && !c.Above[j])
    {
      x.C[e][0] = c.UV[j][0];
      x.C[e][1] = c.UV[j][1];
    }
    else if (c.H[i] == 0.0)
    {
      x.C[e][0] = c.UV[i][0];
      x.C[e][1] = c.UV[i][1];
    }
    else
    {
      // From the ends in the order of their ids: the same bits in every cell.
      const int a = s.Points[i] < s.Points[j] ? i : j;
      const int b = a == i ? j : i;
      const double r = c.H[a] / (c.H[a] - c.H[b]);
      x.C[e][0] = c.UV[a][0] + r * (c.UV[b][0] - c.UV[a][0]);
      x.C[e][1] = c.UV[a][1] + r * (c.UV[b][1] - c.UV[a][1]);
    }
    // The side from this crossing to the next lies in the face opposite the
    // corner that neither edge has.
    const int next = (e + 1) % m;
    const unsigned used = (1u << x.Edge[e][0]) | (1u << x.Edge[e][1]) | (1u << x.Edge[next][0]) |
      (1u << x.Edge[next][1]);
    int missing = 0;
    while ((used >> missing) & 1u)
    {
      ++missing;
    }
    x.CycleFace[e] = missing;
  }
}

/**
 * The cross-section as one or two triangles, each cut out of the target.
 * Each side of a triangle carries the tetrahedron's faces it lies on: a
 * side of the cross-section its face, the diagonal none; but where one
 * triangle has no area (a crossing repeated where a corner lies on the
 * plane, or rounding), the other's diagonal stands for its two sides.
 */
inline void CutByCrossSection(const SurfaceTraceIntersector::Cell& t,
  const SurfaceTraceIntersector::SourceCellType& s, const CrossSection& x,
  SurfaceTraceIntersector::Piece& piece)
{
  const int parts[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
  const int m = x.M;
  const int count = m == 4 ? 2 : 1;
  TriangleIntersector::Cell sub[2];
  bool area[2] = { false, false };
  unsigned sides[2][3]; // per part, per corner k as set here: the faces of the side opposite it
  for (int p = 0; p < count; ++p)
  {
    sub[p].Id = s.Id;
    for (int k = 0; k < 3; ++k)
    {
      const int v = parts[p][k];
      sub[p].X[k][0] = x.C[v][0];
      sub[p].X[k][1] = x.C[v][1];
      sub[p].Points[k] = s.Points[k];
      sub[p].Face[k] = k; // PrepareCorners reorders: Face then names the corner as set here
      const int from = parts[p][(k + 1) % 3];
      const int to = parts[p][(k + 2) % 3];
      sides[p][k] = to == (from + 1) % m ? 1u << x.CycleFace[from] : 0u;
    }
    area[p] = TriangleIntersector::PrepareCorners(sub[p]);
  }
  if (count == 2 && area[0] != area[1])
  {
    const int flat = area[0] ? 1 : 0;
    const unsigned outer = sides[flat][0] | sides[flat][1] | sides[flat][2];
    for (unsigned& side : sides[1 - flat])
    {
      side = side ? side : outer;
    }
  }
  for (int p = 0; p < count; ++p)
  {
    if (!area[p])
    {
      continue; // no area (a tetrahedron touching the plane)
    }
    TriangleIntersector::Piece& part = piece.Parts[piece.NumberOfParts];
    if (!TriangleIntersector::Intersect(t, sub[p], part))
    {
      continue;
    }
    ++piece.NumberOfParts;
    piece.TouchedFaces |= part.TouchedFaces;
    for (int l = 0; l < 3; ++l)
    {
      if ((part.SourceFaces >> l) & 1u)
      {
        piece.SourceFaces |= sides[p][sub[p].Face[l]];
      }
    }
  }
}

/// The tetrahedron's barycentric coordinates on the target's plane (the
/// source's functions on the piece).
inline void PlaneCoordinates(const SurfaceTraceIntersector::Cell& t,
  const SurfaceTraceIntersector::SourceCellType& s, AffineCell<4, 2>& f)
{
  f.Id = s.Id;
  const double d0[3] = { t.Origin[0] - s.X[0][0], t.Origin[1] - s.X[0][1],
    t.Origin[2] - s.X[0][2] };
  for (int k = 0; k < 3; ++k)
  {
    f.Affine[0][k] = k == 0 ? 1.0 : 0.0;
  }
  for (int r = 0; r < 3; ++r)
  {
    const double* inverse = s.Inverse[r];
    f.Affine[r + 1][0] = Dot(inverse, d0);
    f.Affine[r + 1][1] = Dot(inverse, t.Axis[0]);
    f.Affine[r + 1][2] = Dot(inverse, t.Axis[1]);
    for (int k = 0; k < 3; ++k)
    {
      f.Affine[0][k] -= f.Affine[r + 1][k];
    }
  }
  std::copy(s.Points, s.Points + 4, f.Points);
}

/**
 * A target segment clipped by a source cell's faces, one face at a time:
 * the interval [Lo, Hi] of its axis left inside, where each face cuts it,
 * and the faces whose plane holds it.
 */
template <int N>
struct SegmentClip
{
  double Lo = 0.0;
  double Hi = 0.0;
  double Cut[N];
  bool Cuts[N];
  unsigned On = 0;          ///< faces whose plane holds the segment
  unsigned GenericSide = 0; ///< of those, the ones the generic direction points into the cell from
};

/// Face k's plane (line): a normal from its corners in the order of their
/// ids, the first corner, and the orientation of the face with corner k
/// (0: a flat cell).
template <int D, int N, class SourceCell>
inline double FacePlane(const SourceCell& s, int k, double normal[3], const double*& v0)
{
  // Face k (opposite corner k), its corners in the order of their ids.
  int f[D];
  int nf = 0;
  for (int j = 0; j < N; ++j)
  {
    if (j != k)
    {
      f[nf++] = j;
    }
  }
  std::sort(f, f + D, [&s](int a, int b) { return s.Points[a] < s.Points[b]; });
  v0 = s.X[f[0]];
  if constexpr (D == 3)
  {
    const double* v1 = s.X[f[1]];
    const double* v2 = s.X[f[2]];
    double e1[3];
    double e2[3];
    Sub(v1, v0, e1);
    Sub(v2, v0, e2);
    Cross(e1, e2, normal);
    return Orient3D(v0, v1, v2, s.X[k]);
  }
  else
  {
    const double* v1 = s.X[f[1]];
    normal[0] = -(v1[1] - v0[1]);
    normal[1] = v1[0] - v0[0];
    return Orient2D(v0, v1, s.X[k]);
  }
}

/// Clips the segment by face k's half-space; false when the segment lies
/// wholly outside it (or the cell is flat).
template <int D, int N, class SourceCell>
inline bool ClipByFace(const SegmentIntersector::Cell& t, const SourceCell& s, int k, double length,
  SegmentClip<N>& clip)
{
  clip.Cuts[k] = false;
  double normal[3] = { 0.0, 0.0, 0.0 };
  const double* v0 = nullptr;
  const double side = FacePlane<D, N>(s, k, normal, v0);
  if (!(side != 0.0))
  {
    return false;
  }
  double ga = 0.0;
  double gb = 0.0;
  double toward = 0.0;
  double nn = 0.0;
  for (int d = 0; d < D; ++d)
  {
    ga += normal[d] * (t.Corner[0][d] - v0[d]);
    gb += normal[d] * (t.Corner[1][d] - v0[d]);
    toward += normal[d] * Generic[d];
    nn += normal[d] * normal[d];
  }
  // An end within 1e-10 of the segment's and the face's size from the
  // face's plane lies on it (decided once per face: the same in both cells).
  nn = std::sqrt(nn);
  const double size = length + (D == 3 ? std::sqrt(nn) : nn);
  const double snap = HeightTolerance * size * nn;
  ga = std::fabs(ga) <= snap ? 0.0 : ga;
  gb = std::fabs(gb) <= snap ? 0.0 : gb;
  const double sign = side > 0.0 ? 1.0 : -1.0;
  const double ia = sign * ga; // >= 0: end a on the cell's side
  const double ib = sign * gb;
  if (ia >= 0.0 && ib >= 0.0)
  {
    if (ia == 0.0 && ib == 0.0)
    {
      clip.On |= 1u << k;
      clip.GenericSide |= unsigned(sign * toward > 0.0) << k;
    }
    return true;
  }
  if (ia < 0.0 && ib < 0.0)
  {
    return false;
  }
  // Where the segment crosses the face's plane: from the face's own
  // values, the same in both cells that share it.
  const double u = length * (ga / (ga - gb));
  clip.Cuts[k] = true;
  clip.Cut[k] = u;
  if (ia >= 0.0)
  {
    clip.Hi = std::min(clip.Hi, u);
  }
  else
  {
    clip.Lo = std::max(clip.Lo, u);
  }
  return true;
}

/**
 * Whether the cell owns a segment lying in the planes of some of its faces
 * (`on`; none: it owns its interval). A segment in the planes of some faces
 * (on a face, or along an edge) belongs to one of the cells holding it: on
 * a face, to the one the generic direction points into, or the only one on
 * the boundary; along an edge, where no cell knows whether the edge is on
 * the boundary (the generic direction may point out of the mesh there),
 * every cell around it claims it (Tied: piece.Edge set) and the assembler
 * keeps one. The others touch it (a piece without length): the front
 * passes on.
 */
template <int D, int N, class SourceCell, class Piece>
inline bool OwnsSegment(const SourceCell& s, unsigned on, unsigned generic, Piece& piece)
{
  const int planes = ((on & 1u) != 0) + ((on & 2u) != 0) + ((on & 4u) != 0) + ((on & 8u) != 0);
  const bool boundary = (on & s.Boundary) != 0;
  piece.Tied = D == 3 && planes >= 2;
  const bool owned = planes == 0 || piece.Tied || generic == on || boundary;
  if (piece.Tied)
  {
    // The edge: the corners not opposite the two faces.
    int e = 0;
    for (int k = 0; k < N && e < 2; ++k)
    {
      if (!((on >> k) & 1u) || planes > 2)
      {
        piece.Edge[e++] = s.Points[k];
      }
    }
    if (piece.Edge[0] > piece.Edge[1])
    {
      std::swap(piece.Edge[0], piece.Edge[1]);
    }
  }
  return owned;
}

/// The cell's barycentric coordinates along the target's axis (the
/// source's functions on the piece).
template <int D, int N, class SourceCell>
inline void AxisCoordinates(
  const SegmentIntersector::Cell& t, const SourceCell& s, AffineCell<N, 1>& a)
{
  a.Id = s.Id;
  std::copy(s.Points, s.Points + N, a.Points);
  a.Affine[0][0] = 1.0;
  a.Affine[0][1] = 0.0;
  for (int r = 0; r < D; ++r)
  {
    double constant = 0.0;
    double slope = 0.0;
    for (int d = 0; d < D; ++d)
    {
      constant += s.Inverse[r][d] * (t.Origin[d] - s.X[0][d]);
      slope += s.Inverse[r][d] * t.Axis[d];
    }
    a.Affine[r + 1][0] = constant;
    a.Affine[r + 1][1] = slope;
    a.Affine[0][0] -= constant;
    a.Affine[0][1] -= slope;
  }
}
} // namespace

void SurfaceTraceIntersector::Bounds(const Cell& cell, double box[6])
{
  WidenBox(cell.Box3, HeightTolerance * Extent(cell.Box3), box);
}

bool SurfaceTraceIntersector::Intersect(const Cell& t, const SourceCellType& s, Piece& piece)
{
  piece.NumberOfParts = 0;
  piece.TouchedFaces = 0;
  piece.SourceFaces = 0;
  piece.Target = &t;
  const double tolerance = HeightTolerance * Extent(t.Box3);
  if (!BoxesWithinReach(t.Box3, s.Box, tolerance))
  {
    return false;
  }
  CornerHeights c;
  MeasureHeights(t, s, tolerance, c);
  if (c.Up == 0 || c.Up == 4)
  {
    return c.Zeros > 0 && Touches(t, c, piece);
  }
  CrossSection x;
  CrossedEdges(c, x);
  Crossings(s, c, x);
  CutByCrossSection(t, s, x, piece);
  if (piece.NumberOfParts == 0)
  {
    // A cross-section without area: the tetrahedron touches the plane.
    return c.Zeros > 0 && Touches(t, c, piece);
  }
  if (Measure(piece) < SliverFraction * t.Measure)
  {
    // A sliver of rounding size (where the facet and the tetrahedron only
    // touch): no measure, as for the tetrahedra (TetrahedronIntersector),
    // but the front passes on through its faces.
    piece.NumberOfParts = 0;
    return true;
  }
  PlaneCoordinates(t, s, piece.Source);
  return true;
}

double SurfaceTraceIntersector::Moments(const Piece& piece, double (&origin)[2], double (&M)[3][3])
{
  double total = 0.0;
  for (int p = 0; p < piece.NumberOfParts; ++p)
  {
    double o[2];
    double m[3][3];
    const double area = TriangleIntersector::Moments(piece.Parts[p], o, m);
    if (!(area > 0.0))
    {
      continue;
    }
    if (total == 0.0)
    {
      origin[0] = o[0];
      origin[1] = o[1];
      for (auto& row : M)
      {
        std::fill(row, row + 3, 0.0);
      }
    }
    const double shift[2] = { o[0] - origin[0], o[1] - origin[1] };
    AddShiftedMoments<3>(m, shift, M);
    total += area;
  }
  return total;
}

double SurfaceTraceIntersector::Measure(const Piece& piece)
{
  double total = 0.0;
  for (int p = 0; p < piece.NumberOfParts; ++p)
  {
    total += TriangleIntersector::Measure(piece.Parts[p]);
  }
  return total;
}

void SurfaceTraceIntersector::AppendPiece(
  const Piece& piece, Index target, Index source, IntersectionPieces& pieces)
{
  for (int p = 0; p < piece.NumberOfParts; ++p)
  {
    if (piece.Parts[p].NumberOfVertices >= 3)
    {
      SurfaceIntersector::AppendPolygon(*piece.Target, piece.Parts[p], target, source, pieces);
    }
  }
}

template <class Base>
bool CurveTraceIntersector<Base>::Prepare(const MeshView& mesh, Index id, Cell& cell)
{
  return SegmentIntersector::Prepare(mesh, id, cell);
}

template <class Base>
void CurveTraceIntersector<Base>::Bounds(const Cell& cell, double box[6])
{
  WidenBox(cell.Box3, HeightTolerance * cell.Measure, box);
}

template <class Base>
bool CurveTraceIntersector<Base>::Intersect(const Cell& t, const SourceCellType& s, Piece& piece)
{
  constexpr int D = SpaceDimension;
  constexpr int N = Base::Corners;
  piece.NumberOfVertices = 0;
  piece.TouchedFaces = 0;
  piece.SourceFaces = 0;
  piece.Target = &t;
  const double tolerance = HeightTolerance * t.Measure;
  for (int d = 0; d < D; ++d)
  {
    if (s.Box[2 * d] > t.Box3[2 * d + 1] + tolerance ||
      s.Box[2 * d + 1] < t.Box3[2 * d] - tolerance)
    {
      return false;
    }
  }
  const double length = t.X[1][0];
  SegmentClip<N> clip;
  clip.Hi = length;
  for (int k = 0; k < N; ++k)
  {
    if (!ClipByFace<D, N>(t, s, k, length, clip))
    {
      return false;
    }
  }
  double lo = clip.Lo;
  double hi = clip.Hi;
  // Cuts through one vertex or edge of the cell come from different faces,
  // so they differ by rounding: within `tolerance` the cell touches the
  // segment there (a piece without length), and the front passes on to the
  // neighbours across all faces through that point.
  if (!(lo <= hi + tolerance))
  {
    return false;
  }
  if (!OwnsSegment<D, N>(s, clip.On, clip.GenericSide, piece))
  {
    hi = lo;
  }
  // Shorter than a rounding sliver: no length (the front still passes on).
  piece.NumberOfVertices = hi - lo > SliverFraction * length ? 2 : 1;
  piece.X[0][0] = lo;
  piece.X[1][0] = std::max(lo, hi);
  // Face k of the target is its corner 1 - k.
  piece.TouchedFaces = (hi >= length - tolerance ? 1u : 0u) | (lo <= tolerance ? 2u : 0u);
  piece.SourceFaces = clip.On;
  for (int k = 0; k < N; ++k)
  {
    if (clip.Cuts[k] &&
      (std::fabs(clip.Cut[k] - lo) <= tolerance || std::fabs(clip.Cut[k] - hi) <= tolerance))
    {
      piece.SourceFaces |= 1u << k;
    }
  }
  AxisCoordinates<D, N>(t, s, piece.Source);
  return true;
}

template <class Base>
double CurveTraceIntersector<Base>::Measure(const Piece& piece)
{
  return piece.NumberOfVertices == 2 ? piece.X[1][0] - piece.X[0][0] : 0.0;
}

template <class Base>
double CurveTraceIntersector<Base>::Moments(
  const Piece& piece, double (&origin)[1], double (&M)[2][2])
{
  return SegmentIntersector::IntervalMoments(piece.NumberOfVertices, piece.X, origin, M);
}

template <class Base>
void CurveTraceIntersector<Base>::AppendPiece(
  const Piece& piece, Index target, Index source, IntersectionPieces& pieces)
{
  SegmentIntersector::AppendInterval(
    *piece.Target, piece.NumberOfVertices, piece.X, target, source, pieces);
}

template class CurveTraceIntersector<TriangleIntersector>;
template class CurveTraceIntersector<TetrahedronIntersector>;
} // namespace mp
