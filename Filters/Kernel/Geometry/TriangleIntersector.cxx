// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/TriangleIntersector.h"

#include "Geometry/IntersectionPieces.h"
#include "Geometry/Predicates.h"
#include "Geometry/TriangleSides.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace mp
{
namespace
{
using namespace triangle;

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
 * The piece of t and s whose boxes overlap, from the exactly evaluated sides
 * of all corners (Orient3x3), any configuration: corners on the other's
 * edges, shared corners, touching cells. Returns false when they do not
 * meet. The route of the pairs GeneralPiece does not take (not inlined:
 * its registers and stack would burden that route's).
 */
__attribute__((noinline)) bool AnyPiece(const TriangleIntersector::Cell& t,
  const TriangleIntersector::Cell& s, const Placement& place, TriangleIntersector::Piece& piece)
{
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
  double sides[18]; // both in the layout of FilteredSides, for Crossing
  for (int k = 0; k < 3; ++k)
  {
    for (int j = 0; j < 3; ++j)
    {
      sides[2 * (3 * k + j)] = ot[k][j];
      sides[2 * (3 * k + j) + 1] = os[k][j];
    }
  }
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
  unsigned char in[TriangleIntersector::MaxPolygonVertices];
  unsigned char out[TriangleIntersector::MaxPolygonVertices];
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
  // Visited lowest bit first: the order of a loop over k and l, without
  // its test per pair of edges (unpredictable, it was among the most
  // mispredicted branches of a 2D run's intersections).
  for (unsigned crossings = ProperCrossings(posT, negT, posS, negS); crossings != 0;
       crossings &= crossings - 1)
  {
    const EdgePair& e = EdgePairs[__builtin_ctz(crossings)];
    double x[2];
    Crossing(t, s, e, sides, place, x);
    // Source edge l entering the target's side of edge k (c outside):
    // the piece arrives along target edge k and leaves along l; leaving
    // it, the other way round.
    const unsigned entering = ot[e.K][e.C] < 0.0;
    const unsigned target = e.K;
    const unsigned source = 3u + e.L;
    add(x[0], x[1], entering ? target : source, entering ? source : target);
    piece.TouchedFaces |= 1u << e.K;
    piece.SourceFaces |= 1u << e.L;
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

/// Bit (i + 1) % 3 of the result: bit i of a 3-bit mask (corner i's line).
inline unsigned ArrivingLines(unsigned corners)
{
  return ((corners << 1) | (corners >> 2)) & 7u;
}

/**
 * The rest of GeneralPiece: the crossings (bits 2 (3k + l) of `crossings`)
 * placed (Crossing) and kept by the line they arrive along, then the walk
 * from line `start`'s vertex along the leaving lines. `at`, `next` and `held` come with the corners:
 * line L's vertex, its leaving line, and the lines that hold one (bit L).
 */
int ChainPiece(const TriangleIntersector::Cell& t, const TriangleIntersector::Cell& s,
  const double (&sides)[18], unsigned negative, unsigned crossings, const Placement& place,
  int start, const double* (&at)[6], unsigned char (&next)[6], unsigned held,
  TriangleIntersector::Piece& piece)
{
  if (start < 0)
  {
    if (crossings == 0)
    {
      return -1; // no vertex: the cells do not meet
    }
    const EdgePair& e = EdgePairs[__builtin_ctz(crossings) >> 1];
    start = (negative >> e.OC) & 1u ? e.K : 3 + e.L; // its arriving line, as below
  }
  double x[6][2];
  unsigned clash = 0; // a line with two vertices: not a chain
  for (; crossings != 0; crossings &= crossings - 1)
  {
    const EdgePair& e = EdgePairs[__builtin_ctz(crossings) >> 1];
    // Source edge l entering the target's side of edge k (c outside):
    // the piece arrives along target edge k and leaves along l; leaving
    // it, the other way round.
    const bool entering = (negative >> e.OC) & 1u;
    const unsigned in = entering ? e.K : 3u + e.L;
    Crossing(t, s, e, sides, place, x[in]);
    at[in] = x[in];
    next[in] = static_cast<unsigned char>(entering ? 3u + e.L : e.K);
    clash |= held & (1u << in);
    held |= 1u << in;
  }
  if (clash != 0)
  {
    return 0;
  }
  // Each vertex stored only when it differs from the one before (a
  // rounded crossing can equal its neighbour), as StoreWithoutRepeats.
  int line = start;
  unsigned seen = 0;
  int steps = 0;
  int m = 0;
  Doubles2 previous = LoadLanes(at[line]);
  do
  {
    const Doubles2 v = LoadLanes(at[line]);
    std::memcpy(piece.X[m], &v, sizeof v);
    m += (m == 0) | (LaneBits(v != previous) != 0);
    previous = v;
    seen |= 1u << line;
    line = next[line];
  } while (++steps < 6 && line != start);
  // One cycle through every vertex, as ChainByEdges asks.
  if (line != start || seen != held || steps < 3)
  {
    return 0;
  }
  m -= m > 2 && LaneBits(previous != LoadLanes(at[start])) == 0;
  piece.NumberOfVertices = m;
  return 1;
}

/**
 * The piece of t and s in general position: the filter decided every side
 * (FilteredSides: `sides` and their negative signs, none zero),
 * so no corner lies on a line of the other cell's edges and AnyPiece's
 * borderline cases cannot arise. Each vertex of the piece arrives along
 * one of the six edge lines (ChainByEdges' labels), and along each line at
 * most one does: the vertices are kept by that line, the corners where they
 * are, and the piece is the walk from line to line, from the vertex
 * AnyPiece would put first, with the same faces touched. Returns 1 with the
 * piece set, -1 when the cells do not meet, 0 when the labels do not chain
 * into one cycle (AnyPiece then sorts).
 */
int GeneralPiece(const TriangleIntersector::Cell& t, const TriangleIntersector::Cell& s,
  const double (&sides)[18], unsigned negative, const Placement& place,
  TriangleIntersector::Piece& piece)
{
  // Separating edge: all three corners of the other cell outside.
  if (AnyRowFull(negative))
  {
    return -1;
  }
  // Corners inside the other cell: no edge of it has them outside.
  const unsigned columns = AnyInColumns(negative);
  const unsigned targetInside = ~EvenOfSix(columns >> 1) & 7u;
  const unsigned sourceInside = ~EvenOfSix(columns) & 7u;
  const unsigned crossings = GeneralCrossings(negative);
  // The faces at the inside corners (all three but the corner's own, per corner).
  constexpr unsigned char faces[8] = { 0, 6, 5, 7, 3, 7, 7, 7 };
  piece.TouchedFaces = faces[targetInside] | AnyInEvenRows(crossings);
  piece.SourceFaces = faces[sourceInside] | EvenOfSix(AnyInColumns(crossings));
  // Line L (target edges 0-2, source edges 3-5) and its vertex: corner i
  // arrives along edge i + 1 and leaves along edge i + 2, so line L holds
  // corner L + 2 and leaves along L + 1.
  const double* at[6] = { t.X[2], t.X[0], t.X[1], s.X[2], s.X[0], s.X[1] };
  unsigned char next[6] = { 1, 2, 0, 4, 5, 3 };
  const unsigned held = ArrivingLines(targetInside) | ArrivingLines(sourceInside) << 3;
  // AnyPiece's first vertex: the first target corner inside, else the
  // first source corner, else the first crossing.
  const int start = targetInside != 0 ? __builtin_ctz(ArrivingLines(targetInside & -targetInside))
    : sourceInside != 0 ? 3 + __builtin_ctz(ArrivingLines(sourceInside & -sourceInside))
                        : -1;
  return ChainPiece(t, s, sides, negative, crossings, place, start, at, next, held, piece);
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

namespace
{
/**
 * The affine map of corners X (counterclockwise): the measure and the
 * inverse Jacobian of PrepareCorners. False for a map that is not
 * invertible in doubles (zero measure, non-finite inverse).
 */
inline bool AffineMap(const double (&X)[3][2], double& measure, double (&inverse)[2][2])
{
  // Jacobian J = [X1 - X0, X2 - X0]; barycentrics 1, 2 = J^-1 (x - X0).
  const double j00 = X[1][0] - X[0][0];
  const double j01 = X[2][0] - X[0][0];
  const double j10 = X[1][1] - X[0][1];
  const double j11 = X[2][1] - X[0][1];
  const double det = j00 * j11 - j01 * j10;
  measure = 0.5 * std::fabs(det);
  const double reciprocal = 1.0 / det;
  inverse[0][0] = j11 * reciprocal;
  inverse[0][1] = -j01 * reciprocal;
  inverse[1][0] = -j10 * reciprocal;
  inverse[1][1] = j00 * reciprocal;
  return measure > 0.0 &&
    std::isfinite(inverse[0][0] + inverse[0][1] + inverse[1][0] + inverse[1][1]);
}

/// Whether twice the signed area (Orient2D, exact in sign) is a cell's:
/// neither zero nor non-finite.
inline bool HasArea(double twiceArea)
{
  return twiceArea != 0.0 && std::isfinite(twiceArea);
}
} // namespace

bool TriangleIntersector::PrepareCorners(Cell& cell)
{
  const double twiceArea = Orient2D(cell.X[0], cell.X[1], cell.X[2]);
  if (!HasArea(twiceArea))
  {
    return false;
  }
  if (twiceArea < 0.0) // clockwise: swap corners 1 and 2 (and their faces)
  {
    std::swap(cell.Points[1], cell.Points[2]);
    std::swap(cell.Face[1], cell.Face[2]);
    std::swap(cell.X[1][0], cell.X[2][0]);
    std::swap(cell.X[1][1], cell.X[2][1]);
  }
  cell.Box[0] = std::min({ cell.X[0][0], cell.X[1][0], cell.X[2][0] });
  cell.Box[1] = std::max({ cell.X[0][0], cell.X[1][0], cell.X[2][0] });
  cell.Box[2] = std::min({ cell.X[0][1], cell.X[1][1], cell.X[2][1] });
  cell.Box[3] = std::max({ cell.X[0][1], cell.X[1][1], cell.X[2][1] });
  const bool invertible = AffineMap(cell.X, cell.Measure, cell.Inverse);
  for (int k = 0; k < 3; ++k)
  {
    const double* a = cell.X[(k + 1) % 3];
    const double* b = cell.X[(k + 2) % 3];
    cell.Edge[k][0] = b[0] - a[0];
    cell.Edge[k][1] = b[1] - a[1];
    cell.EdgeSize[k] = std::fabs(cell.Edge[k][0]) + std::fabs(cell.Edge[k][1]);
  }
  return invertible;
}

bool TriangleIntersector::PrepareMeasure(const MeshView& mesh, Index id, double& measure)
{
  const CellCorners ids = mesh.Cell(id);
  double X[3][2];
  for (int k = 0; k < 3; ++k)
  {
    const double* x = mesh.Point(ids[k]);
    X[k][0] = x[0];
    X[k][1] = x[1];
  }
  const double twiceArea = Orient2D(X[0], X[1], X[2]);
  if (!HasArea(twiceArea))
  {
    return false;
  }
  if (twiceArea < 0.0) // as PrepareCorners: the same corners in the same order
  {
    std::swap(X[1][0], X[2][0]);
    std::swap(X[1][1], X[2][1]);
  }
  double inverse[2][2];
  return AffineMap(X, measure, inverse);
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
  const Placement place(t, s);
  double sides[18];
  unsigned negative = 0;
  if (FilteredSides(t, s, place.Extent, sides, negative))
  {
    const int met = GeneralPiece(t, s, sides, negative, place, piece);
    if (met >= 0)
    {
      return met > 0;
    }
    piece.TouchedFaces = 0; // labels that do not chain: sorted below
    piece.SourceFaces = 0;
  }
  return AnyPiece(t, s, place, piece);
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
