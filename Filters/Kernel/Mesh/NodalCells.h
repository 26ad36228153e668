// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalCells.h
 * @brief Second-order cells as the kernel sees them: split into simplices on
 *        their own nodes, and remembered whole with those nodes.
 *
 * A quadratic cell (a 6-node triangle, a 10-node tetrahedron, ...) reaches
 * the kernel twice over:
 *  - as the simplices it is split into on its own nodes (corners, mid-edge,
 *    mid-face and body nodes; Geometry/NodalSplit.h), each naming the cell
 *    as its parent (MeshView::Parent). The intersections, the search, the
 *    covered fractions and P0 live on these simplices, so a curved cell is
 *    met as the polygon or polyhedron through its nodes;
 *  - as the cell itself, here: its type and its nodes in the cell's own
 *    order (VTK's order for its quadratic cells), so that a field given at
 *    the nodes is read with the cell's own shape functions
 *    (Geometry/NodalShapes.h) and not as linear on each simplex.
 *
 * A mesh without second-order cells has no NodalCells (MeshView::Nodal is
 * null). In a mesh with some, a linear parent has type None and no nodes.
 */
#ifndef MeshProjection_Kernel_NodalCells_h
#define MeshProjection_Kernel_NodalCells_h

#include "Mesh/MeshView.h"

#include <cstdint>

namespace mp
{
/// A cell with nodes beyond its corners, in VTK's node order of the
/// quadratic cell named. The order-2 Lagrange cells are given in the
/// order of the quadratic cell with the same nodes.
enum class NodalType : std::uint8_t
{
  None = 0,  ///< a linear cell: its simplices carry P1
  Edge3,     ///< VTK_QUADRATIC_EDGE
  Triangle6, ///< VTK_QUADRATIC_TRIANGLE
  Quad8,     ///< VTK_QUADRATIC_QUAD
  Quad9,     ///< VTK_BIQUADRATIC_QUAD
  Tetra10,   ///< VTK_QUADRATIC_TETRA
  Hexa20,    ///< VTK_QUADRATIC_HEXAHEDRON
  Hexa27,    ///< VTK_TRIQUADRATIC_HEXAHEDRON
  Wedge15,   ///< VTK_QUADRATIC_WEDGE
  Wedge18,   ///< VTK_BIQUADRATIC_QUADRATIC_WEDGE
  Pyramid13  ///< VTK_QUADRATIC_PYRAMID
};

/**
 * Per parent cell of a MeshView (MeshView::Parents() of them): its nodal
 * type and its nodes as kernel point ids, in the type's order, stored
 * cell after cell (cell p: Nodes[Offsets[p]] .. Nodes[Offsets[p + 1] - 1];
 * a None cell has none).
 */
struct NodalCells
{
  const NodalType* Type = nullptr;
  const long long* Offsets = nullptr; ///< Parents() + 1 entries
  const long long* Nodes = nullptr;
};
/**
 * Calls f(p) for each point of simplex c that carries a function: its
 * corners, or, when one of them is a geometric-only point (a curved cell
 * split finer than on its nodes: MeshView::GeometricPoints), its parent's
 * nodes, which are the functions living on it. Graphs of functions over
 * the simplices (the fringe's rings, the extrapolation's neighbours) then
 * join a refined cell's nodes as its split on the nodes did.
 */
template <class F>
void ForEachFunctionPoint(const MeshView& mesh, Index c, F&& f)
{
  const CellCorners corners = mesh.Cell(c);
  const int n = mesh.CornersPerCell();
  bool geometric = false;
  for (int k = 0; k < n; ++k)
  {
    geometric = geometric || !mesh.HasFunction(corners[k]);
  }
  if (!geometric)
  {
    for (int k = 0; k < n; ++k)
    {
      f(corners[k]);
    }
    return;
  }
  if (!mesh.Nodal)
  {
    // (A copy of the mesh without its parents: its functions' points only.)
    for (int k = 0; k < n; ++k)
    {
      if (mesh.HasFunction(corners[k]))
      {
        f(corners[k]);
      }
    }
    return;
  }
  const Index p = mesh.ParentOf(c);
  for (long long i = mesh.Nodal->Offsets[p]; i < mesh.Nodal->Offsets[p + 1]; ++i)
  {
    f(static_cast<Index>(mesh.Nodal->Nodes[i]));
  }
}
} // namespace mp

#endif
