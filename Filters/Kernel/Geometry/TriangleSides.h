// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TriangleSides.h
 * @brief The signs and crossings TriangleIntersector builds a piece from
 *        (private to it and its tests).
 *
 * For a target and a source triangle (TriangleIntersector::Cell): the side
 * of each corner of one w.r.t. each edge line of the other, as exactly
 * evaluated orientations (Predicates.h) with their sign masks, and the
 * point where an edge of one properly crosses an edge of the other.
 */
#ifndef MeshProjection_Kernel_TriangleSides_h
#define MeshProjection_Kernel_TriangleSides_h

#include "Geometry/Lanes.h"
#include "Geometry/Predicates.h"
#include "Geometry/TriangleIntersector.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace mp
{
namespace triangle
{
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
 * sides[2 (3k + j)] = Orient2D(t.X[k + 1], t.X[k + 2], s.X[j]) (ot[k][j] of
 * Intersect) and the next one the same with t and s exchanged (os[k][j]),
 * with their signs as `negative` (bits 2 (3k + j) and the next: the masks
 * negT, negS of Intersect interleaved, see GeneralCrossings),
 * when one floating-point filter decides all 18 (returns false, all unset,
 * else). Each is Shewchuk's orient2d with the edge's first corner as its
 * pivot and the edge's vector as prepared (Cell::Edge), the two cells'
 * sides paired as the two lanes of one vector (Lanes.h). Its bound takes the place of
 * each determinant's |left| + |right| by one above it for every point of
 * both boxes: the edge's EdgeSize times `extent` (the larger side of the
 * box around both cells; a difference of two coordinates in it rounds to
 * at most that). (3 + 64u) u covers Shewchuk's (3 + 16u) u with the
 * roundings of the bound itself. A decided determinant is not zero, so its
 * sign bit is its sign: the pair is in general position. Pairs whose
 * extent is outside [2^-450, 2^450] are left to the exact route: there a
 * product could overflow to infinity, or the bound underflow to zero, and
 * the filter would decide a sign it cannot know.
 */
inline bool FilteredSides(const TriangleIntersector::Cell& t, const TriangleIntersector::Cell& s,
  double extent, double (&sides)[18], unsigned& negative)
{
  if (!(extent >= 0x1p-450 && extent <= 0x1p450))
  {
    return false;
  }
  constexpr double c = (3.0 + 64.0 * RoundingUnit) * RoundingUnit;
  const double scale = c * extent;
  Doubles2 px[3];
  Doubles2 py[3];
  for (int j = 0; j < 3; ++j)
  {
    px[j] = Doubles2{ s.X[j][0], t.X[j][0] };
    py[j] = Doubles2{ s.X[j][1], t.X[j][1] };
  }
  Mask2 decided = { -1, -1 };
  unsigned signs = 0; // bit 2 (3k + j): ot[k][j] < 0, the next bit os[k][j] < 0
  for (int k = 0; k < 3; ++k)
  {
    const int a = k == 2 ? 0 : k + 1;
    const Doubles2 ax = { t.X[a][0], s.X[a][0] };
    const Doubles2 ay = { t.X[a][1], s.X[a][1] };
    const Doubles2 ex = { t.Edge[k][0], s.Edge[k][0] };
    const Doubles2 ey = { t.Edge[k][1], s.Edge[k][1] };
    const Doubles2 bound = scale * Doubles2{ t.EdgeSize[k], s.EdgeSize[k] };
    for (int j = 0; j < 3; ++j)
    {
      const Doubles2 det = ex * (py[j] - ay) - ey * (px[j] - ax);
      decided &= Magnitude(det) > bound;
      std::memcpy(&sides[2 * (3 * k + j)], &det, sizeof det);
      signs |= SignBits(det) << (2 * (3 * k + j));
    }
  }
  if (!(decided[0] & decided[1]))
  {
    return false;
  }
  negative = signs;
  return true;
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

/// Target edge K and source edge L as bit 3K + L of a mask of crossings,
/// with their end corners (edge k runs from corner k + 1 to corner k + 2)
/// and the places in FilteredSides' `sides` of the sides of the source's
/// corners C, D w.r.t. target edge K (a table: the divisions by 3 it
/// spares were on the crossings' path).
struct EdgePair
{
  unsigned char K, L, A, B, C, D, OC, OD;
};
constexpr EdgePair MakeEdgePair(int bit)
{
  const int k = bit / 3;
  const int l = bit % 3;
  const int a = (k + 1) % 3;
  const int b = (k + 2) % 3;
  const int c = (l + 1) % 3;
  const int d = (l + 2) % 3;
  return { static_cast<unsigned char>(k), static_cast<unsigned char>(l),
    static_cast<unsigned char>(a), static_cast<unsigned char>(b), static_cast<unsigned char>(c),
    static_cast<unsigned char>(d), static_cast<unsigned char>(2 * (3 * k + c)),
    static_cast<unsigned char>(2 * (3 * k + d)) };
}
constexpr EdgePair EdgePairs[9] = { MakeEdgePair(0), MakeEdgePair(1), MakeEdgePair(2),
  MakeEdgePair(3), MakeEdgePair(4), MakeEdgePair(5), MakeEdgePair(6), MakeEdgePair(7),
  MakeEdgePair(8) };

/**
 * Bits 3k + l: target edge k and source edge l cross properly (each one's
 * end points strictly on both sides of the other's line), from the sign
 * masks of Intersect (pos, neg of ot and of os).
 */
inline unsigned ProperCrossings(unsigned posT, unsigned negT, unsigned posS, unsigned negS)
{
  // straddleT bit 3k + l: source edge l's corners (l+1, l+2) are strictly
  // on opposite sides of target edge k; straddleS bit 3l + k likewise.
  auto straddle = [](unsigned pos, unsigned neg) {
    // Bit 3k + l of rot1(m), rot2(m): entry (l + 1) % 3, (l + 2) % 3 of row k.
    auto rot1 = [](unsigned m) { return ((m >> 1) & 0xDBu) | ((m << 2) & 0x124u); };
    auto rot2 = [](unsigned m) { return ((m >> 2) & 0x49u) | ((m << 1) & 0x1B6u); };
    return (rot1(pos) & rot2(neg)) | (rot1(neg) & rot2(pos));
  };
  const unsigned straddleT = straddle(posT, negT);
  const unsigned straddleS = straddle(posS, negS);
  // straddleS transposed: bit 3l + k to 3k + l.
  const unsigned transposed = (straddleS & 0x111u) | ((straddleS & 0x022u) << 2) |
    ((straddleS & 0x088u) >> 2) | ((straddleS & 0x004u) << 4) | ((straddleS & 0x040u) >> 4);
  return straddleT & transposed & 0x1FFu;
}

/*
 * The general-position route's masks: ot[k][j] < 0 at bit 2 (3k + j) and
 * os[k][j] < 0 at the bit after it (FilteredSides), AnyPiece's negT and
 * negS interleaved, so that each expression below treats both cells.
 */

/// Bits 0-2 of the result: bits 0, 2, 4 of `bits`.
inline unsigned EvenOfSix(unsigned bits)
{
  return (bits & 1u) | ((bits >> 1) & 2u) | ((bits >> 2) & 4u);
}

/// Bit 2j, 2j + 1: column j of either interleaved mask has a bit set.
inline unsigned AnyInColumns(unsigned m)
{
  return (m | (m >> 6) | (m >> 12)) & 0x3Fu;
}

/// Some row of either interleaved mask is full (a separating edge).
inline bool AnyRowFull(unsigned m)
{
  return (m & (m >> 2) & (m >> 4) & 0x30C3u) != 0;
}

/// Bit k: row k of an interleaved mask's first one (even bits) has a bit set.
inline unsigned AnyInEvenRows(unsigned m)
{
  const unsigned r = m | (m >> 2) | (m >> 4);
  return (r & 1u) | ((r >> 5) & 2u) | ((r >> 10) & 4u);
}

/**
 * ProperCrossings in general position (pos = ~neg) from the interleaved
 * negative signs: bit 2 (3k + l) when target edge k and source edge l
 * cross properly.
 */
inline unsigned GeneralCrossings(unsigned m)
{
  // Entries (l + 1) % 3 and (l + 2) % 3 of each row at place l, both
  // masks at once: edge l's ends on opposite sides where they differ.
  const unsigned next = ((m >> 2) & 0xF3CFu) | ((m << 4) & 0x30C30u);
  const unsigned after = ((m >> 4) & 0x30C3u) | ((m << 2) & 0x3CF3Cu);
  const unsigned straddle = next ^ after;
  // The source's (odd bits, 3l + k) at the target's places (even, 3k + l).
  const unsigned s = (straddle >> 1) & 0x15555u;
  const unsigned transposed = (s & 0x10101u) | ((s & 0x404u) << 4) | ((s & 0x4040u) >> 4) |
    ((s & 0x10u) << 8) | ((s & 0x1000u) >> 8);
  return straddle & transposed & 0x15555u;
}
/// What places the crossings of a pair (Crossing): the larger side of the
/// box around both cells, determinants below Limit recomputed exactly, and
/// whether the cells' sizes differ so much that points go along the
/// shorter edge (Careful).
struct Placement
{
  Placement(const TriangleIntersector::Cell& t, const TriangleIntersector::Cell& s)
  {
    this->Extent = std::max(t.Box[1], s.Box[1]) - std::min(t.Box[0], s.Box[0]);
    this->Extent =
      std::max(this->Extent, std::max(t.Box[3], s.Box[3]) - std::min(t.Box[2], s.Box[2]));
    this->Limit = 0x1p-19 * this->Extent * this->Extent;
    const double sourceSize = std::max(s.Box[1] - s.Box[0], s.Box[3] - s.Box[2]);
    const double targetSize = std::max(t.Box[1] - t.Box[0], t.Box[3] - t.Box[2]);
    this->Careful = sourceSize > 16.0 * targetSize || targetSize > 16.0 * sourceSize;
  }
  double Extent;
  double Limit;
  bool Careful;
};

/// Crossing's rare way, from exact sides (along the shorter edge when
/// `careful`); apart, so that the usual way keeps its registers.
__attribute__((noinline)) inline void CrossingFromExactSides(const TriangleIntersector::Cell& t,
  const TriangleIntersector::Cell& s, const EdgePair& e, bool careful, double (&x)[2])
{
  const double* a = t.X[e.A];
  const double* b = t.X[e.B];
  const double* c = s.X[e.C];
  const double* d = s.X[e.D];
  const double* cd = s.Edge[e.L];
  const double* ab = t.Edge[e.K];
  if (careful && ab[0] * ab[0] + ab[1] * ab[1] < cd[0] * cd[0] + cd[1] * cd[1])
  {
    std::swap(a, c); // along the target edge a-b, across the line of c-d
    std::swap(b, d);
    cd = ab;
  }
  const double oc = Orient2DExact(a, b, c);
  const double od = Orient2DExact(a, b, d);
  const double u = oc / (oc - od);
  const Doubles2 point = LoadLanes(c) + u * LoadLanes(cd);
  std::memcpy(x, &point, sizeof point);
}

/**
 * Where target edge a-b and source edge c-d of `e` cross (properly), given
 * their sides in the layout of FilteredSides: those of c, d w.r.t. the
 * line of a-b (strictly of opposite signs) place the point along c-d.
 *
 * Their signs are exact, but a determinant the filter decided is only the
 * rounded one, whose error (below 2^-51 of the sum of its two products'
 * magnitudes, its scale) is large relative to it when a point lies very
 * near the line; so then is the error of the crossing's place along the
 * edge (on nearly parallel edges, a few percent of a piece's area were
 * seen). A determinant below `Limit` (2^-19 D^2, D the extent of both
 * cells' boxes together: at least 2^-20 of its scale, since a scale is at
 * most 2 D^2; FilteredSides' scale is at most 4 D^2) is recomputed exactly
 * with its partner, so that each one used is within about 2^-31 of its
 * value.
 *
 * Placed along an edge, the point's error is about the rounding unit u
 * times the edge's length (the error of u times it), and the rounded
 * orientations' errors (about u D^2) add about u D^2 / |o| of it. For
 * cells of similar sizes both stay within rounding of the cells. For a
 * small cell (size h) and a huge one (size L: `Careful`, one box more than
 * 16 times the other) the first is up to u L along a huge edge, and the
 * second u L / h relative, since the orientations are about L h: both
 * could exceed the small cell. The point is then placed along the shorter
 * edge, from exact orientations. The edge vectors are the cells' Edge,
 * the differences of the corners.
 */
inline void Crossing(const TriangleIntersector::Cell& t, const TriangleIntersector::Cell& s,
  const EdgePair& e, const double (&sides)[18], const Placement& place, double (&x)[2])
{
  const double oc = sides[e.OC];
  const double od = sides[e.OD];
  if (place.Careful || std::fabs(oc) < place.Limit || std::fabs(od) < place.Limit)
  {
    CrossingFromExactSides(t, s, e, place.Careful, x);
    return;
  }
  const double u = oc / (oc - od);
  const Doubles2 point = LoadLanes(s.X[e.C]) + u * LoadLanes(s.Edge[e.L]);
  std::memcpy(x, &point, sizeof point);
}
} // namespace triangle
} // namespace mp

#endif
