// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BernsteinForm.h
 * @brief The Bernstein (Bezier) basis of a second-order target's own space
 *        (NodalSpace.h), and the change of basis between it and the nodes:
 *        what the lumped mass and the bounds of such a target live on.
 *
 * A quadratic corner function of a triangle or tetrahedron integrates to
 * zero or less, so the nodal functions give no lumped mass and no weights
 * for bounds. The same space has a basis of non-negative functions that
 * sum to 1: the Bernstein polynomials of degree 2, one per node, in the
 * barycentric coordinates lambda of a simplex (lambda_a^2 for corner a,
 * 2 lambda_a lambda_b for the mid-edge node of a and b), in tensor
 * products of the 1D ones ((1 - t)^2, 2 t (1 - t), t^2) on Quad9 and
 * Hexa27, and the triangle's times the 1D ones on Wedge18. Each is
 * evaluated through the cell's own reference map, like the nodal
 * functions, so curved cells are served alike. Neighbouring cells agree
 * on their common faces: the global Bernstein functions are continuous
 * and every function of the space is sum_m b_m B_m.
 *
 * In the nodal basis B_m = sum_n C_nm N_n with C_nm = B_m(node n): the
 * field with Bernstein coefficients b has the node values u = C b, e.g.
 * u = (b_a + b_b) / 4 + b_ab / 2 at a mid-edge node. C is sparse (C_nm is
 * not zero only when node m lies on the closure of the edge, face or cell
 * node n stands for), its rows are non-negative and sum to 1, and it is
 * triangular when the nodes are ordered by that dimension (corners, then
 * edges, faces, bodies), which gives b = C^-1 u one node at a time. Points
 * of linear cells keep their P1 functions (the degree-1 Bernstein ones):
 * their rows are the identity's.
 *
 * Quad8, Hexa20, Wedge15 and Pyramid13 have no such basis (the
 * serendipity spaces hold no non-negative basis with one function per
 * node that sums to 1): a mesh with any of them has no Bernstein form
 * (Covers).
 *
 * The sums of rows are taken in an order that depends on the values only
 * (sorted terms), so that processes that share a node compute it alike
 * whatever their local numbering.
 */
#ifndef MeshProjection_Kernel_BernsteinForm_h
#define MeshProjection_Kernel_BernsteinForm_h

#include "Mesh/MeshView.h"
#include "Mesh/NodalCells.h"
#include "Transfer/CsrMatrix.h"

#include <vector>

namespace mp
{
class BernsteinForm
{
public:
  /// Whether cells of `type` have a Bernstein basis here (Edge3,
  /// Triangle6, Tetra10, Quad9, Hexa27, Wedge18; None: P1, itself one).
  static bool Supports(NodalType type);
  /// Whether every parent of `mesh` is of a supported type (true without Nodal).
  static bool Covers(const MeshView& mesh);
  /**
   * The Bernstein functions of a cell of `type` at reference point xi,
   * one per node in the type's node order (function m belongs to node m).
   */
  static void Values(NodalType type, const double* xi, double* B);

  /// C on the point functions of `mesh` (Covers(mesh) must hold).
  void Build(const MeshView& mesh);
  /// Whether Build never ran (a mesh without second-order cells: identity).
  /// A part with no points, built, is not Empty: it takes part in the
  /// collective steps of a distributed Apply like the others.
  bool Empty() const { return !this->Built; }

  /// u = C b: node values from Bernstein coefficients (rows x components, row-major).
  void ToNodes(const double* b, int components, double* u) const;
  /**
   * The same when only the coefficients with `usable` set are known: each
   * node's value from those, its weights rescaled to sum to 1 (0 when it
   * has none).
   */
  void ToNodes(const double* b, int components, const std::vector<char>& usable, double* u) const;
  /// b = C^-1 u: Bernstein coefficients from node values.
  void FromNodes(const double* u, int components, double* b) const;
  /// y = C^T x (x: per node, y: per Bernstein function), e.g. the
  /// functions' integrals from the nodal functions' ones.
  void Transpose(const double* x, int components, double* y) const;

  /// The matrix C (rows: nodes, columns: Bernstein functions, one per node).
  const CsrMatrix& GetMatrix() const { return this->C; }
  /// Bytes held (0 when Empty).
  size_t MemoryBytes() const;

private:
  CsrMatrix C;
  std::vector<Index> Order; ///< the nodes by the dimension of what they stand for
  bool Built = false;
};
} // namespace mp

#endif
