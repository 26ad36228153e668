// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/TriangleIntersector.h"

#include "Geometry/IntersectionPieces.h"
#include "Geometry/Lanes.h"
#include "Geometry/Predicates.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace mp
{
namespace
{
// A monotone function of the angle of (dx, dy), in [0, 4): cheaper than
// atan2 and enough to order points around an interior point.
inline double PseudoAngle(double dx, double dy)
{
  const double r = std::fabs(dx) + std::fabs(dy);
  if (r == 0.0)
  {
    return 0.0;
  }
  const double p = dy / r;
  if (dx < 0.0)
  {
    return 2.0 - p;
  }
  return dy < 0.0 ? 4.0 + p : p;
}

// Stores the n ordered points as the piece's vertices, each only when it
// differs from the one before (and the last when it differs from the first).
// A point left out equals the last one kept, so each is compared with its
// predecessor in `ordered` (not with the last one stored: that comparison
// waited for the store before it, a chain through every vertex).
void StoreWithoutRepeats(const double (*ordered)[2], int n, TriangleIntersector::Piece& p)
{
  p.X[0][0] = ordered[0][0];
  p.X[0][1] = ordered[0][1];
  int m = 1;
  for (int i = 1; i < n; ++i)
  {
    p.X[m][0] = ordered[i][0];
    p.X[m][1] = ordered[i][1];
    m += (ordered[i][0] != ordered[i - 1][0]) | (ordered[i][1] != ordered[i - 1][1]);
  }
  if (m > 2 && ordered[n - 1][0] == ordered[0][0] && ordered[n - 1][1] == ordered[0][1])
  {
    --m;
  }
  p.NumberOfVertices = m;
}

// Orders the points counterclockwise around their mean and drops exact
// duplicates (a crossing that rounds onto another point).
//
// There are at most 6 points: each is a vertex of the convex piece (corners
// of one cell in the other, proper edge crossings, all decided exactly; a
// corner shared by both cells is taken once), and a convex polygon cut from
// two triangles has at most 6 vertices. When the piece has an interior, no
// two of them have the same angle around the mean unless they are equal. Each key is the
// pseudo-angle with the point's index in its lowest bits (non-negative
// doubles order like their bit patterns); a 6-input sorting network orders
// them without data-dependent branches, and equal points end up adjacent.
void SortAndRemoveDoubles(TriangleIntersector::Piece& p)
{
  const int n = p.NumberOfVertices;
  if (n < 2)
  {
    return;
  }
  double cx = 0.0;
  double cy = 0.0;
  for (int i = 0; i < n; ++i)
  {
    cx += p.X[i][0];
    cy += p.X[i][1];
  }
  cx /= n;
  cy /= n;
  std::uint64_t key[6];
  for (int i = 0; i < 6; ++i)
  {
    if (i < n)
    {
      const double angle = PseudoAngle(p.X[i][0] - cx, p.X[i][1] - cy); // in [0, 4]
      std::uint64_t bits;
      std::memcpy(&bits, &angle, sizeof bits);
      key[i] = (bits & ~std::uint64_t(7)) | std::uint64_t(i);
    }
    else
    {
      key[i] = ~std::uint64_t(0);
    }
  }
  auto exchange = [&key](int i, int j) {
    const std::uint64_t a = key[i];
    const std::uint64_t b = key[j];
    key[i] = a < b ? a : b;
    key[j] = a < b ? b : a;
  };
  exchange(0, 5);
  exchange(1, 3);
  exchange(2, 4);
  exchange(1, 2);
  exchange(3, 4);
  exchange(0, 3);
  exchange(2, 5);
  exchange(0, 1);
  exchange(2, 3);
  exchange(4, 5);
  exchange(1, 2);
  exchange(3, 4);
  double sorted[6][2];
  for (int i = 0; i < n; ++i)
  {
    const int from = static_cast<int>(key[i] & 7u);
    sorted[i][0] = p.X[from][0];
    sorted[i][1] = p.X[from][1];
  }
  StoreWithoutRepeats(sorted, n, p);
}

/**
 * Orders the vertices of a piece in general position (no corner of either
 * cell on a line of the other's edges) by the edges they lie on, without
 * sorting: each vertex lies on two of the six edge lines (0-2 the target's,
 * 3-5 the source's), one along which the piece's boundary arrives (`in`) and
 * one along which it leaves (`out`), both cells and the piece traversed
 * counterclockwise. A convex piece has at most one edge on each line, so the
 * vertex after v is the one arriving along v's leaving line. The labels
 * come from exact signs, so the order is exact even where rounded crossings
 * nearly coincide. Returns false (the piece untouched) unless the labels
 * chain all the vertices into one cycle; drops rounded crossings equal to
 * their predecessor.
 */
bool ChainByEdges(TriangleIntersector::Piece& p, const unsigned char* in, const unsigned char* out)
{
  const int n = p.NumberOfVertices;
  if (n < 3 || n > 6)
  {
    return false;
  }
  signed char arriving[6] = { -1, -1, -1, -1, -1, -1 };
  for (int v = 0; v < n; ++v)
  {
    arriving[in[v]] = static_cast<signed char>(v);
  }
  double ordered[6][2];
  int v = 0;
  for (int i = 0; i < n; ++i)
  {
    ordered[i][0] = p.X[v][0];
    ordered[i][1] = p.X[v][1];
    v = arriving[out[v]];
    // One cycle through all n vertices: back at the first only at the end.
    if (v < 0 || (v == 0) != (i == n - 1))
    {
      return false;
    }
  }
  StoreWithoutRepeats(ordered, n, p);
  return true;
}

/**
 * o[k][j] = Orient2D(a[k], b[k], c[j]) for 3 lines and 3 points, with one
 * floating-point filter for all nine (Predicates.h): the nine determinants
 * and their error bounds are computed without branches, and only when one is
 * within its bound are the undecided ones recomputed exactly.
 */
inline void Orient3x3(const double (&x)[3][2], const double (&c)[3][2], double (&o)[3][3])
{
  // The three points as the lanes of two vectors per coordinate (points
  // 0-1, and 2 twice), so that each line's determinants and filters are
  // two vector expressions (Lanes.h):
  // the same operations in the same order as one at a time, the same
  // values. Scalar, these 18 filtered orientations per pair were an eighth
  // of a 2D run's instructions.
  constexpr double bound = (3.0 + 16.0 * RoundingUnit) * RoundingUnit;
  const Doubles2 cx[2] = { { c[0][0], c[1][0] }, { c[2][0], c[2][0] } };
  const Doubles2 cy[2] = { { c[0][1], c[1][1] }, { c[2][1], c[2][1] } };
  Mask2 decidedLanes = { -1, -1 };
  for (int k = 0; k < 3; ++k)
  {
    const double* a = x[(k + 1) % 3];
    const double* b = x[(k + 2) % 3];
    for (int h = 0; h < 2; ++h)
    {
      const Doubles2 left = (a[0] - cx[h]) * (b[1] - cy[h]);
      const Doubles2 right = (a[1] - cy[h]) * (b[0] - cx[h]);
      const Doubles2 det = left - right;
      o[k][2 * h] = det[0];
      if (h == 0)
      {
        o[k][1] = det[1];
      }
      decidedLanes &= Magnitude(det) > bound * (Magnitude(left) + Magnitude(right));
    }
  }
  const bool decided = (decidedLanes[0] & decidedLanes[1]) != 0;
  if (decided)
  {
    return;
  }
  for (int k = 0; k < 3; ++k)
  {
    for (int j = 0; j < 3; ++j)
    {
      o[k][j] = Orient2D(x[(k + 1) % 3], x[(k + 2) % 3], c[j]);
    }
  }
}

/**
 * Bits 3k + j of pos, neg: o[k][j] > 0, < 0 (a NaN: neither). Entries 0-1
 * of a row as one vector, their signs by SSE2 movemask (generic code
 * elsewhere); compared one by one, these were a visible share of a 2D
 * run's instructions.
 */
inline void SignBits3x3(const double (&o)[3][3], unsigned& pos, unsigned& neg)
{
  pos = 0;
  neg = 0;
  for (int k = 0; k < 3; ++k)
  {
    const Doubles2 r = LoadLanes(&o[k][0]);
    pos |= (LaneBits(r > 0.0) | static_cast<unsigned>(o[k][2] > 0.0) << 2) << (3 * k);
    neg |= (LaneBits(r < 0.0) | static_cast<unsigned>(o[k][2] < 0.0) << 2) << (3 * k);
  }
}

/**
 * Where target edge a-b and source edge c-d cross (properly), given the
 * sides oa, ob of a, b w.r.t. the line of c-d and oc, od of c, d w.r.t. the
 * line of a-b (each pair strictly of opposite signs).
 *
 * Their signs are exact, but a determinant the filter decided is only the
 * rounded one, whose error (below 2^-51 of the sum of its two products'
 * magnitudes, its scale) is large relative to it when a point lies very
 * near the line; so then is the error of the crossing's place along the
 * edge (on nearly parallel edges, a few percent of a piece's area were
 * seen). A determinant below `limit` (2^-19 D^2, D the extent of both
 * cells' boxes together: at least 2^-20 of its scale, since a scale is at
 * most 2 D^2) is recomputed exactly with its partner, so that each one used
 * is within about 2^-31 of its value.
 *
 * Placed along an edge, the point's error is about the rounding unit u
 * times the edge's length (the error of u times it), and the rounded
 * orientations' errors (about u D^2) add about u D^2 / |o| of it. For
 * cells of similar sizes both stay within rounding of the cells. For a
 * small cell (size h) and a huge one (size L: `careful`, one box more than
 * 16 times the other) the first is up to u L along a huge edge, and the
 * second u L / h relative, since the orientations are about L h: both
 * could exceed the small cell. The point is then placed along the shorter
 * edge, from exact orientations.
 */
inline void Crossing(const double* a, const double* b, double oa, double ob, const double* c,
  const double* d, double oc, double od, double limit, bool careful, double (&x)[2])
{
  if (careful &&
    (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) <
      (d[0] - c[0]) * (d[0] - c[0]) + (d[1] - c[1]) * (d[1] - c[1]))
  {
    std::swap(a, c); // along the target edge a-b, across the line of c-d
    std::swap(b, d);
    std::swap(oa, oc);
    std::swap(ob, od);
  }
  if (careful || std::fabs(oc) < limit || std::fabs(od) < limit)
  {
    oc = Orient2DExact(a, b, c);
    od = Orient2DExact(a, b, d);
  }
  const double u = oc / (oc - od);
  x[0] = c[0] + u * (d[0] - c[0]);
  x[1] = c[1] + u * (d[1] - c[1]);
}

} // namespace

bool TriangleIntersector::Prepare(const MeshView& mesh, Index id, Cell& cell)
{
  const CellCorners ids = mesh.Cell(id);
  cell.Id = id;
  for (int k = 0; k < 3; ++k)
  {
    const double* x = mesh.Point(ids[k]);
    cell.Points[k] = ids[k];
    cell.Face[k] = k;
    cell.X[k][0] = x[0];
    cell.X[k][1] = x[1];
  }
  return PrepareCorners(cell);
}

bool TriangleIntersector::PrepareCorners(Cell& cell)
{
  double twiceArea = Orient2D(cell.X[0], cell.X[1], cell.X[2]);
  if (!(twiceArea != 0.0) || !std::isfinite(twiceArea))
  {
    return false;
  }
  if (twiceArea < 0.0) // clockwise: swap corners 1 and 2 (and their faces)
  {
    std::swap(cell.Points[1], cell.Points[2]);
    std::swap(cell.Face[1], cell.Face[2]);
    std::swap(cell.X[1][0], cell.X[2][0]);
    std::swap(cell.X[1][1], cell.X[2][1]);
    twiceArea = -twiceArea;
  }
  cell.Box[0] = std::min({ cell.X[0][0], cell.X[1][0], cell.X[2][0] });
  cell.Box[1] = std::max({ cell.X[0][0], cell.X[1][0], cell.X[2][0] });
  cell.Box[2] = std::min({ cell.X[0][1], cell.X[1][1], cell.X[2][1] });
  cell.Box[3] = std::max({ cell.X[0][1], cell.X[1][1], cell.X[2][1] });
  // Jacobian J = [X1 - X0, X2 - X0]; barycentrics 1, 2 = J^-1 (x - X0).
  const double j00 = cell.X[1][0] - cell.X[0][0];
  const double j01 = cell.X[2][0] - cell.X[0][0];
  const double j10 = cell.X[1][1] - cell.X[0][1];
  const double j11 = cell.X[2][1] - cell.X[0][1];
  const double det = j00 * j11 - j01 * j10;
  cell.Measure = 0.5 * std::fabs(det);
  const double inverse = 1.0 / det;
  cell.Inverse[0][0] = j11 * inverse;
  cell.Inverse[0][1] = -j01 * inverse;
  cell.Inverse[1][0] = -j10 * inverse;
  cell.Inverse[1][1] = j00 * inverse;
  return cell.Measure > 0.0 &&
    std::isfinite(
      cell.Inverse[0][0] + cell.Inverse[0][1] + cell.Inverse[1][0] + cell.Inverse[1][1]);
}

void TriangleIntersector::Bounds(const Cell& cell, double box[6])
{
  box[0] = cell.Box[0];
  box[1] = cell.Box[1];
  box[2] = cell.Box[2];
  box[3] = cell.Box[3];
  box[4] = 0.0;
  box[5] = 0.0;
}

void TriangleIntersector::Center(const Cell& cell, double q[2])
{
  for (int d = 0; d < 2; ++d)
  {
    q[d] = (cell.X[0][d] + cell.X[1][d] + cell.X[2][d]) / 3.0;
  }
}

int TriangleIntersector::Locate(const Cell& cell, const double* q, int first)
{
  for (int i = 0; i < 3; ++i)
  {
    const int k = (first + i) % 3;
    if (Orient2D(cell.X[(k + 1) % 3], cell.X[(k + 2) % 3], q) < 0.0)
    {
      return k;
    }
  }
  return -1;
}

bool TriangleIntersector::Intersect(const Cell& t, const Cell& s, Piece& piece)
{
  piece.NumberOfVertices = 0;
  piece.TouchedFaces = 0;
  piece.SourceFaces = 0;
  // Cheap rejection (the paper's conclusion): disjoint closed bounding boxes.
  if (t.Box[1] < s.Box[0] || s.Box[1] < t.Box[0] || t.Box[3] < s.Box[2] || s.Box[3] < t.Box[2])
  {
    return false;
  }

  // ot[k][j]: side of source corner j w.r.t. target edge k (corners k+1, k+2),
  // os[l][i]: side of target corner i w.r.t. source edge l. Positive = inside.
  double ot[3][3];
  double os[3][3];
  Orient3x3(t.X, s.X, ot);
  Orient3x3(s.X, t.X, os);
  // Sign masks, bit 3k + j for entry [k][j].
  unsigned posT = 0;
  unsigned negT = 0;
  unsigned posS = 0;
  unsigned negS = 0;
  SignBits3x3(ot, posT, negT);
  SignBits3x3(os, posS, negS);
  // Separating edge: all three corners of the other cell strictly outside.
  constexpr unsigned row = 7u;
  if (((negT & row) == row) | (((negT >> 3) & row) == row) | (((negT >> 6) & row) == row) |
    ((negS & row) == row) | (((negS >> 3) & row) == row) | (((negS >> 6) & row) == row))
  {
    return false;
  }
  constexpr unsigned column = 1u | 8u | 64u; // entries [0][0], [1][0], [2][0]
  // Each vertex's edge lines, arriving and leaving (ChainByEdges): target
  // edge k is line k, source edge l line 3 + l; edge k runs from corner
  // k + 1 to corner k + 2, so corner i is reached along edge i + 1 and left
  // along edge i + 2.
  unsigned char in[MaxPolygonVertices];
  unsigned char out[MaxPolygonVertices];
  int n = 0;
  auto add = [&piece, &in, &out, &n](double x, double y, unsigned arriving, unsigned leaving) {
    piece.X[n][0] = x;
    piece.X[n][1] = y;
    in[n] = static_cast<unsigned char>(arriving);
    out[n] = static_cast<unsigned char>(leaving);
    ++n;
  };
  // Corners of the target in the closed source: they lie on the two target
  // faces that meet at that corner, and on the source faces they are on.
  const unsigned zeroS = ~(posS | negS);
  unsigned targetInside = 0;
  for (int i = 0; i < 3; ++i)
  {
    if (!(negS & (column << i)))
    {
      targetInside |= 1u << i;
      add(t.X[i][0], t.X[i][1], (i + 1) % 3, (i + 2) % 3);
      piece.TouchedFaces |= 7u & ~(1u << i);
      const unsigned on = (zeroS >> i) & column; // bits 0, 3, 6: on source edge 0, 1, 2
      piece.SourceFaces |= (on & 1u) | ((on >> 2) & 2u) | ((on >> 4) & 4u);
    }
  }
  // Corners of the source in the closed target (skipping one equal to a
  // target corner already added); one on target edge k touches face k.
  const unsigned zeroT = ~(posT | negT);
  for (int j = 0; j < 3; ++j)
  {
    if (negT & (column << j))
    {
      continue;
    }
    piece.SourceFaces |= 7u & ~(1u << j); // the source edges at corner j
    const unsigned on = (zeroT >> j) & column;
    piece.TouchedFaces |= (on & 1u) | ((on >> 2) & 2u) | ((on >> 4) & 4u);
    bool known = false;
    for (int i = 0; i < 3; ++i)
    {
      known |= ((targetInside >> i) & 1u) && t.X[i][0] == s.X[j][0] && t.X[i][1] == s.X[j][1];
    }
    if (!known)
    {
      add(s.X[j][0], s.X[j][1], 3 + (j + 1) % 3, 3 + (j + 2) % 3);
    }
  }
  // Proper crossings: both pairs of end points strictly on opposite sides.
  // Every touching configuration is already covered by the corner tests.
  // straddleT bit 3k + l: source edge l's corners (l+1, l+2) are strictly on
  // opposite sides of target edge k; straddleS bit 3l + k likewise.
  auto straddle = [](unsigned pos, unsigned neg) {
    // Bit 3k + l of rot1(m), rot2(m): entry (l + 1) % 3, (l + 2) % 3 of row k.
    auto rot1 = [](unsigned m) { return ((m >> 1) & 0xDBu) | ((m << 2) & 0x124u); };
    auto rot2 = [](unsigned m) { return ((m >> 2) & 0x49u) | ((m << 1) & 0x1B6u); };
    return (rot1(pos) & rot2(neg)) | (rot1(neg) & rot2(pos));
  };
  const unsigned straddleT = straddle(posT, negT);
  const unsigned straddleS = straddle(posS, negS);
  // Crossings' determinants below this are recomputed exactly (Crossing).
  double extent = std::max(t.Box[1], s.Box[1]) - std::min(t.Box[0], s.Box[0]);
  extent = std::max(extent, std::max(t.Box[3], s.Box[3]) - std::min(t.Box[2], s.Box[2]));
  const double limit = 0x1p-19 * extent * extent;
  // Cells of very different sizes: crossings placed carefully.
  const double sourceSize = std::max(s.Box[1] - s.Box[0], s.Box[3] - s.Box[2]);
  const double targetSize = std::max(t.Box[1] - t.Box[0], t.Box[3] - t.Box[2]);
  const bool careful = sourceSize > 16.0 * targetSize || targetSize > 16.0 * sourceSize;
  // The crossings as bits 3k + l (straddleS transposed: bit 3l + k to
  // 3k + l), visited lowest first: the order of a loop over k and l,
  // without its test per pair of edges (unpredictable, it was among the
  // most mispredicted branches of a 2D run's intersections).
  const unsigned transposed = (straddleS & 0x111u) | ((straddleS & 0x022u) << 2) |
    ((straddleS & 0x088u) >> 2) | ((straddleS & 0x004u) << 4) | ((straddleS & 0x040u) >> 4);
  for (unsigned crossings = straddleT & transposed & 0x1FFu; crossings != 0;
       crossings &= crossings - 1)
  {
    const int bit = __builtin_ctz(crossings);
    const int k = bit / 3;
    const int l = bit % 3;
    const int ci = (l + 1) % 3;
    const int di = (l + 2) % 3;
    double x[2];
    const int ai = (k + 1) % 3;
    const int bi = (k + 2) % 3;
    Crossing(t.X[ai], t.X[bi], os[l][ai], os[l][bi], s.X[ci], s.X[di], ot[k][ci], ot[k][di], limit,
      careful, x);
    // Source edge l entering the target's side of edge k (c outside):
    // the piece arrives along target edge k and leaves along l; leaving
    // it, the other way round.
    const unsigned entering = ot[k][ci] < 0.0;
    const unsigned target = static_cast<unsigned>(k);
    const unsigned source = static_cast<unsigned>(3 + l);
    add(x[0], x[1], entering ? target : source, entering ? source : target);
    piece.TouchedFaces |= 1u << k;
    piece.SourceFaces |= 1u << l;
  }
  piece.NumberOfVertices = n;
  if (piece.NumberOfVertices == 0)
  {
    return false;
  }
  // In general position (no orientation zero) the labels order the piece;
  // a corner on a line of the other cell (shared points, touching cells)
  // can put several vertices on one point or line: sorted by angle.
  constexpr unsigned all = 0x1FFu;
  if (((zeroS | zeroT) & all) == 0 && ChainByEdges(piece, in, out))
  {
    return true;
  }
  SortAndRemoveDoubles(piece);
  return true;
}

double TriangleIntersector::Measure(const Piece& p)
{
  double twice = 0.0;
  for (int i = 1; i + 1 < p.NumberOfVertices; ++i)
  {
    const double ax = p.X[i][0] - p.X[0][0];
    const double ay = p.X[i][1] - p.X[0][1];
    const double bx = p.X[i + 1][0] - p.X[0][0];
    const double by = p.X[i + 1][1] - p.X[0][1];
    twice += ax * by - ay * bx;
  }
  return 0.5 * twice;
}

void TriangleIntersector::AppendPiece(
  const Piece& p, Index target, Index source, IntersectionPieces& pieces)
{
  for (int v = 0; v < p.NumberOfVertices; ++v)
  {
    pieces.Points.insert(pieces.Points.end(), { p.X[v][0], p.X[v][1], 0.0 });
  }
  pieces.Offsets.push_back(pieces.Offsets.back() + p.NumberOfVertices);
  pieces.TargetCell.push_back(target);
  pieces.SourceCell.push_back(source);
  pieces.Measure.push_back(Measure(p));
}
} // namespace mp
