// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TetrahedronIntersector.h
 * @brief Intersection polyhedron of two tetrahedra: geometry only.
 *
 * The 3D counterpart of TriangleIntersector. The paper (Gander & Japhet 2009,
 * Sec. 3) sketches the tetrahedron case as "edge/face crossings plus corners
 * inside, ordered face by face"; here the equivalent clipping formulation is
 * used: the source tetrahedron is clipped by the four face planes of the
 * target, each clip splitting every tetrahedron of the current piece into at
 * most three, so the result comes directly as a tetrahedral decomposition of
 * the convex intersection polyhedron. That is what the mortar integrals need
 * (a rule exact for quadratics on each tetrahedron), it never has to order
 * points on a face, and every vertex is classified once per plane, so the
 * topology of a clip is consistent by construction.
 *
 * Two tetrahedra "meet" when the intersection has positive volume. A face of
 * the target is "touched" when the piece has a face of positive area on it.
 * Then either the source reaches beyond that face, and the target neighbour
 * across it overlaps the same source cell, or a face of the source lies on
 * it, and the neighbour overlaps the source cell across that face: either
 * way the advancing front gets a starting candidate without any search,
 * also for meshes whose faces coincide (identical meshes, refinements).
 *
 * All storage is fixed-size (at most 3^4 = 81 tetrahedra per piece).
 */
#ifndef MeshProjection_Kernel_TetrahedronIntersector_h
#define MeshProjection_Kernel_TetrahedronIntersector_h

#include "Mesh/MeshView.h"

#include <algorithm>

namespace mp
{
struct IntersectionPieces;

class TetrahedronIntersector
{
public:
  static constexpr int Dimension = 3;
  static constexpr int Corners = 4;
  static constexpr int Faces = 4;
  static constexpr int MaxTetrahedra = 81;
  /// Cells meet in positive volume: the front may trust supporting
  /// boundary faces (Search/SupportingFaces.h).
  static constexpr bool MeetsInVolume = true;

  /// A tetrahedron prepared once for many intersection tests.
  struct Cell
  {
    Index Id = -1;
    Index Points[4]; ///< point ids, positively oriented
    int Face[4];     ///< mesh-local face index of face k (k opposite corner k)
    double X[4][3];
    /// X by coordinate (ByAxis[a][v] = X[v][a]): the four corners' distances
    /// from a plane are then one vector expression (FaceSides).
    double ByAxis[3][4];
    double Box[6];       ///< xmin, xmax, ymin, ymax, zmin, zmax
    double Measure;      ///< volume, > 0
    double FaceScale;    ///< volume^(2/3): the area of a typical face
    double Normal[4][3]; ///< inward normal of face k (not unit), through X[(k+1)%4]
    /// 64 eps |u|max |v|max of the two edges spanning face k: times a bound
    /// on |x - X[(k+1)%4]|, the error bound of a distance from that face's
    /// plane by Normal (FaceSides.h).
    double SideBound[4];
    /// The cell's affine map: x - X[0] to barycentric coordinates 1..3
    /// (geometry; the P1 space of Transfer/Space.h builds its basis from it).
    double Inverse[3][3];
  };

  /// The intersection as a set of tetrahedra.
  struct Piece
  {
    int NumberOfTetrahedra = 0;
    /// Corner k of tetrahedron i is Points[Corner[i][k]]: from the vertex
    /// graph, its vertices (tetrahedra share them, and only they are
    /// copied); from the splitting clipper, four points per tetrahedron.
    int Corner[MaxTetrahedra][4];
    double Points[4 * MaxTetrahedra][3];
    /// Of each tetrahedron, signed: rounding may leave a sliver negative.
    double Volume[MaxTetrahedra];
    /// The moments of the tetrahedra about Origin (= Points[Corner[0][0]]), as Moments
    /// returns them, set by Intersect when it has tetrahedra: summed while
    /// the clipper's graph cuts the piece, or after the splitting clipper.
    /// M[0][0], the volume, is always set then; the other entries only when
    /// it is positive.
    double Origin[3];
    double M[4][4];
    /// bit k: the piece has a face of positive area (above 1e-12 of the
    /// smaller cell's typical face) on target face k
    unsigned TouchedFaces = 0;
    /// Bit l: some vertex of the piece lies on face l of the source (Cell
    /// order). Only neighbours across those can meet the target too: the
    /// source cells meeting the convex target are connected through faces
    /// meeting it in positive area, and such a face holds piece vertices.
    unsigned SourceFaces = 15;
    /// For a touched face k: -1 when the source reaches beyond it (the source
    /// cell itself meets the target neighbour), else the source's own face
    /// (in Cell order) lying on it: the source neighbour across meets it.
    int SeedFace[4];
  };

  /**
   * Whether a piece is far above rounding: at least 1e-9 of the smaller
   * cell's volume (Intersect's own floor is 1e-13). Only such pieces are
   * trusted to bound a target cell's cover at supporting boundary faces
   * (Search/SupportingFaces.h): a sliver of rounding size where the cells
   * nearly only touch can lie on a face whose neighbour, tested on its own,
   * does not meet the target.
   */
  static bool Substantial(const Cell& t, const Cell& s, const Piece& piece)
  {
    return piece.NumberOfTetrahedra > 0 && piece.M[0][0] >= 1e-9 * std::min(t.Measure, s.Measure);
  }
  /// Gathers cell `id`; false for a cell of zero (or non-finite) volume.
  static bool Prepare(const MeshView& mesh, Index id, Cell& cell);
  /// The source cell as the spaces see it on a piece: itself.
  static const Cell& SourceCell(const Cell& s, const Piece&) { return s; }
  /// Never: a false Intersect means the cells do not meet (see SurfaceIntersector).
  static bool Screened(const Piece&) { return false; }
  /// A piece's measure on the source cell per unit of its own: 1 (the same space).
  static double SourceScale(const Cell&, const Piece&) { return 1.0; }
  /// The source cell that starts the target neighbour across face k.
  static Index FaceSeed(const Piece& piece, int k, const Cell& s, const MeshView& source)
  {
    return piece.SeedFace[k] < 0 ? s.Id : source.Neighbor(s.Id, s.Face[piece.SeedFace[k]]);
  }
  static void Bounds(const Cell& cell, double box[6]);
  /// The mean of the corners.
  static void Center(const Cell& cell, double q[3]);
  /**
   * One step of a walk toward point q: -1 when q lies in the closed cell,
   * else a face k (Cell order) with q strictly beyond it, the first such
   * face from `first` on (exact orientations).
   */
  static int Locate(const Cell& cell, const double* q, int first);
  /**
   * Clips one cell by the face planes of the other (the one fewer planes
   * cut); true when the intersection has positive volume. The clipped cell
   * is kept as a polyhedron (a vertex graph), cut into tetrahedra at the
   * end; should rounding ever leave that graph inconsistent, the splitting
   * clipper below takes over.
   */
  static bool Intersect(const Cell& t, const Cell& s, Piece& piece);
  /**
   * True only when the cells certainly do not meet (Intersect is then
   * false): their boxes are disjoint, or the four corners of one lie
   * strictly outside a face plane of the other by FaceSides' filter (so
   * exactly). A cheap screen that stops at the first separating plane, for
   * candidates that mostly miss (the locator's); false says nothing.
   */
  static bool Apart(const Cell& t, const Cell& s);
  /// The same with the reference clipper only: every plane splits every
  /// tetrahedron of the piece in at most three (slower; for tests).
  static bool IntersectBySplitting(const Cell& t, const Cell& s, Piece& piece);
  /**
   * The piece's moments up to order 2 about `origin` (set to one of its
   * vertices): M[0][0] the volume, M[0][1+a] the first moments, M[1+a][1+b]
   * the second moments of x - origin. Returns the volume, 0 (origin and M
   * unset) for a piece without interior. Those Intersect summed: no work
   * per tetrahedron. (Inline, so that the caller may fold the copy away:
   * out of line it was a memcpy call per pair.)
   */
  static double Moments(const Piece& piece, double (&origin)[3], double (&M)[4][4])
  {
    if (piece.NumberOfTetrahedra == 0 || !(piece.M[0][0] > 0.0))
    {
      return 0.0;
    }
    for (int a = 0; a < 3; ++a)
    {
      origin[a] = piece.Origin[a];
    }
    for (int a = 0; a < 4; ++a)
    {
      for (int b = 0; b < 4; ++b)
      {
        M[a][b] = piece.M[a][b];
      }
    }
    return piece.M[0][0];
  }
  static double Measure(const Piece& piece);

  /// Appends the piece's tetrahedra (with their own volumes) to `pieces`.
  static void AppendPiece(
    const Piece& piece, Index target, Index source, IntersectionPieces& pieces);

private:
  /// Sums the moments of the piece's tetrahedra into its Origin and M.
  static void SumMoments(Piece& piece);
  static bool IntersectCells(const Cell& t, const Cell& s, Piece& piece, bool asGraph);
};
} // namespace mp

#endif
