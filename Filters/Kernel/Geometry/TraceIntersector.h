// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TraceIntersector.h
 * @brief Traces: a surface or a curve (target) lying inside a volume mesh
 *        (source), each target cell cut by the source cells.
 *
 * The L2 projection of a volume field onto a surface or a curve inside it:
 * the conservative counterpart of Slice or Probe followed by a resampling.
 * The pieces are the parts of a target facet (segment) inside each source
 * tetrahedron (triangle); the source's P1 functions, restricted to the
 * target's plane (line), are affine there (SourceSide.h, AffineCell), so the
 * mortar integrals are those of the target's own space.
 *
 * Surfaces in a tetrahedral mesh (SurfaceTraceIntersector). Every source
 * point gets one height over the target facet's plane and one image in its
 * frame (SurfaceIntersector::ToFrame). A tetrahedron meets the plane in its
 * cross-section: the points where its edges cross the plane, each computed
 * from the edge's two ends in the order of their ids, so that the
 * tetrahedra sharing an edge have the same point, bit for bit. The
 * cross-sections of a mesh thus tile the plane in the frame, and the exact
 * 2D intersector (TriangleIntersector) cuts the target facet by them (a
 * quadrilateral cross-section as two triangles). Heights within 1e-10 of
 * the facet's size are zero (a point on the plane), and zero counts as below
 * the plane: a facet lying on faces of the source mesh takes the
 * tetrahedra on the side its normal points to, or the one there is where
 * the face is on the source's boundary (a surface on the boundary of the
 * volume is covered whole from the inside).
 *
 * Curves in a triangle mesh (2D) or a tetrahedral mesh (CurveTraceIntersector).
 * The target segment is clipped by each face's half-space. The face's value
 * at the segment's two ends (the orientation of the face's points, sorted by
 * id, with the end; within 1e-10 of the sizes, zero) is computed once per
 * face: two cells sharing a face cut the segment at the same parameter, so
 * their intervals tile the segment. A segment lying in a face's plane (line)
 * belongs to the cell on the side of a fixed generic direction, or to the
 * only cell where the face is on the boundary; one along an edge (3D) is
 * claimed by every cell around it (Tied) and kept once by the assembler.
 * Cuts within 1e-10 of the segment's length of each other (through a vertex
 * or an edge of the cell) count as touching.
 *
 * Cells that only touch a target, and cells holding a segment that another
 * cell owns, meet it in a piece without measure, so that the front passes
 * through them; neither kind screens: a false Intersect means the cells do
 * not meet.
 */
#ifndef MeshProjection_Kernel_TraceIntersector_h
#define MeshProjection_Kernel_TraceIntersector_h

#include "Geometry/SegmentIntersector.h"
#include "Geometry/SourceSide.h"
#include "Geometry/SurfaceIntersector.h"
#include "Geometry/TetrahedronIntersector.h"
#include "Geometry/TriangleIntersector.h"

#include <utility>

namespace mp
{
struct IntersectionPieces;

class SurfaceTraceIntersector
{
public:
  static constexpr int Dimension = 2;
  static constexpr int Corners = 3;
  static constexpr int Faces = 3;
  using Cell = SurfaceIntersector::Cell;
  using SourceSide = BoundedCells<TetrahedronIntersector>;
  using SourceCellType = SourceSide::Cell;

  struct Piece
  {
    /// The target facet against the one or two triangles of the cross-section.
    int NumberOfParts = 0;
    TriangleIntersector::Piece Parts[2];
    unsigned TouchedFaces = 0; ///< bit k: face k of the target meets the source
    unsigned SourceFaces = 0;  ///< bit l: face l of the source (Cell order) meets the target
    AffineCell<4, 2> Source;   ///< the tetrahedron's functions in the target's frame
    const Cell* Target = nullptr;
  };

  /// The target facet (SurfaceIntersector::Prepare).
  static bool Prepare(const MeshView& mesh, Index id, Cell& cell)
  {
    return SurfaceIntersector::Prepare(mesh, id, cell);
  }
  static Index FaceSeed(const Piece&, int, const SourceCellType& s, const MeshView&)
  {
    return s.Id;
  }
  /// The facet's box, widened by its height tolerance.
  static void Bounds(const Cell& cell, double box[6]);
  static void Center(const Cell& cell, double q[3]) { SurfaceIntersector::Center(cell, q); }
  static bool Intersect(const Cell& t, const SourceCellType& s, Piece& piece);
  static bool Screened(const Piece&) { return false; }
  /// No measure of a volume is covered by a surface.
  static double SourceScale(const SourceCellType&, const Piece&) { return 0.0; }
  static const AffineCell<4, 2>& SourceCell(const SourceCellType&, const Piece& piece)
  {
    return piece.Source;
  }
  static double Moments(const Piece& piece, double (&origin)[2], double (&M)[3][3]);
  static double Measure(const Piece& piece);
  /// Appends each part as a polygon in 3D, on the target facet.
  static void AppendPiece(
    const Piece& piece, Index target, Index source, IntersectionPieces& pieces);
};

/// Base: TriangleIntersector (a curve in a 2D mesh) or TetrahedronIntersector.
template <class Base>
class CurveTraceIntersector
{
public:
  static constexpr int Dimension = 1;
  static constexpr int Corners = 2;
  static constexpr int Faces = 2;
  static constexpr int SpaceDimension = Base::Dimension;
  using Cell = SegmentIntersector::Cell;
  using SourceSide = BoundedCells<Base>;
  using SourceCellType = typename SourceSide::Cell;

  struct Piece
  {
    int NumberOfVertices = 0; ///< 0: empty; 1: a point; 2: an interval
    double X[2][1];           ///< the interval on the target's axis
    unsigned TouchedFaces = 0;
    unsigned SourceFaces = 0;
    AffineCell<Base::Corners, 1> Source;
    const Cell* Target = nullptr;
    /// Along an edge of the source: every cell around the edge (Edge: its
    /// point ids, ascending) claims the piece, and the assembler keeps the
    /// claim of the lowest source cell id.
    bool Tied = false;
    Index Edge[2] = { -1, -1 };
  };

  static bool Prepare(const MeshView& mesh, Index id, Cell& cell);
  static Index FaceSeed(const Piece&, int, const SourceCellType& s, const MeshView&)
  {
    return s.Id;
  }
  static void Bounds(const Cell& cell, double box[6]);
  static void Center(const Cell& cell, double q[3]) { SegmentIntersector::Center(cell, q); }
  static bool Intersect(const Cell& t, const SourceCellType& s, Piece& piece);
  static bool Screened(const Piece&) { return false; }
  static double SourceScale(const SourceCellType&, const Piece&) { return 0.0; }
  /// Whether the piece is claimed by every source cell around an edge, and which edge.
  static bool Tied(const Piece& piece) { return piece.Tied; }
  static std::pair<Index, Index> TieKey(const Piece& piece)
  {
    return { piece.Edge[0], piece.Edge[1] };
  }
  static const AffineCell<Base::Corners, 1>& SourceCell(const SourceCellType&, const Piece& piece)
  {
    return piece.Source;
  }
  static double Moments(const Piece& piece, double (&origin)[1], double (&M)[2][2]);
  static double Measure(const Piece& piece);
  static void AppendPiece(
    const Piece& piece, Index target, Index source, IntersectionPieces& pieces);
};

extern template class CurveTraceIntersector<TriangleIntersector>;
extern template class CurveTraceIntersector<TetrahedronIntersector>;
} // namespace mp

#endif
