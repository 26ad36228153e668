// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FringeAggregation.h
 * @brief A well-posed fringe: P1 target functions whose support the source
 *        covers too little are aggregated to well-covered neighbours.
 *
 * Where the source covers only a sliver of a target function's support,
 * its row of M_tt is tiny and nearly a combination of its neighbours': the
 * L2 projection then fits the function's value to the sliver and can put
 * it far off (the value is extrapolated from a sliver). Aggregated finite
 * elements (Badia, Verdugo and Martin 2018) remove these
 * functions from the unknowns: an ill-posed function i (its covered
 * fraction, int_covered phi_i / int phi_i, below a threshold) takes the
 * value of an extension of free (well-covered) functions nearby that
 * reproduces affine functions,
 *
 *     u_i = sum_k w_ik u_k,   sum_k w_ik = 1,   sum_k w_ik x_k = x_i,
 *
 * so u = P u_free with P the identity on free functions. The projection is
 * the Galerkin one on the span of the aggregated basis P^T phi:
 *
 *     P^T M_tt P u_free = P^T M_ts u_s.
 *
 * Since P reproduces affine functions, linear fields stay exact; since
 * every row of P sums to 1, the aggregated basis still sums to 1 on the
 * covered part and the integral is conserved; P^T M_tt P is symmetric
 * positive definite on the free functions.
 *
 * The weights are those of a weighted least-squares fit through the free
 * points of the rings around i (the points sharing a cell with i, then
 * theirs), evaluated at i, ring by ring until the points allow a stable
 * fit: quadratic where its weights stay bounded (the extension's error is
 * then of third order, below the projection's second), else affine. The
 * quadratic fit is sought within FringeRings rings on surfaces and
 * curves, FringeVolumeRings on 2D and volume meshes (a point on an edge
 * or a corner of the target, reaching out of the source, finds the
 * points of a quadratic fit only there; its affine fit
 * would extrapolate over a cell or two with an error of second order, many
 * times the interior's). A function with no quadratic fit takes the affine
 * one of the first ring that allows one; a function with no stable fit
 * within those rings (a corner of the target poking out of the source, its
 * free neighbours all on one face) seeks an affine one farther, up to
 * FringeSearchRings.
 *
 * On a second-order target (MeshView::Nodal: its point data the cells'
 * own quadratic field, an order more accurate inside than P1), a function
 * whose rings give only an affine fit takes, where one is near, the value
 * of a well-covered root cell's own function extrapolated to it
 * (FringeRoots.h): the shape functions of a straight parent whose nodes
 * are all free, at i's reference coordinates in it, a third-order
 * extension like the quadratic fit. A distributed target's halo carries
 * its cells' parents (FringeHalo), so that every part finds the serial root.
 *
 * On surfaces and curves the fit is in the tangent coordinates of i
 * (FringeFrames.h), in 2D or 1D as on a 2D mesh: the extension reproduces
 * the functions affine in those coordinates (ambient linear fields on a
 * plane surface or a straight curve), and its rows still sum to 1. Where
 * the stencil is curved, a fit that reproduces the ambient affine
 * functions too (FringeFits.h) is sought first: more points, then farther
 * rings (a quadratic one within FringeRings, an affine one up to
 * FringeSearchRings), the tangent fit kept only where none of those stays
 * within QuadraticAmplification (two cells beyond the end of a curved
 * curve's well-covered points).
 *
 * Every valid value is then a stable one: a function that finds no stable
 * fit even there is dropped to invalid when its support is covered less
 * than FringeStrandedDropFraction (it would keep the plain projection's
 * fit to its sliver), and stays free only above that (a tenth of its
 * support covered determines its value).
 */
#ifndef MeshProjection_Kernel_FringeAggregation_h
#define MeshProjection_Kernel_FringeAggregation_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"
#include "Transfer/CsrMatrix.h"

#include <vector>

namespace mp
{
/// Per point of a mesh (triangles, tetrahedra, triangles of a surface, segments of a curve): int phi_i over its whole support.
LargeVector<double> SupportIntegrals(const MeshView& mesh);

/// The extension of a fringe: P (functions x functions) and which rows it aggregates.
struct FringeExtension
{
  CsrMatrix P;                  ///< identity rows for free functions, weights for aggregated ones
  std::vector<char> Aggregated; ///< per function: 1 when its value comes from others
  std::vector<char> Dropped;    ///< per function: invalid in the output (see ExtendFringe)
  Index Count = 0;              ///< aggregated functions
  Index Stranded = 0;           ///< functions dropped with no stencil (not aggregated)
};

/**
 * The rings around an ill-posed function (the points sharing a cell with
 * it, then theirs, ...) its stencil is sought in first on surfaces and
 * curves (in their tangent coordinates): a quadratic
 * fit through any of them, else the affine fit of the first ring that
 * allows one.
 */
constexpr int FringeRings = 3;

/**
 * The same on 2D and volume meshes (VolumeFit in FringeFits.h): a
 * quadratic fit is sought up to this ring. Within
 * FringeSearchRings, so that the halo of a distributed target holds them.
 */
constexpr int FringeVolumeRings = 5;

/**
 * The farthest ring an affine stencil is sought in when the first
 * FringeRings rings hold none (their free points all on a face of a
 * corner poking out of the source). The search stays bounded: a stencil
 * six cells away still extends a function from the source's side, and a
 * distributed target's halo reaches this many of the longest edges
 * beyond each part (Parts::Halo), so that every process finds the stencils
 * the serial run does.
 */
constexpr int FringeSearchRings = 6;

/**
 * Functions of a surface or a curve covered less than this fraction of
 * their support are aggregated and, in the output, invalid: their support
 * holds no more than a corner of the source, so their value would be an
 * extrapolation over about a cell (their share of the covered integral
 * goes to their stencil). FringeDropFractionOf gives every target's.
 */
constexpr double FringeDropFraction = 0.02;

/**
 * The same for the functions of a target with second-order cells
 * (MeshView::Nodal). Their interior is a whole order more accurate than a
 * linear target's, while an extension over a cell or more (the nearest
 * well-covered nodes or root cells, FringeRoots.h, are farther in units of
 * node spacing) is not: a node covered a few percent would carry an error
 * tens of times the interior's. Below a tenth of its support covered its
 * value is an extrapolation, not a projection, and is dropped; above, the
 * covered part holds enough to anchor it.
 */
constexpr double FringeNodalDropFraction = 0.1;

/**
 * The same for the functions of a linear 2D or volume target. A function
 * covered a few percent takes an extension of a cell or two from one side,
 * whose weights (a dozen, of either sign) carry the errors of free points
 * covered in part several times over: on Gmsh tetrahedral and hexahedral
 * pairs such points reached six times the interior's error. Below a tenth
 * of its support covered its value is an extrapolation, not a projection,
 * as on a second-order target; surfaces and curves keep FringeDropFraction.
 */
constexpr double FringeVolumeDropFraction = 0.1;

/// The drop fraction for functions of `target` (FringeNodalDropFraction on a
/// target with second-order cells, FringeVolumeDropFraction on a linear 2D or
/// volume one, else FringeDropFraction).
inline double FringeDropFractionOf(const MeshView& target)
{
  if (target.Nodal)
  {
    return FringeNodalDropFraction;
  }
  return target.IsVolumeMesh() ? FringeVolumeDropFraction : FringeDropFraction;
}

/**
 * A function with no stable stencil within FringeSearchRings rings and
 * covered less than this fraction of its support is dropped to invalid
 * too (Stranded): its value would be the plain projection's fit to its
 * sliver. Its unknown stays in the system (the others' values, exact on
 * affine fields, do not depend on it being dropped); with no stencil to
 * hand it to, its share of the covered integral leaves the valid values'
 * integral. A point whose every cell is covered less than 0.1% has its
 * support covered at most (d + 1) x 0.1% x (a cell's measure over its
 * smallest simplex's), about 2.4% for a hexahedron: below this fraction,
 * so that no such point stays valid. Above it the function stays free: a
 * tenth of its support determines its value.
 */
constexpr double FringeStrandedDropFraction = 0.1;

/**
 * The power of their covered fractions by which the fits of point data on
 * a linear 2D or volume target weigh their free points (FitCoverage in
 * FringeFits.h). A free point covered in part is projected from one side
 * of its support: its value carries a larger error than a fully covered
 * one's, and an extension, summing a dozen weights of either sign, carries
 * it several times over; weighed so, the fit leans on the well-covered
 * points (it still reproduces the same polynomials).
 */
constexpr double FringeCoveragePower = 2.0;

/**
 * Cell data sent to the points of a linear 2D or volume target (each
 * source cell its constant value, SpaceType::P0) aggregates the functions
 * covered less than this fraction of their support (FringeThreshold when
 * higher). A point covered in part takes the projection of the cells'
 * constants over the covered part of its support only: a one-sided mean,
 * whose error is of first order where a fully covered point's is of
 * second. Aggregated, its value comes from points whose supports are
 * mostly covered.
 */
constexpr double FringeCellDataThreshold = 0.5;

/**
 * For the same cell data, the quadratic fit of a function covered less
 * than FringeCellDataAffineFraction whose sum |w| is above this gives way
 * to the affine fit of the same rings when that one's is at most
 * FringeCellDataAffineAmplification. The free values beside a cell-data
 * fringe carry errors of either sign from layer to layer (the points
 * covered in part one way, the fully covered ones next to them the
 * other), and a quadratic fit's weights, alternating in sign across those
 * layers, add them up. A point about one layer out from a face of free
 * points has a short affine extrapolation, whose own error is the smaller
 * part there; at a corner or an edge of the target, farther out (the
 * affine weights amplify more), the affine fit's own error is the larger
 * one and the quadratic stays.
 */
constexpr double FringeCellDataAmplification = 6.0;

/// The affine fits FringeCellDataAmplification gives way to: sum |w| at
/// most this (3 for a point one layer out from a flat layer of points).
constexpr double FringeCellDataAffineAmplification = 3.5;

/// The functions FringeCellDataAmplification applies to: covered less than
/// this (FringeThreshold's default). Those covered 25% to 50%, aggregated
/// for cell data only, lie nearer the covered part, where an affine fit's
/// own error over a coarse Input's cell can be the larger part.
constexpr double FringeCellDataAffineFraction = 0.25;

/**
 * The extension of the functions of `mesh`'s points that are valid but
 * whose `fraction` is below `threshold`, each onto the free points of the
 * rings around it (FringeRings, FringeVolumeRings on 2D and volume meshes, then farther
 * up to FringeSearchRings for an affine fit). Those below `drop` are marked Dropped too. A function
 * with no stable fit stays free, Dropped (and Stranded) when below
 * FringeStrandedDropFraction. The
 * stencils are fitted in `runner`'s tasks (the same whatever their number).
 * P's rows hold their columns in ascending order, or, with `stencilOrder`,
 * nearest first as the stencil found them (an order that does not depend
 * on the numbering: parts of a distributed target that number a point's
 * stencil differently then extend it to the same bits). With a positive
 * `coveragePower`, the fits weigh their points by their `fraction` to that
 * power (FitCoverage, FringeCoveragePower). With a positive
 * `quadraticAmplification` (FringeCellDataAmplification), a quadratic fit
 * whose weights amplify more gives way to a short affine one
 * (FringeCellDataAffineAmplification).
 */
FringeExtension ExtendFringe(const MeshView& mesh, const std::vector<char>& valid,
  const std::vector<double>& fraction, double threshold, double drop, const TaskRunner& runner,
  bool stencilOrder = false, double coveragePower = 0.0, double quadraticAmplification = 0.0);

/**
 * P^T M P over the same rows (an aggregated row holds a 1 on the diagonal:
 * its unknown is decoupled, its right-hand side P^T b is 0).
 */
CsrMatrix AggregatedMass(
  const CsrMatrix& mass, const FringeExtension& extension, const TaskRunner& runner);

/// y = P^T x (functions x c); aggregated rows of y are 0.
void RestrictToFree(const FringeExtension& extension, const double* x, double* y, int c);

/// x = P x in place (functions x c): aggregated rows from the free ones.
void ExtendFromFree(const FringeExtension& extension, double* x, int c);
} // namespace mp

#endif
