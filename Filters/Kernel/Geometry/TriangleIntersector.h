// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TriangleIntersector.h
 * @brief Intersection polygon of two triangles: geometry only.
 *
 * Implements Section 3 of Gander & Japhet, "An algorithm for non-matching
 * grid projections with linear complexity" (DD18, 2009): the intersection of
 * two triangles is the convex hull of (a) the points where an edge of one
 * crosses an edge of the other and (b) the corners of each triangle lying in
 * the other, borderline cases included; these points in counterclockwise
 * order, duplicates removed, are the polygon. Unlike the original
 * floating-point tests, every decision here is the sign of an exactly
 * evaluated orientation (Predicates.h), so a corner lying on an edge is
 * "inside" for both cells that share the edge; in general position those
 * signs also give the order (each point lies on two edge lines, the polygon
 * arriving along one and leaving along the other), else the points are
 * sorted by angle.
 *
 * Along with the polygon it reports which faces (edges) of the target
 * triangle the closed source triangle touches: the target's neighbours
 * across those faces also meet that source triangle, which is how the
 * advancing front passes on starting candidates without any search.
 *
 * Everything is fixed-size; no allocation happens per pair.
 */
#ifndef MeshProjection_Kernel_TriangleIntersector_h
#define MeshProjection_Kernel_TriangleIntersector_h

#include "Mesh/MeshView.h"

namespace mp
{
struct IntersectionPieces;

class TriangleIntersector
{
public:
  static constexpr int Dimension = 2;
  static constexpr int Corners = 3;
  static constexpr int Faces = 3;
  /// Room for the candidate points: at most 6 arise (exact decisions, see
  /// SortAndRemoveDoubles); the margin costs nothing.
  static constexpr int MaxPolygonVertices = 12;

  /// A triangle prepared once for many intersection tests.
  struct Cell
  {
    Index Id = -1;
    Index Points[3]; ///< point ids, in counterclockwise order
    int Face[3];     ///< mesh-local face index of face k (k opposite corner k)
    double X[3][2];  ///< corner coordinates as given (exact predicates use them)
    double Box[4];   ///< xmin, xmax, ymin, ymax
    double Measure;  ///< area, > 0
    /// The cell's affine map: x - X[0] to barycentric coordinates 1 and 2
    /// (geometry; the P1 space of Transfer/Space.h builds its basis from it).
    double Inverse[2][2];
    /// Edge k as a vector, X[k + 2] - X[k + 1] (rounded), and the sum of
    /// its components' magnitudes: each side of a point w.r.t. edge k is
    /// then two products, and one bound per edge filters them (Intersect).
    double Edge[3][2];
    double EdgeSize[3];
  };

  /// The intersection of a target and a source triangle.
  struct Piece
  {
    int NumberOfVertices = 0;        ///< 0: empty; 1 or 2: the cells only touch
    double X[MaxPolygonVertices][2]; ///< counterclockwise
    unsigned TouchedFaces = 0;       ///< bit k: face k of the target meets the source
    /// bit l: face l of the source (in Cell order) meets the target. Only
    /// neighbours across those can meet the target too (through the target).
    unsigned SourceFaces = 0;
  };

  /**
   * Gathers cell `id` of `mesh`. Returns false for a cell of zero area (its
   * corners collinear, decided exactly); such a cell meets nothing.
   */
  static bool Prepare(const MeshView& mesh, Index id, Cell& cell);
  /**
   * The rest of Prepare for a cell whose Id, Points, Face and X are set:
   * orders the corners counterclockwise (with their points and faces) and
   * sets Box, Measure and Inverse. False for zero area.
   */
  static bool PrepareCorners(Cell& cell);
  /**
   * Whether Prepare would succeed on cell `id`, and then the Measure it
   * would set, bit for bit, without the rest of the prepared cell (for
   * loops over all cells that need only their measures).
   */
  static bool PrepareMeasure(const MeshView& mesh, Index id, double& measure);
  /// The source cell as the spaces see it on a piece: itself.
  static const Cell& SourceCell(const Cell& s, const Piece&) { return s; }
  /// Never: a false Intersect means the cells do not meet (see SurfaceIntersector).
  static bool Screened(const Piece&) { return false; }
  /// A piece's measure on the source cell per unit of its own: 1 (the same space).
  static double SourceScale(const Cell&, const Piece&) { return 1.0; }
  /// The source cell that starts the target neighbour across a touched face:
  /// the source cell itself (it meets the closed face, hence the neighbour).
  static Index FaceSeed(const Piece&, int, const Cell& s, const MeshView&) { return s.Id; }

  /// Bounding box as xmin, xmax, ymin, ymax, zmin, zmax (z is 0).
  static void Bounds(const Cell& cell, double box[6]);

  /// The mean of the corners (x, y).
  static void Center(const Cell& cell, double q[2]);

  /**
   * One step of a walk toward point q: -1 when q lies in the closed cell,
   * else a face k (Cell order) with q strictly beyond it, the first such
   * face from `first` on (exact orientations).
   */
  static int Locate(const Cell& cell, const double* q, int first);

  /**
   * Intersects target `t` with source `s` (both closed). Returns false when
   * they do not meet at all. When they only touch, `piece` has fewer than 3
   * vertices (measure 0) but `TouchedFaces` still tells which faces of the
   * target the source meets.
   */
  static bool Intersect(const Cell& t, const Cell& s, Piece& piece);

  /**
   * The piece's moments up to order 2 about `origin` (set to its first
   * vertex): M[0][0] the area, M[0][1+a] the first moments, M[1+a][1+b] the
   * second moments of x - origin, so that the integral of the product of two
   * affine functions f, g of x - origin is f^T M g. Returns the area, 0 (M
   * unset) for a piece without interior.
   */
  static double Moments(const Piece& piece, double (&origin)[2], double (&M)[3][3]);

  /// Area of the piece (0 when it has fewer than 3 vertices).
  static double Measure(const Piece& piece);

  /// Appends the piece (one polygon, with its area) to `pieces`.
  static void AppendPiece(
    const Piece& piece, Index target, Index source, IntersectionPieces& pieces);
};
/// (Always inlined, as ShiftMoments (Moments.h): the assembler reads M at
/// once, and from a call its two-lane loads of entries stored one by one
/// waited for the stores.)
inline __attribute__((always_inline)) double TriangleIntersector::Moments(
  const Piece& p, double (&origin)[2], double (&M)[3][3])
{
  // Moments of the polygon (1, x, y, x^2, xy, y^2) relative to its first
  // vertex, edge by edge (Green's theorem): exact for any polygon. A local
  // origin inside both cells keeps affine functions of size 1 over the
  // piece, so that thin cells cannot make them cancel.
  if (p.NumberOfVertices < 3)
  {
    return 0.0;
  }
  const double ox = p.X[0][0];
  const double oy = p.X[0][1];
  double m0 = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
  for (int i = 1; i + 1 < p.NumberOfVertices; ++i)
  {
    const int j = i + 1;
    const double px = p.X[i][0] - ox;
    const double py = p.X[i][1] - oy;
    const double qx = p.X[j][0] - ox;
    const double qy = p.X[j][1] - oy;
    const double cross = px * qy - py * qx;
    m0 += cross;
    mx += cross * (px + qx);
    my += cross * (py + qy);
    mxx += cross * (px * px + px * qx + qx * qx);
    myy += cross * (py * py + py * qy + qy * qy);
    mxy += cross * (2 * px * py + px * qy + qx * py + 2 * qx * qy);
  }
  // Scaled by products with the constants' reciprocals (within a rounding
  // of the quotients): divisions are far slower than products, and five
  // of them were a large part of this function's time.
  constexpr double sixth = 1.0 / 6.0;
  constexpr double twelfth = 1.0 / 12.0;
  constexpr double twentyFourth = 1.0 / 24.0;
  m0 *= 0.5;
  mx *= sixth;
  my *= sixth;
  mxx *= twelfth;
  myy *= twelfth;
  mxy *= twentyFourth;
  if (!(m0 > 0.0))
  {
    return 0.0; // rounding of a sliver
  }
  origin[0] = ox;
  origin[1] = oy;
  // The integral of (a + b x + c y)(a' + b' x + c' y) is (a, b, c) M (a', b', c')^T.
  M[0][0] = m0;
  M[0][1] = M[1][0] = mx;
  M[0][2] = M[2][0] = my;
  M[1][1] = mxx;
  M[1][2] = M[2][1] = mxy;
  M[2][2] = myy;
  return m0;
}
} // namespace mp

#endif
