// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalSplit.h
 * @brief Second-order cells split into simplices on their own nodes
 *        (corners, mid-edge, mid-face and body nodes), the same way on both
 *        sides of every shared face.
 *
 * A quadratic cell (Mesh/NodalCells.h: NodalType, nodes in VTK's order) is
 * cut into simplices whose vertices are exactly its nodes:
 *  - Edge3: 2 segments; Triangle6: 4 triangles (3 corners, the mid one);
 *  - Quad8: 4 corner triangles and the quadrilateral of the 4 mid-edge
 *    nodes; Quad9: 4 sub-quadrilaterals about the centre node; the
 *    quadrilaterals split by CellSplit's polygon rule (fanned from their
 *    lowest key);
 *  - Tetra10, Hexa20, Wedge15, Pyramid13: each corner cut off (the
 *    tetrahedron of the corner and its edges' mid nodes; the pyramid's apex
 *    with its 4 edges' mid nodes is a small pyramid, split by CellSplit);
 *    what remains (the octahedron of a Tetra10, the cuboctahedron of a
 *    Hexa20, ...) is a polyhedron whose faces are the polygons of each
 *    cell face's mid-edge nodes and the corners' cuts, split by CellSplit's
 *    3D rule (the cone from its lowest key over its faces' fans);
 *  - Hexa27: 8 sub-hexahedra on the 3x3x3 lattice of its nodes; Wedge18:
 *    8 sub-wedges (4 sub-triangles of the 6-node triangle, on 2 layers),
 *    each split by CellSplit's linear rule.
 * The split of a face depends only on the face's own nodes and their keys:
 * corner triangles are fixed, and a quadrilateral of nodes is fanned from
 * its lowest key (a face through the cone's apex is fanned from it, and the
 * apex is then the face's lowest key too). Two cells sharing a face (with
 * the same nodes) split it alike, so the simplices form a conforming mesh
 * and P1 on them is continuous.
 *
 * The simplices keep the cell's orientation (VTK's positive cells give
 * positive simplices: Orient3D > 0, and for 2D cells the orientation of the
 * cell's outline; positive as VTK's parametric coordinates are, in which a
 * wedge's triangle 0 1 2 turns counterclockwise seen from 3 4 5, as Gmsh's
 * prisms do, unlike CellSplit's linear wedge). Curved cells (mid nodes off the straight edges) are split
 * alike: the split is the polygon or polyhedron through their nodes. A cell
 * whose simplices do not all have one orientation (a folded curved cell, or
 * an edge whose mid node is not between its ends) is refused
 * (SplitStatus::NotStarShaped); simplices flatter than CellSplit's
 * tolerance are left out, as CellSplit does.
 */
#ifndef MeshProjection_Kernel_NodalSplit_h
#define MeshProjection_Kernel_NodalSplit_h

#include "Geometry/CellSplit.h"
#include "Geometry/NodalShapes.h"
#include "Mesh/MeshView.h"
#include "Mesh/NodalCells.h"

#include <vector>

namespace mp
{
/**
 * Splits one second-order cell. `nodes`: its NodalNodeCount(type) point
 * ids in the type's (VTK's) order; `points`: 3 coordinates per point id;
 * `keys` (optional, one per point id): replaces the ids in the rule, as in
 * CellSplit.h. Simplices (NodalCellDimension(type) + 1 ids each) are appended
 * to `simplices`; on a refusal nothing is appended.
 */
SplitStatus SplitNodalCell(NodalType type, const double* points, const Index* nodes,
  std::vector<Index>& simplices, const Index* keys = nullptr);
} // namespace mp

#endif
