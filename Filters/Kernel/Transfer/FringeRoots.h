// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FringeRoots.h
 * @brief The fringe on second-order targets: an ill-posed node takes the
 *        value of a well-covered cell's own function, extrapolated to it.
 *
 * On a target with second-order cells (MeshView::Nodal) the point data is
 * the cells' own quadratic field (NodalSpace.h), an order more accurate
 * than P1 inside; a fit through the free points of rings around an
 * ill-posed node (FringeFits.h), often affine, extends it with an error
 * of second order, many times the interior's. Aggregated finite elements
 * proper (Badia, Verdugo and Martin 2018) extend it by a root cell's own
 * polynomial instead: node i takes
 *
 *     u_i = sum_k N_k^R(xi_R(x_i)) u_k
 *
 * over the nodes k of a parent R whose nodes are all free, xi_R the inverse
 * of R's isoparametric map (NodalReference), N^R its shape functions
 * (NodalValues): the functions NodalSpace evaluates. The weights sum to 1
 * and reproduce every field of R's space, every quadratic on the cells
 * this rule takes (below): a third-order extension.
 *
 * The rule takes the place of an affine fit only: where the rings allow a
 * quadratic fit (FringeAggregation.h), of third order too and through more
 * points, that fit stays. R is sought among the nodal parents of the simplices within
 * FringeRootRings rings of i whose corners' map is affine (straight
 * simplices, parallelograms, parallelepipeds, straight wedges with
 * parallel triangles: their map extrapolates as one polynomial, and every
 * type but the pyramid then reproduces every quadratic), or straight
 * Quad9, Hexa27 and Wedge18 (their corners' multilinear map: their tensor
 * spaces reproduce every quadratic through it too), on 2D and volume
 * meshes. Curved cells are left out: their map, extrapolated, bends. Of those, the one with the smallest amplification sum_k |w_k|
 * (nearest, in effect), ties broken by its nodes' centroid (not by the
 * numbering), and only while that amplification stays within
 * FringeRootAmplification; else the affine fit.
 */
#ifndef MeshProjection_Kernel_FringeRoots_h
#define MeshProjection_Kernel_FringeRoots_h

#include "Mesh/MeshView.h"

#include <vector>

namespace mp
{
/**
 * The rings of simplices around an ill-posed node (the simplices around it,
 * then those around their corners, ...) whose parents are candidate roots.
 * A second-order cell spans about two rings of its split: three reach the
 * cells next to the one holding i and theirs, and stay well within the
 * halo of a distributed target (FringeSearchRings of the longest edges).
 */
constexpr int FringeRootRings = 3;

/**
 * The largest amplification sum_k |w_k| a root's extension may have. A
 * quadratic extrapolated a whole cell out weighs its free values 17 times
 * (the 1D Lagrange functions at -1, and a triangle's across an edge), a
 * tensor cell's two cells diagonally out 17^2 times: the extension's error
 * is then that many times the free values' errors plus a third-order term,
 * and still below an affine fit's second-order error over the same reach
 * on the fringe of a second-order target, whose inside is an order more
 * accurate. Beyond this the affine fit stays.
 */
constexpr double FringeRootAmplification = 400.0;

/**
 * Whether parent p of `mesh` can be a root: a nodal parent of the mesh's own
 * dimension whose nodes are an affine image of its reference nodes (within
 * 1e-9 of its size), not a pyramid; or a straight Quad9, Hexa27 or Wedge18
 * (NodalIsStraight, 1e-9).
 */
bool IsAffineRoot(const MeshView& mesh, Index p);

/**
 * The root extension of node i: among the parents of the simplices `cells`
 * (within FringeRootRings rings of i) that are roots (`root`, per parent:
 * 1 when IsAffineRoot) with every node `usable`, the one of smallest
 * amplification within FringeRootAmplification. Its nodes into `points`
 * (nearest to i first, ties by their coordinates) and their weights into
 * `weights`; false, both empty, when there is none.
 */
bool RootExtension(const MeshView& mesh, Index i, const std::vector<Index>& cells,
  const std::vector<char>& root, const std::vector<char>& usable, std::vector<Index>& points,
  std::vector<double>& weights);
} // namespace mp

#endif
