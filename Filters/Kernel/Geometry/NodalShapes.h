// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalShapes.h
 * @brief The isoparametric shape functions of the second-order cells
 *        (Mesh/NodalCells.h), and the inverse of the map they define.
 *
 * Each NodalType has VTK's reference cell and node order: reference
 * coordinates xi in [0, 1] as vtkCell::GetParametricCoords gives them
 * (NodalReferenceNodes), and one shape function N_n per node with
 * N_n(xi_m) = delta_nm and sum_n N_n = 1. A cell with nodes X_n is the
 * image of its reference cell under x(xi) = sum_n N_n(xi) X_n, and a field
 * with nodal values f_n is f(x(xi)) = sum_n N_n(xi) f_n: the same functions
 * carry the geometry and the field, so every field linear in x is carried
 * exactly, curved cell or not (the partition of unity does it).
 *
 * The functions, in VTK's order and equal to VTK's own
 * (vtkQuadratic*::InterpolationFunctions and InterpolationDerivs, checked
 * by Filters/Testing/Cxx/TestNodalShapesVTK.cxx; for the pyramid the
 * derivatives are those of VTK's functions, which VTK 9.2's own
 * InterpolationDerivs are not), span in the reference coordinates
 * (x, y, z) = xi:
 *  - Edge3, Triangle6, Tetra10 (quadratic Lagrange: lambda_i (2 lambda_i - 1)
 *    at the corners, 4 lambda_i lambda_j at the mid-edge nodes, lambda the
 *    barycentric coordinates): P2, every polynomial of degree <= 2;
 *  - Quad9, Hexa27 (tensor products of the 1D quadratic Lagrange
 *    functions): degree <= 2 in each coordinate;
 *  - Quad8 (serendipity): P2 and x^2 y, x y^2;
 *  - Hexa20 (serendipity): P2, xyz, the six x^2 y, and x^2 yz, x y^2 z,
 *    x y z^2;
 *  - Wedge15: P2 in (x, y) times P1 in z, and z^2, x z^2, y z^2;
 *  - Wedge18: P2 in (x, y) times P2 in z;
 *  - Pyramid13: VTK's functions (VTK 9.2), written out in the .cxx. They
 *    live on the pyramid seen as the cube [0, 1]^3 collapsed at z = 1 (every
 *    xi with z = 1 is the apex; its listed (0, 0, 1) is one of them), are
 *    of degree <= 2 in each coordinate of that cube, Kronecker at the nodes
 *    and sum to 1. They are not the rational pyramid functions
 *    (Bedrosian's), and they do not reproduce every quadratic: on a straight
 *    pyramid with the square base [0, 1]^2 at height 0 and the apex at
 *    height 1, they reproduce 1, x, y, z, xy, xz, yz, z^2 in the physical
 *    coordinates but not x^2 or y^2. Used as they are, so that the field is
 *    the one ParaView shows.
 * So on a straight cell whose corners are an affine image of the
 * reference corners, every type but Pyramid13 reproduces every polynomial
 * of degree <= 2 in the physical coordinates. On a straight cell that is
 * not (a trapezoid: nodes on the corners' multilinear map), Quad9, Hexa27
 * and Wedge18 still do, Quad8, Hexa20, Wedge15 and Pyramid13 reproduce
 * degree 1 only (the point data of the first three takes their complete
 * sibling's space there: Geometry/HiddenNodes.h). Every type reproduces degree 1 on every cell, curved or
 * not (the partition of unity).
 *
 * Products of shape functions are integrated by SimplexQuadrature.h on the
 * simplex pieces; NodalDegree gives the degree the pieces' rule needs.
 */
#ifndef MeshProjection_Kernel_NodalShapes_h
#define MeshProjection_Kernel_NodalShapes_h

#include "Mesh/NodalCells.h"

namespace mp
{
/// The most nodes a NodalType has (Hexa27).
constexpr int MaxNodalNodes = 27;

/// Nodes of the type (0 for None).
int NodalNodeCount(NodalType type);

/// Corners of the type (the first nodes in VTK's order; 0 for None).
int NodalCornerCount(NodalType type);

/// 1 for Edge3, 2 for the surface types, 3 for the volume types, 0 for None.
int NodalCellDimension(NodalType type);

/**
 * The highest total degree, in the reference coordinates, of the type's
 * shape functions: 2 for Edge3, Triangle6 and Tetra10, 3 for Quad8
 * (x^2 y), 4 for Quad9 (x^2 y^2), 4 for Hexa20 (x^2 y z), 6 for Hexa27
 * (x^2 y^2 z^2), 3 for Wedge15 (lambda^2 z), 4 for Wedge18
 * (lambda^2 z^2), 6 for Pyramid13 (VTK's functions have x^2 y^2 z^2).
 * On a cell that is an affine image of its reference (a straight simplex,
 * a parallelogram, a parallelepiped, a straight wedge with parallel
 * triangles), the functions are polynomials of that degree in x, so the
 * product of fields of types a and b is one of degree NodalDegree(a) +
 * NodalDegree(b), which SimplexQuadrature of that degree integrates
 * exactly on any simplex piece. On other cells (curved, trapezoidal, every
 * pyramid) they are not polynomials in x and no finite rule is exact; the
 * same degree is then the natural choice.
 * 0 for None.
 */
int NodalDegree(NodalType type);

/**
 * The reference coordinates of the type's nodes, 3 per node (unused
 * coordinates 0): VTK's GetParametricCoords, e.g. Triangle6 (0,0) (1,0)
 * (0,1) (0.5,0) (0.5,0.5) (0,0.5).
 */
void NodalReferenceNodes(NodalType type, double* xi);

/**
 * The shape functions at reference point xi (its first
 * NodalCellDimension(type) coordinates are read): N[n] for each node n.
 */
void NodalValues(NodalType type, const double* xi, double* N);

/**
 * Their derivatives at xi: dN[n * 3 + a] = dN_n / dxi_a for a below the
 * cell's dimension, 0 for the others.
 */
void NodalDerivatives(NodalType type, const double* xi, double* dN);

/// Both at once (one pass over the nodes): as NodalValues and
/// NodalDerivatives.
void NodalValuesAndDerivatives(NodalType type, const double* xi, double* N, double* dN);

/**
 * The corners' own (multi)linear functions at xi, those of the linear cell
 * on the same corners: barycentric for Edge3, Triangle6 and Tetra10,
 * bilinear and trilinear for the quadrilaterals and hexahedra, lambda_i
 * times 1 - xi_2 or xi_2 for the wedges, and VTK's linear pyramid on the
 * collapsed cube ((1 - xi_2) times the base's bilinear function, xi_2 for
 * the apex). N[c] and dN[c * 3 + a] as for NodalValues and
 * NodalDerivatives, one per corner; either may be null.
 */
void NodalCornerFunctions(NodalType type, const double* xi, double* N, double* dN);

/**
 * The inverse isoparametric map: the xi (3 coordinates written, those past
 * the cell's dimension 0) with sum_n N_n(xi) X_n = x, for the cell with
 * nodes X (3 doubles per node, the first spaceDimension of each read) and
 * the point x (spaceDimension coordinates).
 *
 * When the cell's dimension equals spaceDimension this is Newton's method
 * on the full map, started from the inverse of the corners' (multi)linear
 * map (itself found by Newton; for a simplex it is one affine solve, and a
 * straight simplex gets exactly that solve's xi). When the cell's
 * dimension is lower (a curve or a surface in space) it is Gauss-Newton:
 * the xi of the point of the curved cell nearest to x (its foot), started
 * alike. Points outside the cell are expected (pieces of a straight split
 * of a curved neighbour reach a little past the curved boundary): the map
 * is extrapolated, never clamped, so xi may leave the reference cell.
 *
 * Converges to ~1e-14 in xi (relative to the cell's size, which is 1 in
 * xi): stops at a step below 1e-14 (not applied), after applying one below
 * 1e-9 that is below 1e-3 times the step before it (quadratic convergence:
 * the next would be below 1e-15), or at one below 1e-10 that is more than
 * half the step before it (the steps no longer shrink: rounding).
 * Near the foot of a point off a curve or surface Gauss-Newton converges
 * linearly, at a rate that grows with the point's distance times the
 * cell's curvature. Returns false, with xi the last iterate, when the
 * Jacobian is singular (relative to its columns' lengths, 1e-13) or when
 * 50 steps do not converge; and, when the cell's dimension equals
 * spaceDimension, with xi a converged preimage of x, when the Jacobian
 * there is oriented against the corners' map's at the reference centre
 * (the cell's orientation as its corners give it): x lies past
 * a fold of the extrapolated map (far outside a strongly curved cell,
 * where x has several preimages) or in an inverted part of an invalid
 * cell.
 */
bool NodalReference(
  NodalType type, const double* X, int spaceDimension, const double* x, double* xi);

/**
 * One cell's inverse isoparametric map, for many points: Prepare keeps the
 * cell's nodes relative to its first corner and its orientation (the
 * corners' map's Jacobian at the reference centre), once; then each point
 * is found by NodalReference's full-map Newton iterations and fold check.
 * Find starts them from a reference point the caller knows to be near
 * (the piecewise-affine image of the point on the simplex of the cell's
 * split it lies in: a few steps; on a straight cell, NodalIsStraight,
 * the corners' cheaper map first, as NodalReference does); FindFromCentre is NodalReference's own
 * start (the corners' map inverted from the centre), the same operations
 * and the same xi. Both return false, xi then the last iterate, where
 * NodalReference does.
 */
class NodalInverse
{
public:
  /// Binds the cell of `type` with nodes X (3 doubles each; the first
  /// spaceDimension read); false (nothing found later) for a type without
  /// a dimension or a space it does not fit in.
  bool Prepare(NodalType type, const double* X, int spaceDimension);
  /// xi of x (spaceDimension coordinates) by Newton from `start`; false
  /// too when the xi found lies farther than FindReach from `start` in any
  /// reference coordinate: the extrapolated map has other preimages on the
  /// cell's own orientation far outside it, which a poor start can reach.
  bool Find(const double* x, const double* start, double* xi) const;
  /// (A start from the point's own simplex of the split is within a small
  /// fraction of the reference cell, whose coordinates span 1.)
  static constexpr double FindReach = 0.5;
  /// xi of x from NodalReference's start.
  bool FindFromCentre(const double* x, double* xi) const;
  /// That start: the reference cell's centre (3 coordinates).
  const double* ReferenceCentre() const { return this->Centre; }

private:
  /// x relative to the first corner; false when Prepare failed.
  bool Local(const double* x, double* local) const;
  /// The full map's Newton iterations from xi and the fold check.
  bool Converge(const double* local, double* xi) const;

  NodalType Type = NodalType::None;
  int Dimension = 0;               ///< of the cell
  int Space = 0;                   ///< coordinates of a point
  int Count = 0;                   ///< nodes
  double X[MaxNodalNodes][3] = {}; ///< relative to the first corner
  double Origin[3] = {};           ///< the first corner
  double Centre[3] = {};           ///< NodalReference's start
  double Orientation = 0.0;        ///< the corners' map's determinant at Centre
  bool Straight = false;           ///< NodalIsStraight: the map is the corners'
};

/**
 * Whether the cell is straight: every non-corner node lies where the
 * corners' (multi)linear map puts its reference point, within tolerance
 * times the cell's size (the corners' bounding-box diagonal). Then the
 * isoparametric map is the corners' map (every type's functions hold it):
 * affine for simplices, (multi)linear otherwise, and curved-cell
 * approximations can be skipped.
 */
bool NodalIsStraight(NodalType type, const double* X, int spaceDimension, double tolerance);
} // namespace mp

#endif
