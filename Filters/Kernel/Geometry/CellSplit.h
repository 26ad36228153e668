// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellSplit.h
 * @brief Cells that are not simplices, split into simplices on their own
 *        corners, the same way on both sides of every shared face.
 *
 * The rule is decided by point ids alone (a global vertex-id rule, as in
 * Dompierre et al., "How to subdivide pyramids, prisms and hexahedra into
 * tetrahedra", 1999), so two cells sharing a face split it alike and the
 * simplices form a conforming mesh without any extra point:
 *  - a polygonal face (quadrilateral or more) is fanned from its
 *    lowest-numbered corner (for a quadrilateral: the diagonal through it);
 *  - a 3D cell is the cone from its lowest-numbered corner (the apex) over
 *    the fanned triangles of its faces. The faces through the apex are
 *    fanned from it too, so they add nothing; the cone's sides are exactly
 *    their triangles. A hexahedron gives 6 tetrahedra, a wedge 3, a pyramid
 *    2, any convex polyhedron one per triangle of the faces away from its
 *    apex.
 * The cone tiles the cell when the apex sees every face from inside: all
 * its tetrahedra have one orientation once the faces are oriented alike
 * (then the winding number is 1 inside and 0 outside, so nothing overlaps).
 * That holds for every convex cell. A non-convex cell that folds from its
 * lowest corner is coned from the next corner it does not fold from. The
 * faces away from that apex keep their fans; the faces through it are then
 * split from the apex (a planar one adds only flat tetrahedra from its own
 * fan), so across those faces the neighbour's split may differ: the piecewise
 * linear space is then not continuous there (it still holds every linear
 * function, so exactness and conservation stay). A cell star-shaped from
 * none of its corners is refused (NotStarShaped); a centre point tied to the
 * corners would take it (not done). Tetrahedra whose volume is below 1e-12 of the cube of
 * the cell's size are left out whatever their sign (faces split into
 * coplanar pieces, as on the coarse side of a refinement interface, give
 * such slivers, signed by rounding).
 *
 * In 2D the edges are the faces and stay whole whatever the split, so a
 * polygon is fanned from its lowest corner when that fan is one-signed, and
 * cut into ears otherwise (non-convex polygons).
 *
 * Point data stays on the cells' own points: the space is P1 on this
 * decomposition (linear on each simplex, continuous across shared faces).
 */
#ifndef MeshProjection_Kernel_CellSplit_h
#define MeshProjection_Kernel_CellSplit_h

#include "Mesh/MeshView.h"

#include <vector>

namespace mp
{
enum class SplitStatus
{
  Split,         ///< simplices appended (possibly none, for a flat cell)
  NotStarShaped, ///< the cone from the lowest corner overlaps itself: nothing appended
  OpenFaces      ///< the faces do not close a volume (an edge not shared by exactly two)
};

/*
 * `keys` (optional, one per point id) replaces the point ids in the rule:
 * the lowest corner is the one of lowest key. Global point ids as keys
 * give the same split on every process of a distributed mesh, whatever
 * each process's own numbering.
 */

/**
 * Splits a planar polygon (ids: its n >= 3 corners in order) into
 * triangles (3 ids each, appended), in the polygon's own plane. Triangles of
 * zero area are left out. Returns false for a polygon that cannot be cut
 * into ears (self-intersecting); nothing is appended then.
 */
bool SplitPolygon(const double* points, const Index* ids, int n, std::vector<Index>& triangles,
  const Index* keys = nullptr);

/**
 * Splits a 3D cell given by its faces, as a VTK face stream without the
 * leading face count: n0, ids of face 0, n1, ids of face 1, ...
 * `oriented`: the faces are known to be oriented alike (each edge runs once
 * each way, as in the standard cells' tables); if not (polyhedra from
 * files), they are oriented here first. Tetrahedra (4 ids each) are
 * appended; flat tetrahedra (see above) are left out.
 */
SplitStatus SplitPolyhedron(const double* points, const Index* faces, int nfaces, bool oriented,
  std::vector<Index>& tetrahedra, const Index* keys = nullptr);

/// The standard linear 3D cells other than the tetrahedron.
enum class CellShape
{
  Hexahedron,      ///< 8 corners: 0-3 bottom, 4-7 above them
  Voxel,           ///< 8 corners in x, y, z order (a hexahedron 0 1 3 2 4 5 7 6)
  Wedge,           ///< 6 corners: triangles 0 1 2 and 3 4 5
  Pyramid,         ///< 5 corners: base 0-3, apex 4
  PentagonalPrism, ///< 10 corners: 0-4 bottom, 5-9 above them
  HexagonalPrism   ///< 12 corners: 0-5 bottom, 6-11 above them
};

/// The faces of a standard cell (corners in VTK's order) as a face stream,
/// oriented alike. Returns the number of faces.
int StandardCellFaces(CellShape shape, const Index* corners, std::vector<Index>& stream);
} // namespace mp

#endif
