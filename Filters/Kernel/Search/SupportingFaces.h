// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SupportingFaces.h
 * @brief The boundary faces of a tetrahedral mesh whose plane has the whole
 *        mesh on one side: where the front needs no boundary query.
 *
 * Where the inner front of a target cell T runs into the source boundary,
 * T's intersection with the source may be disconnected, so the front asks
 * the locator for the boundary cells near T (PairSearch.h). On a 3D mesh
 * of a ball that is a target cell in two or three at 10^4 cells, and the
 * candidates it brings almost never meet T.
 *
 * No query is needed when every boundary face the inner front ran into
 * *supports* the source: the whole source (every point of its cells) lies
 * in the closed half-space H_f on the face's inner side. Then nothing is
 * missing. Let K be the part of T covered by the source cells met, and
 * R = T ∩ (H_f over those faces), convex. Inside T, K is bounded only by
 * such faces (a face with a neighbour that T reaches in positive area has
 * that neighbour met too). For y inside K and x inside R but not in K, the
 * segment from y to x would leave K through such a face f at some z, with
 * y, z, x in that order and x strictly inside H_f: then y is strictly
 * outside H_f, which cannot be. So R is K's, and every source cell meeting
 * T in positive volume (all of which lie in R, the source being in every
 * H_f) overlaps a cell met: it is one (cells do not overlap each other).
 *
 * That argument holds for exact pieces; Intersect's are rounded, and
 * count a pair as meeting above a floor (1e-13 of the smaller cell). A
 * piece of rounding size met first (a sliver where the cells nearly only
 * touch) can lie on a face whose neighbour, tested on its own, does not
 * meet T, and the front would stop there: so the front trusts the faces
 * of substantial pieces only (TetrahedronIntersector::Substantial) and
 * asks otherwise. What remains is the gap the front has anywhere, away
 * from the boundary too: a neighbour that T reaches by less than the floor
 * is not met, and a much smaller cell beyond it that meets T above its own
 * floor is reached by no front (graded meshes at 1e-7 scale ratios).
 *
 * On a convex source every boundary face supports it. A Gmsh ball's facets
 * are not exactly a convex hull's (a few edges fold inward by rounding or
 * the surface mesher's choice), and all faces but those near such edges
 * still support it.
 *
 * Decided exactly (Orient3D), for each plane once: boundary faces that are
 * exactly coplanar and share an edge with the same inner side (a flat side
 * of a box) are tested together. The points are searched through a k-d
 * tree of boxes, a box skipped when a bound of its rounding error shows all
 * its points strictly inside; a face whose plane passes near more points
 * than its budget allows (visits of tree nodes and exact evaluations, in
 * proportion to the faces of its plane) is left unsupported, so the cost
 * stays linear in the boundary. Non-finite points make no face
 * supporting, nor do magnitudes where the bounds could overflow or
 * underflow.
 */
#ifndef MeshProjection_Kernel_SupportingFaces_h
#define MeshProjection_Kernel_SupportingFaces_h

#include "Mesh/MeshView.h"

#include <vector>

namespace mp
{
/**
 * For each cell of a tetrahedral mesh in space with neighbours set, a bit
 * k set when face k has no neighbour and supports the mesh (see above);
 * `cells` lists the cells with a face without neighbour (BoundaryCells),
 * the others get no bit. Empty for any other mesh.
 */
std::vector<unsigned char> SupportingFaces(const MeshView& mesh, const std::vector<Index>& cells);
} // namespace mp

#endif
