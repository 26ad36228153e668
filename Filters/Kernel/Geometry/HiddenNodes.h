// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file HiddenNodes.h
 * @brief The space of a serendipity cell that is not an affine image of
 *        its reference cell: the space of its complete sibling, whose
 *        extra (hidden) nodes take values fixed by the cell's own nodes so
 *        that every quadratic polynomial is reproduced on straight cells.
 *
 * A Quad8, Hexa20 or Wedge15 (Geometry/NodalShapes.h) reproduces every
 * quadratic of the physical coordinates only where it is an affine image
 * of its reference cell. On any straight cell (its map bilinear or
 * trilinear) a quadratic pulled back to the reference cell lies in the
 * span of the complete sibling's functions (Quad9, Hexa27, Wedge18), whose
 * first nodes are the cell's own: the sibling reproduces it once its extra
 * nodes (the quadrilateral's centre, the hexahedron's face centres and
 * body centre, the wedge's quadrilateral face centres) carry the
 * polynomial's values there. Those values are written here as fixed
 * combinations of the cell's node values, u_h = sum_n W[h][n] u_n, chosen
 * per cell:
 *  - each hidden node depends on the nodes of the face it lies on (8 for a
 *    face centre; all of the cell's for the quadrilateral's centre and the
 *    hexahedron's body centre), taken in the order of their ids, so that
 *    the two cells on a face give its centre the same value (the field
 *    stays continuous across faces);
 *  - W starts from the serendipity weights s_n = N_n(xi_h) (the cell's own
 *    function at the hidden node's reference point: on an affine cell
 *    they are already exact) and takes the smallest change that makes the
 *    combination exact for the quadratic monomials of the coordinates
 *    (centred on the nodes and scaled by their extent), the linear ones
 *    kept exact as s makes them: the hidden node's place is the cell's own
 *    map at xi_h, so linear fields stay reproduced on curved cells too.
 *    The coordinates are the physical ones for the quadrilateral in the
 *    plane and the body centre; a face (or a quadrilateral in space) is
 *    taken in its principal axes, with the quadratic monomials of its two
 *    in-plane coordinates only, and the change then made orthogonal to
 *    its normal coordinate (so linear fields stay exact on a curved or
 *    twisted face; the normal coordinate's own quadratics, nearly
 *    dependent on the others on a slightly bent face, would make the
 *    weights huge). Monomials that the nodes cannot tell from the ones
 *    before are left out.
 * On a planar face (or a planar quadrilateral) every quadratic is then
 * exact; on a twisted or curved face no combination of its nodes is (a
 * quadratic on a bilinear twisted face needs the ninth value): there the
 * field is exact for linear fields, and the in-plane quadratics are
 * matched as the nodes' projections onto the face's plane have them.
 */
#ifndef MeshProjection_Kernel_HiddenNodes_h
#define MeshProjection_Kernel_HiddenNodes_h

#include "Geometry/NodalShapes.h"
#include "Mesh/MeshView.h"

namespace mp
{
/// The most hidden nodes of a type (Hexa20: 6 face centres and the body).
constexpr int MaxHiddenNodes = 7;
/// The most own nodes of a type with a complete sibling (Hexa20).
constexpr int MaxHiddenOwners = 20;

/// Quad9 for Quad8, Hexa27 for Hexa20, Wedge18 for Wedge15; None for the
/// other types.
NodalType CompleteSibling(NodalType type);

/**
 * The hidden nodes' weights of one cell of `type` (one with a
 * CompleteSibling): W[h * NodalNodeCount(type) + n] for the hidden node h
 * (the sibling's node NodalNodeCount(type) + h) and the cell's node n. X
 * holds the nodes' coordinates (3 per node, the first spaceDimension
 * read), ids their global numbers (the order in which a face's nodes are
 * combined).
 */
void HiddenNodeWeights(
  NodalType type, const double* X, const Index* ids, int spaceDimension, double* W);

/**
 * The functions of such a cell at reference point xi: phi_n = M_n(xi) +
 * sum_h W[h][n] M_h(xi), M the sibling's shape functions; one per own
 * node, summing to 1.
 */
void HiddenNodeFunctions(NodalType type, const double* W, const double* xi, double* phi);
} // namespace mp

#endif
