// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CurvedSplit.h
 * @brief Curved second-order cells split finer than on their own nodes: a
 *        lattice of order 2L in reference space, mapped through the cell's
 *        isoparametric map, so that the simplices approach the curved cell
 *        as 1 / L^2.
 *
 * NodalSplit.h splits a second-order cell on its nodes: a curved cell (mid
 * nodes off its straight edges) is then the polygon or polyhedron through
 * them. At level L >= 2 a curved Edge3, Triangle6, Tetra10, Quad8 or Quad9
 * is split instead on the lattice of order n = 2L of its reference cell
 * (the nodes are the lattice of order 2, a sub-lattice of it), each lattice
 * point xi placed at x(xi) = sum_n N_n(xi) X_n (NodalShapes.h):
 *  - Edge3: n segments; Triangle6: the n^2 triangles of the triangle
 *    lattice; Quad8, Quad9: the n^2 sub-squares, each cut along the
 *    diagonal from its lowest lattice corner;
 *  - Tetra10: the n^3 tetrahedra of Freudenthal's (Kuhn's) subdivision,
 *    whose edges run along the 6 directions of the cell's edges, and
 *    whose faces on each cell face are the face's triangle lattice.
 * Every simplex keeps the cell's orientation (positive in the reference
 * cell); a refinement whose simplices do not all have one orientation (the
 * isoparametric map folds) is refused, and the caller keeps NodalSplit's.
 *
 * The bound: on an edge with mid node m and ends a, b, let
 * d = m - (a + b) / 2. The quadratic map is the chord's affine map plus
 * 4 t (1 - t) d; its piecewise linear interpolant on sub-intervals of
 * length 1 / n misses it by at most |d| / n^2 = |d| / (4 L^2) (at each
 * sub-interval's middle). The refined cell's region differs from the
 * curved cell's only along its boundary (inside, its simplices tile it
 * whatever their diagonals), and on a triangle face the lattice's edges run
 * along the face's 3 edge directions, on each of which only that edge's
 * 4 lambda_a lambda_b d_e term curves: so the refined cell's boundary lies
 * within |d_e| / (4 L^2) of a curved edge e, and within the sum of its
 * edges' bounds on a tetrahedron's curved face. L = 1 (NodalSplit's) is
 * |d_e| / 4; each level divides it by L^2, and the measure's error falls
 * alike.

 * Lattice points that are not nodes are new points. A point on an edge
 * (or a tetrahedron's face) is computed from that edge's (face's) own
 * nodes, in the order of their keys, with the edge's (face's) own
 * quadratic functions: two cells sharing the edge or face compute the same
 * bits, and the splitter gives them one id (named by the corners' ids and
 * the point's lattice weights on them). Points inside a cell are its own.
 * Shared curved faces are thus split alike and the refined simplices are
 * conforming between curved cells; a face a curved cell shares with a
 * straight (unrefined) cell is refined on one side only: its lattice
 * points lie on the straight face's flat sub-facets (the map is affine
 * there), so the two sides still tile the same face, with hanging points,
 * as a linear cell next to a quadratic one has.
 */
#ifndef MeshProjection_Kernel_CurvedSplit_h
#define MeshProjection_Kernel_CurvedSplit_h

#include "Geometry/CellSplit.h"
#include "Mesh/MeshView.h"
#include "Mesh/NodalCells.h"

#include <array>
#include <cstddef>
#include <unordered_map>
#include <vector>

namespace mp
{
/// Whether CurvedSplitter refines cells of this type (Edge3, Triangle6,
/// Tetra10, Quad8, Quad9); the others keep NodalSplit's split.
bool IsRefinedWhenCurved(NodalType type);

/**
 * The largest |d_e| / (4 L^2) of a cell's edges relative to its size (the
 * corners' bounding-box diagonal), d_e the offset of edge e's mid node from
 * the middle of its chord: the sag the refinement at `level` leaves on that
 * edge (see the file's comment). 0 for a straight cell or a type with no
 * mid-edge nodes.
 */
double RelativeCurvedSag(NodalType type, const double* points, const Index* nodes, int level);

/**
 * Splits curved second-order cells at one level, adding the lattice points
 * that are not nodes. Construct with the mesh's points (3 per id), the id
 * the first added point gets (the mesh's point count), the level (>= 2;
 * below, nothing is ever refined) and the keys (optional, one per point id,
 * as in CellSplit.h: the order in which a shared edge's or face's points are
 * computed, so that pieces of a distributed mesh with global keys compute
 * the same bits).
 */
class CurvedSplitter
{
public:
  CurvedSplitter(const double* points, Index firstNew, int level, const Index* keys = nullptr);

  /**
   * Appends the refined simplices of cell `nodes` (NodalNodeCount(type)
   * ids in the type's order) to `simplices`, with ids of the mesh's points
   * and of added points. Returns false, appending and adding nothing, when
   * the type is not refined, the level is below 2, or the refinement folds.
   * Call only for curved cells (a straight cell refined would be split
   * into more simplices of the same shape).
   */
  bool Split(NodalType type, const Index* nodes, std::vector<Index>& simplices);

  /// The added points, 3 coordinates each: id firstNew + k is point k.
  const std::vector<double>& AddedPoints() const { return this->Added; }
  Index AddedCount() const { return static_cast<Index>(this->Added.size() / 3); }
  int Level() const { return this->Order / 2; }

private:
  /// A lattice point shared by cells: its corners' ids and its integer
  /// weights on them (as many pairs as corners it is between, 2 or 3),
  /// ids ascending, unused entries -1.
  using Name = std::array<Index, 6>;
  struct NameHash
  {
    std::size_t operator()(const Name& n) const;
  };
  /// One lattice point of the cell being split: its integer weights on
  /// the corners (or tensor coordinates for quadrilaterals), and its
  /// position.
  struct Local
  {
    int W[4];
    double X[3];
    Index Id; ///< the mesh point it is, or -1 (to add)
  };

  void Lattice(NodalType type, const Index* nodes);
  void Place(NodalType type, const Index* nodes, Local& p) const;
  void PlaceOnEdge(NodalType type, const Index* nodes, int a, int b, int wa, Local& p) const;
  void PlaceOnFace(const Index* nodes, const int (&c)[3], const int (&w)[3], Local& p) const;
  bool OneSigned(NodalType type, const Index* nodes) const;
  Index IdOf(NodalType type, const Index* nodes, Local& p);
  Index KeyOf(Index id) const { return this->Keys ? this->Keys[id] : id; }

  const double* Points;
  Index FirstNew;
  int Order; ///< 2 L
  const Index* Keys;
  std::vector<double> Added;
  std::unordered_map<Name, Index, NameHash> Shared;
  std::vector<Local> Lat;   ///< the current cell's lattice points
  std::vector<int> Simplex; ///< and its simplices, in lattice indices
};
} // namespace mp

#endif
