// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SegmentIntersector.h
 * @brief Two segments of two curves (in the plane or in space): the source
 *        segment projected onto the target segment's line, then the two
 *        intervals intersected there.
 *
 * The classic mortar case: the interfaces of 2D subdomains are curves, each
 * side discretized on its own, and the paper's algorithm in one dimension.
 * As for surfaces (SurfaceIntersector.h), every target segment has its own
 * frame (origin at corner 0, unit axis toward corner 1) and every source
 * point is mapped onto that axis by one formula (orthogonal projection), so
 * adjacent source segments, which share a point, have images that share
 * their ends exactly and tile the target segment without gap or overlap.
 * Every decision is a comparison of those images (exact as doubles).
 *
 *  - Segments meet when their directions make an angle whose cosine, taken
 *    without sign (curves have no orientation), is at least the target
 *    view's SurfaceMinCosine, when their closed images overlap, and when,
 *    over the whole piece, the source lies within the reach of the target's
 *    line (SurfaceReach times the target segment's length).
 *  - The piece is an interval of the target's axis; its moments give the
 *    mortar integrals with the 1D spaces (P1: the hat functions; P0).
 *  - Face k of a segment is its corner 1 - k (the point opposite corner k):
 *    a target neighbour across a face whose point the source covers meets
 *    that source segment too.
 */
#ifndef MeshProjection_Kernel_SegmentIntersector_h
#define MeshProjection_Kernel_SegmentIntersector_h

#include "Mesh/MeshView.h"

namespace mp
{
struct IntersectionPieces;

class SegmentIntersector
{
public:
  static constexpr int Dimension = 1;
  static constexpr int Corners = 2;
  static constexpr int Faces = 2;

  /// A segment in the frame of its own line (X: positions on the axis).
  struct Cell
  {
    Index Id = -1;
    Index Points[2];      ///< in increasing X
    int Face[2];          ///< mesh-local face index of face k (k opposite corner k)
    double X[2][1];       ///< positions on the axis, X[0] < X[1]
    double Measure;       ///< length
    double Inverse[1][1]; ///< 1 / length: the barycentric coordinate of corner 1
    double Origin[3];
    double Axis[3];      ///< unit, toward corner 1
    double Corner[2][3]; ///< the corners in space, in the order of Points
    double Box3[6];
    double Reach;     ///< as a target: the largest distance to a source segment that meets it
    double MinCosine; ///< as a target: the smallest |cosine| of the directions' angle
  };

  struct Piece
  {
    int NumberOfVertices = 0;  ///< 0: empty; 1: the segments touch at a point; 2: an interval
    double X[2][1];            ///< the interval on the target's axis
    unsigned TouchedFaces = 0; ///< bit k: face k (corner 1 - k) of the target lies on the source
    unsigned SourceFaces = 0;  ///< bit l: face l of the source (Cell order) lies on the target
    Cell Projected;            ///< the source segment on the target's axis (its functions)
    const Cell* Target = nullptr;
    bool Screened = false; ///< near the target but out by angle, reach or a point image
  };

  static bool Prepare(const MeshView& mesh, Index id, Cell& cell);
  static Index FaceSeed(const Piece&, int, const Cell& s, const MeshView&) { return s.Id; }
  static void Bounds(const Cell& cell, double box[6]);
  static void Center(const Cell& cell, double q[3]);
  static int Locate(const Cell& cell, const double* q, int first);
  static bool Intersect(const Cell& t, const Cell& s, Piece& piece);
  static const Cell& SourceCell(const Cell&, const Piece& piece) { return piece.Projected; }
  static bool Screened(const Piece& piece) { return piece.Screened; }
  /// A piece's length on the source segment per unit of its length on the target's line.
  static double SourceScale(const Cell& s, const Piece& piece)
  {
    return s.Measure / piece.Projected.Measure;
  }
  /// Length M[0][0], first and second moments of x - origin (origin: the piece's start).
  static double Moments(const Piece& piece, double (&origin)[1], double (&M)[2][2]);
  static double Measure(const Piece& piece);
  static void AppendPiece(
    const Piece& piece, Index target, Index source, IntersectionPieces& pieces);
  /// The moments of the interval X[0]..X[1] (when n == 2; else 0) about its start.
  static double IntervalMoments(
    int n, const double (&X)[2][1], double (&origin)[1], double (&M)[2][2]);
  /// Appends the interval of `frame`'s axis (n points) as a segment in space.
  static void AppendInterval(const Cell& frame, int n, const double (&X)[2][1], Index target,
    Index source, IntersectionPieces& pieces);
  /// The position of x on `frame`'s axis; `offset` is x minus its foot on the axis.
  static double ToFrame(const Cell& frame, const double* x, double offset[3]);
};
} // namespace mp

#endif
