// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NodalTypes.h
 * @brief VTK's second-order cell types as the kernel's mp::NodalType: which
 *        nonlinear cells the filter accepts, and their nodes in the order of
 *        the quadratic cell with the same nodes.
 *
 * Accepted: VTK's quadratic edge, triangle, quadrilateral (8 nodes),
 * biquadratic quadrilateral (9), tetrahedron (10), hexahedron (20),
 * triquadratic hexahedron (27), wedge (15), biquadratic-quadratic wedge
 * (18) and pyramid (13), and the Lagrange curve, triangle, quadrilateral,
 * tetrahedron, hexahedron and wedge of order 2 (3, 6, 9, 10, 27 and 18
 * nodes). A Lagrange cell's nodes are mapped to the quadratic cell's by
 * their parametric coordinates (vtkCell::GetParametricCoords of both,
 * matched once per type), so the map follows VTK's numbering whatever it
 * is. Every other nonlinear type (higher Lagrange orders, Bézier cells,
 * quadratic-linear cells, the biquadratic triangle, the cubic line, ...)
 * is refused by name.
 *
 * Not a public class of the module: no export macro, not wrapped.
 */
#ifndef MeshProjection_Adapter_NodalTypes_h
#define MeshProjection_Adapter_NodalTypes_h

#include "Mesh/NodalCells.h"

#include "vtkType.h"

#include <array>
#include <string>

class vtkDataSet;

namespace mpvtk
{
/// Whether cells of VTK type `type` are accepted as second-order cells
/// (for Lagrange types: when they are of order 2, see NodalCellTypes).
bool IsAcceptedNonlinear(int type);

/// The sentence that lists the accepted nonlinear cells, for messages.
const char* AcceptedNonlinearCells();

/**
 * The nodal type of each accepted VTK type, and for Lagrange types the
 * map to the quadratic cell's node order (built from the parametric
 * coordinates on first use of each type).
 */
class NodalCellTypes
{
public:
  /**
   * The kernel's type of a cell of VTK type `type` with `npts` nodes, or
   * None when it is not an accepted second-order cell (a Lagrange cell of
   * another order, a wrong count). `data` gives the HigherOrderDegrees
   * cell array of Lagrange cells, when it has one (cell `c`'s degrees must
   * then be 2).
   */
  mp::NodalType TypeOf(int type, vtkIdType npts, vtkDataSet* data, vtkIdType c);
  /**
   * `nodes` (in VTK's order for `type`, NodalNodeCount(nodal) of them)
   * into `ordered`, in the order of the quadratic cell `nodal`.
   */
  void Order(int type, mp::NodalType nodal, const vtkIdType* nodes, long long* ordered);

private:
  /// Lagrange node of each quadratic node, per Lagrange type (68..73);
  /// empty until first used.
  std::array<std::array<int, 27>, 6> Maps{};
  std::array<bool, 6> Built{};
};
} // namespace mpvtk

#endif
