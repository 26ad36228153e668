// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TetrahedronIntersector.h
 * @brief Intersection polyhedron of two tetrahedra and its P1 mortar integrals.
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

#include "MeshView.h"

namespace mp
{
struct IntersectionPieces;
}

namespace mp
{
class TetrahedronIntersector
{
public:
  static constexpr int Dimension = 3;
  static constexpr int Corners = 4;
  static constexpr int Faces = 4;
  static constexpr int MaxTetrahedra = 81;

  /// A tetrahedron prepared once for many intersection tests.
  struct Cell
  {
    Index Id = -1;
    Index Points[4];   ///< point ids, positively oriented
    int Face[4];       ///< mesh-local face index of face k (k opposite corner k)
    double X[4][3];
    double Box[6];     ///< xmin, xmax, ymin, ymax, zmin, zmax
    double Measure;    ///< volume, > 0
    double FaceScale;  ///< volume^(2/3): the area of a typical face
    double Normal[4][3]; ///< inward normal of face k (not unit), through X[(k+1)%4]
    double NormalScale[4]; ///< |u|max |v|max of the two edges spanning face k (error bounds)
    double Inverse[3][3]; ///< maps x - X[0] to barycentric coordinates 1..3
  };

  /// The intersection as a set of tetrahedra.
  struct Piece
  {
    int NumberOfTetrahedra = 0;
    double X[MaxTetrahedra][4][3];
    double Volume[MaxTetrahedra]; ///< of each tetrahedron, > 0 (from the clipping)
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

  /// Gathers cell `id`; false for a cell of zero (or non-finite) volume.
  static bool Prepare(const MeshView& mesh, Index id, Cell& cell);
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
  /// The same with the reference clipper only: every plane splits every
  /// tetrahedron of the piece in at most three (slower; for tests).
  static bool IntersectBySplitting(const Cell& t, const Cell& s, Piece& piece);
  /**
   * Adds Mts[i][j] += integral of phi_i^t phi_j^s and Mtt[i][k] += integral of
   * phi_i^t phi_k^t over the piece, exactly, from the piece's moments up to
   * order 2 (summed over its tetrahedra). Returns the volume of the piece.
   */
  static double Integrate(
    const Piece& piece, const Cell& t, const Cell& s, double Mts[4][4], double Mtt[4][4]);

  /**
   * What the projection sums per piece: the right-hand sides
   * rhs[i][c] += integral of phi_i^t u_c for the source field with values
   * u[j][c] at the corners of `s` (Cell order), c < components, and the
   * piece's moment matrix about the target's corner 0 added to `moments`
   * (MortarBlocks.h), from which TargetMass() gives the target cell's M_tt
   * block once all its pieces are in. Returns the volume of the piece.
   */
  static double IntegrateField(const Piece& piece, const Cell& t, const Cell& s,
    double (&moments)[4][4], const double* const (&u)[4], int components, double* const (&rhs)[4]);
  /// As IntegrateField, with the M_ts block (Mts[i][j] += integral of
  /// phi_i^t phi_j^s) instead of the right-hand sides.
  static double IntegrateMixed(
    const Piece& piece, const Cell& t, const Cell& s, double Mts[4][4], double (&moments)[4][4]);
  /// The M_tt block of `t` (set, not added) from the summed moments of its
  /// pieces (IntegrateField, IntegrateMixed).
  static void TargetMass(const Cell& t, const double (&moments)[4][4], double (&Mtt)[4][4]);
  static double Measure(const Piece& piece);

  /// Appends the piece's tetrahedra (with their own volumes) to `pieces`.
  static void Append(const Piece& piece, Index target, Index source, double volume,
    IntersectionPieces& pieces);

private:
  static bool IntersectCells(const Cell& t, const Cell& s, Piece& piece, bool asGraph);
};
} // namespace mp

#endif
