// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FringeFits.h
 * @brief The weights of one fringe stencil: the weighted least-squares
 *        polynomial fit through its points, evaluated at the ill-posed point.
 *
 * FringeAggregation.h extends an ill-posed function i from free points
 * around it, u_i = sum_k w_ik u_k. The weights are those of a weighted
 * least-squares fit of degree 1 or 2 through the points, in i's frame
 * (FringeFrames.h: the mesh's coordinates on volume meshes, the tangent
 * ones on surfaces and curves), evaluated at i: they sum to 1 and
 * reproduce the functions affine in those coordinates.
 *
 * On a curved stencil of a surface or a curve the fit also takes the
 * points' normal coordinates, so that it reproduces the ambient affine
 * functions (a linear Source field on a trace stays exact): its quadratic
 * monomials that the normal coordinates nearly fit (on a sphere the normal
 * one is nearly (u^2 + v^2) / 2R) are left out, and the tangent fit kept
 * where those weights would amplify more than QuadraticAmplification.
 */
#ifndef MeshProjection_Kernel_FringeFits_h
#define MeshProjection_Kernel_FringeFits_h

#include "Mesh/MeshView.h"
#include "Transfer/FringeFrames.h"

#include <cstddef>
#include <vector>

namespace mp
{
/**
 * The largest sum of |w_ik| a quadratic extension on a surface or a curve
 * (or a curved stencil's fit through the normal coordinates) may have: the
 * factor by which it can
 * amplify an oscillation of the free values. One-sided quadratic
 * extrapolations reach a dozen and more (three points on a line: 3, -3, 1
 * already 7); such weights couple the stencil's functions with alternating
 * signs in P^T M P and widen its spectrum (the conjugate gradients then
 * need up to three times the iterations). The affine fit, taken beyond
 * this, is of second order only: at a curved boundary it leaves the
 * fringe's error several times the interior's, so the bound keeps what
 * quadratic fits it can.
 */
constexpr double QuadraticAmplification = 8.0;

/**
 * The same bound for a quadratic fit of a volume mesh (triangles in the
 * plane, tetrahedra: VolumeFit). A corner of a volume target reaching out
 * of the source is extrapolated along two or three directions at once:
 * the affine fit's error there (its weights times the squared distances,
 * a cell and two away) is many times the interior's, while the free values
 * a quadratic fit amplifies are smooth along the fringe (they are errors
 * of the same projection, of second order).
 */
constexpr double VolumeQuadraticAmplification = 12.0;

/**
 * Whether a fit at a point of `mesh` in `frame` follows the volume rule
 * (VolumeQuadraticAmplification here, FringeVolumeRings and more points
 * first in FringeAggregation.cxx): on volume meshes, fitted in their own
 * coordinates (2D or 3D), and on any fit in 3D coordinates (a point of a
 * surface whose cells give no tangent). Surfaces and curves, fitted in
 * their tangent coordinates, keep QuadraticAmplification.
 */
inline bool VolumeFit(const MeshView& mesh, const StencilFrame& frame)
{
  return mesh.IsVolumeMesh() || frame.Dimension == 3;
}

/// The amplification a quadratic fit at a point of `mesh` in `frame` may have.
inline double QuadraticAmplificationIn(const MeshView& mesh, const StencilFrame& frame)
{
  return VolumeFit(mesh, frame) ? VolumeQuadraticAmplification : QuadraticAmplification;
}

/**
 * How a fit weighs its points by how well their values are known: each
 * point's least-squares weight times its covered fraction (at most 1) to
 * the power Power. A free point whose support the source covers in part
 * carries a larger error than a fully covered one (its projection sees
 * one side only), and an extension amplifies what it takes from it. With
 * a positive Amplification, a quadratic fit that amplifies more gives way
 * to a short affine one (FringeAggregation.cxx's ShortAffineFit).
 */
struct FitCoverage
{
  const double* Fraction = nullptr; ///< per point of the mesh, its covered fraction
  double Power = 0.0;
  /// When positive, the sum |w| above which a quadratic fit gives way to a
  /// short affine one (FringeCellDataAmplification, FringeAggregation.h).
  double Amplification = 0.0;
};

/**
 * The smallest eigenvalue of a quadratic fit's normal matrix weighed by
 * FitCoverage (the points' offsets over the stencil's size h, the matrix
 * over the sum of its weights) below which the fit is refused: the points
 * that determine it (their spread, judged without Coverage's factors, at
 * least 1e-4) must also be ones whose values are well known, else the fit
 * carries the errors of a few points covered in part many times over (a
 * farther ring or the affine fit then extends the point).
 */
constexpr double WeighedQuadraticSpread = 1e-4;

/**
 * The weights of points[0 .. keep) that give, at point i, the value of the
 * least-squares polynomial fit of degree `degree` (1 or 2) through them in
 * i's `frame` (the minimum-norm weights reproducing those polynomials at
 * i), or empty when the points do not allow a stable fit: when they do
 * not spread well (nearly on a line, a plane or a conic), or, quadratic,
 * when the weights amplify more than QuadraticAmplificationIn. Either degree
 * reproduces the affine functions of the frame's coordinates and sums to 1;
 * `ambient`, when given, says whether the weights also reproduce the
 * ambient affine functions (always on volume meshes and flat stencils; on
 * curved ones where the fit through the normal coordinates is kept).
 */
std::vector<double> FitWeights(const MeshView& mesh, const StencilFrame& frame, Index i,
  const std::vector<Index>& points, size_t keep, int degree, bool* ambient = nullptr,
  const FitCoverage* coverage = nullptr);
} // namespace mp

#endif
