// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SurfaceIntersector.h
 * @brief Two triangles of two surfaces in 3D: the source triangle projected
 *        onto the target triangle's plane, then intersected there.
 *
 * Two facetizations of one curved surface do not lie on each other: a
 * source facet is above or below the target facets it overlaps. The
 * standard mortar construction for surfaces (mortar contact, interface
 * coupling) projects each source facet onto the target facet's plane along
 * the target facet's normal and intersects the two there; the mortar
 * integrals are then taken on the target facet.
 *
 *  - Every target cell has its own orthonormal frame (origin at corner 0,
 *    first axis along edge 01, the normal from the corners' order). Its own
 *    corners and every source point are mapped into that frame by the same
 *    formula, so a point shared by two source triangles has one image: the
 *    projections of adjacent source facets share their edges bit for bit,
 *    and the exact 2D predicates (TriangleIntersector) make them tile the
 *    target facet without gap or overlap wherever the source surface is a
 *    graph over it. A point the two meshes share maps onto the target
 *    corner exactly.
 *  - The projection is affine, so a source barycentric coordinate is an
 *    affine function on the target plane: the projected source triangle
 *    carries the source P1 functions (Piece::Projected), and the spaces of
 *    Transfer/Space.h work unchanged in the target's frame.
 *  - Two facets meet only when their normals are within the angle whose
 *    cosine is the target view's SurfaceMinCosine (so the two sides of a
 *    thin plate or shell, or the faces at a sharp edge, are never matched:
 *    the normals' orientation counts; with SurfaceOrientation 1 the source's
 *    normal is reversed first, as for two bodies' boundaries facing each
 *    other, with 2 either way), and when, over their whole piece,
 *    the source facet lies within the reach of the target facet's plane
 *    (SurfaceReach times the target facet's longest edge), above or below.
 *    A projection that folds (non-positive orientation) meets nothing.
 *
 * A planar surface seen this way gives exactly the 2D result up to rounding
 * in the frames; the search (PairSearch.h) is the same advancing front,
 * over surface neighbours (edges), with locator boxes widened by the reach.
 */
#ifndef MeshProjection_Kernel_SurfaceIntersector_h
#define MeshProjection_Kernel_SurfaceIntersector_h

#include "Geometry/TriangleIntersector.h"
#include "Mesh/MeshView.h"

namespace mp
{
struct IntersectionPieces;

class SurfaceIntersector
{
public:
  /// The pieces, moments and spaces live in the target facet's plane.
  static constexpr int Dimension = 2;
  static constexpr int Corners = 3;
  static constexpr int Faces = 3;

  /**
   * A triangle in 3D prepared once. The TriangleIntersector part (X, Box,
   * Measure, Inverse, Face, Points) is the triangle in its own frame.
   */
  struct Cell : TriangleIntersector::Cell
  {
    double Origin[3];    ///< corner 0
    double Axis[2][3];   ///< orthonormal axes of the plane
    double Normal[3];    ///< unit normal, right-handed with the corners' order
    double Corner[3][3]; ///< the corners in 3D as given, in the order of Points
    double Box3[6];      ///< xmin, xmax, ymin, ymax, zmin, zmax of the corners
    double Reach;        ///< as a target: the largest distance to a source facet that meets it
    double MinCosine;    ///< as a target: the smallest cosine of the normals' angle
    int Orientation;     ///< as a target: MeshView::SurfaceOrientation
  };

  struct Piece : TriangleIntersector::Piece
  {
    /// The source triangle in the target's frame (ids and faces of the
    /// source, counterclockwise): the source functions on the piece.
    TriangleIntersector::Cell Projected;
    const Cell* Target = nullptr; ///< its frame maps the piece back to 3D
    /// After a false Intersect: the source facet is near the target (boxes
    /// within reach) but was screened out by the normals' angle, a folded
    /// image or the reach. The front cannot rely on its neighbours then.
    bool Screened = false;
  };

  /// False for a triangle of zero area (or with corners that are not finite).
  static bool Prepare(const MeshView& mesh, Index id, Cell& cell);
  static Index FaceSeed(const Piece&, int, const Cell& s, const MeshView&) { return s.Id; }
  /// The corners' box widened by the reach on every side.
  static void Bounds(const Cell& cell, double box[6]);
  /// The mean of the corners (x, y, z).
  static void Center(const Cell& cell, double q[3]);
  /// A walk step toward q projected onto the cell's plane (TriangleIntersector::Locate).
  static int Locate(const Cell& cell, const double* q, int first);
  static bool Intersect(const Cell& t, const Cell& s, Piece& piece);
  static bool Screened(const Piece& piece) { return piece.Screened; }
  /// A piece's area on the source facet per unit of its area on the target's
  /// plane (the projection's Jacobian on that facet).
  static double SourceScale(const Cell& s, const Piece& piece)
  {
    return s.Measure / piece.Projected.Measure;
  }
  /// The source cell as the spaces see it on this piece: its projection.
  static const TriangleIntersector::Cell& SourceCell(const Cell&, const Piece& piece)
  {
    return piece.Projected;
  }
  static double Moments(const Piece& piece, double (&origin)[2], double (&M)[3][3])
  {
    return TriangleIntersector::Moments(piece, origin, M);
  }
  static double Measure(const Piece& piece) { return TriangleIntersector::Measure(piece); }
  /// Appends the piece as a polygon in 3D, on the target facet.
  static void AppendPiece(
    const Piece& piece, Index target, Index source, IntersectionPieces& pieces);

  /// Appends `polygon` (in `frame`'s plane) as a polygon in 3D.
  static void AppendPolygon(const Cell& frame, const TriangleIntersector::Piece& polygon,
    Index target, Index source, IntersectionPieces& pieces);
  /// Point x (3D) in `frame`'s plane coordinates; the same formula for all.
  static void ToFrame(const Cell& frame, const double* x, double uv[2], double& height);
};
} // namespace mp

#endif
