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
 * Quad8, Hexa20, Wedge15 and Pyramid13 have no Bernstein basis; their
 * form takes the same kind of C, a corner's row itself and a mid-edge
 * node's s (b_a + b_b) + (1 - 2 s) b_e (EdgeShare), and the functions
 * Psi_m = sum_n C_nm phi_n of their own functions phi (VTK's on affine
 * cells; the complete sibling's with hidden nodes elsewhere,
 * Geometry/HiddenNodes.h), which sum to 1 (C's rows do). With s = 1/4
 * (the edge's quadratic Bernstein relation) a corner's Psi dips below
 * zero; with s = 7/16 those of Quad8, Hexa20 and Wedge15 are
 * non-negative on affine cells (in reference coordinates a corner's is
 * the linear cell's corner function times 1 - (x + y) / 4, 1 - (x + y +
 * z) / 4 or (3 + lambda - z) / 4: s >= 3/8, 5/12 and 3/8 would do), and
 * integrate to 5/24 and
 * 1/24 of an affine Quad8 at corners and edges, 3/32 and 1/48 of a
 * Hexa20, 19/144 and 1/48 (1/36 on the vertical edges) of a Wedge15. On
 * other cells the hidden nodes' weights move them a little and they may
 * dip below zero; VTK's Pyramid13 would need s near 0.45 and keeps 1/4
 * (its Psi integrate to 1/30 and 1/10 of the cell at base corners and
 * apex, 7/60 and 3/40 at base and slanted edges, and dip below zero), so
 * that it shares its edges with tetrahedra. These four types' forms are
 * Signed: a lumped coefficient need not be a mean, and an Apply clips
 * them (MassType::Lumped). Node values, convex combinations of the
 * coefficients, keep their bounds; the field between them does where the
 * Psi are non-negative. The two shares on one edge would make its row
 * depend on which cell read it: a mesh whose second-order cells take
 * both has no form (EdgeShares, Covers).
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
  /// Whether cells of `type` have a form here (every nodal type: a
  /// Bernstein basis for Edge3, Triangle6, Tetra10, Quad9, Hexa27,
  /// Wedge18 and None, P1 itself one; a signed one for the others).
  static bool Supports(NodalType type);
  /// Whether `type`'s form may be signed (Quad8, Hexa20, Wedge15, Pyramid13).
  static bool Signed(NodalType type);
  /// The weight s of each corner in a mid-edge node's row (1/4, or 7/16
  /// for Quad8, Hexa20 and Wedge15).
  static double EdgeShare(NodalType type);
  /// Which shares the second-order parents of `mesh` take (bits).
  enum
  {
    QuarterShare = 1,
    SevenSixteenthsShare = 2
  };
  static int EdgeShares(const MeshView& mesh);
  /// Whether every parent of `mesh` is of a supported type and they take
  /// one share (true without Nodal). A distributed mesh needs the parts to
  /// agree on EdgeShares too: a part's edges are its neighbours'.
  static bool Covers(const MeshView& mesh);
  /// Whether some parent of `mesh` has a signed form.
  static bool HasSigned(const MeshView& mesh);
  /**
   * The functions of a cell of `type` at reference point xi, one per node
   * in the type's node order (function m belongs to node m): the
   * Bernstein ones, or for a signed type sum_n C_nm N_n with the type's
   * own functions N (those of an affine cell).
   */
  static void Values(NodalType type, const double* xi, double* B);

  /// C on the point functions of `mesh` (Covers(mesh) must hold).
  void Build(const MeshView& mesh);
  /// Whether the mesh built on has a signed form (HasSigned).
  bool IsSigned() const { return this->AnySigned; }
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
  bool AnySigned = false;
};
} // namespace mp

#endif
