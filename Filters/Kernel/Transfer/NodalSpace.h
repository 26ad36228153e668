// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalSpace.h
 * @brief Point data in the cells' own space: on a second-order parent its
 *        own shape functions through the inverse of its isoparametric map,
 *        on a linear parent P1 of its simplices; and the cell and corner
 *        functions beside it, all evaluated at points.
 *
 * A mesh with second-order cells (MeshView::Nodal, Mesh/NodalCells.h)
 * reaches the kernel as the simplices of its cells' split on their own
 * nodes. Its point functions stay one per kernel point (SpaceSize is
 * unchanged), but on a simplex whose parent has a NodalType they are the
 * parent's shape functions N_n(xi(x)), xi the inverse of the parent's
 * isoparametric map (Geometry/NodalShapes.h): every node of the parent
 * lives on each of its simplices. A curved parent's functions are its true
 * isoparametric ones, evaluated at points of the pieces cut from its
 * straight split. On an affine parent (a straight simplex: Edge3,
 * Triangle6, Tetra10 with its mid nodes on its straight edges; a
 * parallelogram, parallelepiped or straight prism) the inverse map is
 * affine and is taken once per cell; other parents (curved ones, general
 * quads, hexahedra, wedges, pyramids) take Newton's inverse at every point
 * (Geometry/NodalShapes.h: NodalInverse, prepared once per parent), started
 * from the point's image under the affine map of the split simplex it lies
 * in (its corners are nodes of the parent, whose reference points are
 * known). Where Newton fails from there and from the reference centre (a
 * point past a fold of a strongly curved cell, a singular Jacobian), the
 * functions are those at that start, and the point is counted
 * (Unconverged) for the filter's warning. A Quad8, Hexa20
 * or Wedge15 parent that is not an affine image of its reference cell
 * takes its complete sibling's functions with hidden nodes
 * (Geometry/HiddenNodes.h), their weights taken when the parent is bound,
 * so that quadratics stay in its space on straight cells.
 *
 * These functions are not affine on a piece, so the moments of the linear
 * path (Space.h) cannot integrate them: QuadratureAssembler.h integrates
 * them by quadrature at the points this file evaluates them at.
 *
 * NodalFunctions evaluates one cell's functions of one kind (the point
 * functions above, P0 per parent, DP1 per simplex corner) at points given
 * with the mesh's SpaceDimension coordinates.
 */
#ifndef MeshProjection_Kernel_NodalSpace_h
#define MeshProjection_Kernel_NodalSpace_h

#include "Geometry/HiddenNodes.h"
#include "Geometry/NodalShapes.h"
#include "Mesh/MeshView.h"
#include "Mesh/NodalCells.h"
#include "Transfer/Space.h"

#include <algorithm>
#include <string>

namespace mp
{
/// The most functions a cell has (a 27-node hexahedron).
constexpr int MaxNodalFunctions = MaxNodalNodes;

/// Whether point functions on `mesh` are the cells' own (it has Nodal).
inline bool HasNodalSpace(SpaceType space, const MeshView& mesh)
{
  return space == SpaceType::P1 && mesh.Nodal != nullptr;
}

/// The type of parent p of a mesh (None without Nodal).
inline NodalType NodalTypeOf(const MeshView& mesh, Index p)
{
  return mesh.Nodal ? mesh.Nodal->Type[p] : NodalType::None;
}

/// How many functions of `space` every cell of `mesh` has, when all have
/// as many (a mesh of one cell type); else 0.
int UniformFunctionCount(const MeshView& mesh, SpaceType space);

/**
 * The checks of a mesh's Nodal arrays: offsets increasing from 0, each
 * nodal parent with its type's node count, nodes that exist, and every
 * simplex of a nodal parent on that parent's nodes only. An error naming
 * the first bad parent, or empty.
 */
std::string CheckNodalCells(const MeshView& mesh, const char* name);

/**
 * One cell's functions of one space, bound to a kernel cell (Bind) and
 * evaluated at points (Values):
 *  - P1: the parent's nodes when it has a NodalType (its shape functions
 *    through the inverse map), else the simplex's corners (barycentric);
 *  - P0: the parent's one function, 1;
 *  - DP1: the simplex's corners' own functions (c (d + 1) + k).
 * Rebinding the same cell (or a simplex of the same second-order parent)
 * costs nothing: a task keeps one per side, each bound to one mesh only.
 */
class NodalFunctions
{
public:
  /// Binds kernel cell c of `mesh` for `space`.
  void Bind(const MeshView& mesh, SpaceType space, Index c);
  /// The bound functions' values at x (SpaceDimension coordinates), in the order of Dofs.
  void Values(const double* x, double* values) const;
  /**
   * An affine cell's functions read from coordinates that are affine in x
   * (the barycentric ones, or a second-order parent's reference ones):
   * those of x into c (at most 4; their count returned), and the values
   * from such c, which may be a barycentric combination of several points'
   * (a quadrature point's from its simplex's corners').
   */
  int Coordinates(const double* x, double* c) const;
  void ValuesAt(const double* c, double* values) const;

  /**
   * Points of non-affine parents whose inverse map failed (NodalInverse:
   * not converged, singular, or past a fold), evaluated at the start
   * instead: counted by Values, summed by the assembler for the warning.
   */
  mutable Index Unconverged = 0;

  /// Whether the functions are polynomials of x (an affine cell: a
  /// straight or linear parent, P0, DP1), so that rules integrate them exactly.
  bool IsAffine() const { return this->Affine; }

  /// What the bound functions are the same on: the parent for a
  /// second-order parent's functions and for P0, else the cell.
  Index Key() const
  {
    return this->Space == SpaceType::P0 || this->Type != NodalType::None ? this->Parent
                                                                         : this->Cell;
  }
  /// The Key of kernel cell c's functions of `space`.
  static Index KeyOf(const MeshView& mesh, SpaceType space, Index c)
  {
    const Index p = mesh.ParentOf(c);
    const bool byParent =
      space == SpaceType::P0 || (space == SpaceType::P1 && NodalTypeOf(mesh, p) != NodalType::None);
    return byParent ? p : c;
  }

  int Count = 0;                   ///< functions on the cell
  Index Dofs[MaxNodalFunctions];   ///< their global numbers
  int Degree = 1;                  ///< polynomial degree on a straight cell (P0: 0)
  Index Cell = -1;                 ///< the bound kernel cell
  SpaceType Space = SpaceType::P1; ///< the bound space

private:
  /// The barycentric coordinates 0..d of x in the affine simplex (of its
  /// orthogonal projection onto a facet's plane or a segment's line).
  void Barycentric(const double* x, double* lambda) const;
  /// Origin and Inverse for the simplex on points `simplex` of `mesh`
  /// (Corners of them); false, Inverse 0, when it is degenerate.
  bool AffineMap(const MeshView& mesh, const Index* simplex);
  /// Inverse for a facet or segment in a higher space from its edges e
  /// (column k - 1: corner k - corner 0); false when they are dependent.
  bool ProjectionInverse(const double (&e)[3][3]);
  /// A non-affine parent's simplex c: its affine map, and its corners'
  /// reference points into Reference (the start of Newton's inverse).
  void BindSimplex(const MeshView& mesh, Index c);
  /// A non-affine serendipity parent (Quad8, Hexa20, Wedge15): its
  /// functions become its complete sibling's with hidden nodes
  /// (Geometry/HiddenNodes.h), their weights taken for this cell, and
  /// its Degree.
  void BindHiddenNodes();

  NodalType Type = NodalType::None;
  Index Parent = -1;         ///< of the bound cell
  int Dimension = 2;         ///< coordinates of a point (the mesh's SpaceDimension)
  int Corners = 3;           ///< of the affine simplex (Dimension + 1)
  bool Affine = true;        ///< the values come from the barycentric coordinates
  double Origin[3] = {};     ///< corner 0 of the affine simplex
  double Inverse[3][3] = {}; ///< x - Origin (Dimension coordinates) to barycentric 1..d
  /// The reference coordinates of the affine simplex's corners (a nodal
  /// parent's: an affine one's frame, else the bound simplex's).
  double Reference[4][3] = {};
  NodalInverse Map;                                ///< a non-affine parent's inverse map
  double Nodes[3 * MaxNodalFunctions] = {};        ///< the parent's nodes (3 coordinates each)
  NodalType Sibling = NodalType::None;             ///< non-affine serendipity: the complete sibling
  double Hidden[MaxHiddenNodes * MaxHiddenOwners]; ///< its hidden nodes' weights
};
} // namespace mp

#endif
