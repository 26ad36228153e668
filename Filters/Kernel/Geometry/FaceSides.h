// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FaceSides.h
 * @brief On which side of each face plane of one tetrahedron the corners
 *        of another lie, exactly signed (private to TetrahedronIntersector
 *        and its tests).
 *
 * Both clippers (ClipByPlane.h, VertexGraph.h) cut by the face planes of
 * the clipping cell and take the sides of the clipped cell's corners from
 * here: a floating-point filter decides the clear cases, Orient3D the
 * others, so every corner's side is the exact one and the clip agrees with
 * the tests that decided the pair meets at all. SideBits turns a table of
 * sides into bit patterns, which the intersector uses to pick the planes
 * that cut and the cuts' tables.
 */
#ifndef MeshProjection_Kernel_FaceSides_h
#define MeshProjection_Kernel_FaceSides_h

#include "Geometry/Lanes.h"
#include "Geometry/Predicates.h"
#include "Geometry/TetrahedronIntersector.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace mp
{
namespace clipping
{
/**
 * Whether x lies on the plane of the triangle (a, b, c) for a reason that
 * shows in the coordinates alone: all four share a coordinate (a face on a
 * box's side), x is a corner, or x lies on the axis-parallel line through
 * two corners. Such configurations are common where meshes share a
 * boundary, and Orient3D finds them too (its filter cannot decide an
 * exact zero) after its own arithmetic: this decides them first, with the
 * same zero. (a, b, c: the corners of a face of positive area.)
 */
inline bool OnFacePlaneByCoordinates(
  const double* a, const double* b, const double* c, const double* x)
{
  // Per corner, bit i: coordinate i equal to x's.
  unsigned same[3] = { 0, 0, 0 };
  const double* corner[3] = { a, b, c };
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 3; ++i)
    {
      same[j] |= static_cast<unsigned>(corner[j][i] == x[i]) << i;
    }
  }
  // Two corners sharing two coordinates with x: x on the line through
  // them, or equal to one of them (which shares all three).
  static constexpr unsigned char twoOrMore[8] = { 0, 0, 0, 1, 0, 1, 1, 1 };
  return (same[0] & same[1] & same[2]) != 0 ||
    (twoOrMore[same[0] & same[1]] | twoOrMore[same[0] & same[2]] | twoOrMore[same[1] & same[2]]) !=
    0 ||
    same[0] == 7u || same[1] == 7u || same[2] == 7u;
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
  if (std::fabs(d) > c.SideBound[k] * size)
  {
    return d;
  }
  const double* b = c.X[(k + 2) % 4];
  const double* e = c.X[(k + 3) % 4];
  if (OnFacePlaneByCoordinates(a, b, e, x))
  {
    return (k % 2) ? 0.0 : -0.0; // Orient3D's 0, signed as below
  }
  const double o = Orient3D(a, b, e, x);
  return (k % 2) ? o : -o;
}

/// The extent of two cells' boxes together, per axis the largest: what
/// FaceSides' filters bound |x - a| by (the same for either cell's planes).
inline double PairExtent(
  const TetrahedronIntersector::Cell& c, const TetrahedronIntersector::Cell& other)
{
  double size = 0.0;
  for (int d = 0; d < 3; ++d)
  {
    size = std::max(size,
      std::max(c.Box[2 * d + 1], other.Box[2 * d + 1]) - std::min(c.Box[2 * d], other.Box[2 * d]));
  }
  return size;
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
/// 48 comparisons and shifts per pair were a visible cost of a 3D run).
inline void GetSideBits(const double (&sides)[4][4], SideBits& bits)
{
  for (int k = 0; k < 4; ++k)
  {
    const Doubles2 r0 = LoadLanes(&sides[k][0]);
    const Doubles2 r1 = LoadLanes(&sides[k][2]);
    bits.Negative[k] = LaneBits(r0 < 0.0) | LaneBits(r1 < 0.0) << 2;
    bits.Zero[k] = LaneBits(r0 == 0.0) | LaneBits(r1 == 0.0) << 2;
    bits.NotPositive[k] = bits.Negative[k] | bits.Zero[k]; // (a NaN is in neither)
  }
}

/**
 * FaceSides' second pass: sides[k][v] = FaceSide(c, k, x[v]) where the
 * first pass's filter (bound[k]) left it undecided, then the bits. Out of
 * line: inlined, this rarer path cost the first pass registers.
 */
__attribute__((noinline)) inline void DecideSides(const TetrahedronIntersector::Cell& c,
  const TetrahedronIntersector::Cell& other, const double (&bound)[4], double (&sides)[4][4],
  SideBits& bits)
{
  // Only the undecided ones again: a decided value is FaceSide's already.
  for (int k = 0; k < 4; ++k)
  {
    for (int v = 0; v < 4; ++v)
    {
      if (!(std::fabs(sides[k][v]) > bound[k]))
      {
        sides[k][v] = FaceSide(c, k, other.X[v]);
      }
    }
  }
  GetSideBits(sides, bits);
}

/**
 * sides[k][v] = FaceSide(c, k, x[v]) for the four faces of `c` and the four
 * corners of `other`, with the filters of all sixteen evaluated first,
 * without branches, and the exact path taken only for the undecided ones.
 * The filters bound |x - a| by `size`, PairExtent(c, other) (once per pair
 * instead of per point): looser than FaceSide's own, so a point this one
 * leaves undecided is then classified by FaceSide, and the signs and values
 * are FaceSide's either way. (Looser still for cells of very different
 * sizes or shapes: more pairs then take that second pass.) `bits` gets
 * the table's SideBits: when every filter decided, from the sign bits the
 * filters already hold (no side is then zero).
 */
inline void FaceSides(const TetrahedronIntersector::Cell& c,
  const TetrahedronIntersector::Cell& other, double size, double (&sides)[4][4], SideBits& bits)
{
  // The corners by coordinate, two per vector (Lanes.h): the same operations
  // in the same order as FaceSide's fast path, so the same values; a lane
  // is decided when its distance's magnitude is beyond the bound (a NaN
  // never is). Scalar, these 32 evaluations per pair were a large cost of
  // a 3D run: they are done for every candidate pair.
  const double(&corner)[3][4] = other.ByAxis;
  Doubles2 x0[2], x1[2], x2[2];
  for (int h = 0; h < 2; ++h)
  {
    x0[h] = LoadLanes(&corner[0][2 * h]);
    x1[h] = LoadLanes(&corner[1][2 * h]);
    x2[h] = LoadLanes(&corner[2][2 * h]);
  }
  Mask2 decided = { -1, -1 };
  double bound[4];
  unsigned negative[4] = { 0, 0, 0, 0 };
  for (int k = 0; k < 4; ++k)
  {
    const double* a = c.X[(k + 1) % 4];
    const double* n = c.Normal[k];
    bound[k] = c.SideBound[k] * size;
    for (int h = 0; h < 2; ++h)
    {
      const Doubles2 d = n[0] * (x0[h] - a[0]) + n[1] * (x1[h] - a[1]) + n[2] * (x2[h] - a[2]);
      std::memcpy(&sides[k][2 * h], &d, sizeof d);
      decided &= Magnitude(d) > bound[k];
      negative[k] |= SignBits(d) << (2 * h);
    }
  }
  if (decided[0] && decided[1])
  {
    // None zero (nor NaN): the signs are the bits.
    for (int k = 0; k < 4; ++k)
    {
      bits.Negative[k] = negative[k];
      bits.NotPositive[k] = negative[k];
      bits.Zero[k] = 0;
    }
    return;
  }
  DecideSides(c, other, bound, sides, bits);
}

/// The same without the bits.
inline void FaceSides(const TetrahedronIntersector::Cell& c,
  const TetrahedronIntersector::Cell& other, double size, double (&sides)[4][4])
{
  SideBits bits;
  FaceSides(c, other, size, sides, bits);
}

/// FaceSides with the size of the two cells' boxes.
inline void FaceSides(const TetrahedronIntersector::Cell& c,
  const TetrahedronIntersector::Cell& other, double (&sides)[4][4])
{
  FaceSides(c, other, PairExtent(c, other), sides);
}

/// Of four rows of 4 bits, packed 4 apart (row k at bit 4k): bit k of the
/// result for each row with all bits set (bits 4k, 4k + 1, 4k + 2, 4k + 3
/// ANDed onto bit 4k, those four gathered to bits 0-3 by one product).
inline unsigned FullRows(unsigned packed)
{
  const unsigned full = packed & packed >> 1 & packed >> 2 & packed >> 3 & 0x1111u;
  return ((full * 0x1248u) >> 12) & 15u;
}

/// The same for rows with any bit set.
inline unsigned NonZeroRows(unsigned packed)
{
  const unsigned any = (packed | packed >> 1 | packed >> 2 | packed >> 3) & 0x1111u;
  return ((any * 0x1248u) >> 12) & 15u;
}

/// Four rows of 4 bits packed 4 apart.
inline unsigned PackRows(const unsigned (&rows)[4])
{
  return rows[0] | rows[1] << 4 | rows[2] << 8 | rows[3] << 12;
}

/// The number of bits set in a 4-bit pattern.
inline unsigned CountBits4(unsigned bits)
{
  static constexpr unsigned char count[16] = { 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4 };
  return count[bits & 15u];
}
} // namespace clipping
} // namespace mp

#endif
