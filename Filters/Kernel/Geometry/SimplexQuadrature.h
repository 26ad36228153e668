// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SimplexQuadrature.h
 * @brief Quadrature rules on the segment, the triangle and the tetrahedron,
 *        exact for every polynomial up to a given total degree.
 *
 * The integral of f over a simplex S of measure |S| with corners v_0..v_d
 * is taken as
 *
 *     int_S f  ~  |S| sum_q Weight[q] f(sum_k Barycentric[q][k] v_k),
 *
 * exactly (up to rounding) when f is a polynomial of total degree at most
 * the rule's Degree, whatever the simplex (the rule is affine invariant).
 * The weights are positive and sum to 1, and every point lies strictly
 * inside (all barycentric coordinates positive), so no point of a rule
 * falls on a neighbour's side of a face.
 *
 * Each rule is the one with fewer points of two kinds:
 *  - Stroud's conical products: the simplex is the image of the unit cube
 *    under the collapse xi_1 = a, xi_2 = b (1 - a), xi_3 = c (1 - a)(1 - b),
 *    whose Jacobian (1 - a)^(d-1) (1 - b)^(d-2) is taken into the
 *    Gauss-Jacobi rules of weights (1 - a)^(d-1) and (1 - b)^(d-2) on
 *    [0, 1] (Gauss-Legendre for the last direction). Each one-dimensional
 *    rule has n = ceil((Degree + 1) / 2) points, exact to degree
 *    2n - 1 >= Degree for the collapsed polynomial (of degree at most Degree
 *    in each direction): n^d points in all. The Gauss-Jacobi nodes are the
 *    roots of the Jacobi polynomials, found by bisection on their
 *    three-term recurrence, and the weights come from the polynomials'
 *    derivatives at them, so no table is copied;
 *  - compact symmetric rules with positive weights and inner points:
 *    triangle degree 2 (3 points), 4 (6), 5 (7), 6 (12); tetrahedron
 *    degree 2 (4), 5 (14), 6 (24). Their parameters solve the symmetric
 *    moment equations (see the .cxx).
 * E.g. the tetrahedron's degree 4 (the product of two quadratic fields)
 * takes the 14-point rule, not the 27-point product; degree 7 and above
 * are conical products (64 points and more in a tetrahedron).
 *
 * All rules (dimensions 1 to 3, degrees 0 to MaxSimplexDegree) are built
 * once, at the first call, under C++'s thread-safe initialization of a
 * function-local static: afterwards SimplexQuadrature() only returns a
 * reference, from any thread.
 */
#ifndef MeshProjection_Kernel_SimplexQuadrature_h
#define MeshProjection_Kernel_SimplexQuadrature_h

#include <vector>

namespace mp
{
/// The highest total degree SimplexQuadrature() gives a rule for.
constexpr int MaxSimplexDegree = 12;

/// A quadrature rule on the simplex of a dimension (see the file's comment).
struct SimplexRule
{
  int Dimension = 0; ///< 1 segment, 2 triangle, 3 tetrahedron
  int Degree = 0;    ///< exact for every polynomial of total degree <= Degree
  int Points = 0;
  /// (Dimension + 1) barycentric coordinates per point, point after point;
  /// the first is that of corner 0 (1 - the reference coordinates' sum).
  std::vector<double> Barycentric;
  /// One per point: positive, summing to 1 (a fraction of the measure).
  std::vector<double> Weight;
};

/**
 * The rule for `dimension` (1, 2 or 3) exact to total degree `degree`
 * (0 to MaxSimplexDegree). Throws std::out_of_range for other arguments.
 * The reference stays valid for the program's life.
 */
const SimplexRule& SimplexQuadrature(int dimension, int degree);
} // namespace mp

#endif
