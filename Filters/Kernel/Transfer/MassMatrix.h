// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MassMatrix.h
 * @brief The target mass matrix M_tt of a space, assembled once the search is done.
 *
 * P1: the point graph of the mesh (every pair of points sharing a cell, and
 * every point with itself), built from the cells around each point in
 * concurrent tasks over point ranges; the values by the same ranges, each
 * task through the cells around its points only (about its share of the
 * cells, even where the cells' ids around a range of points reach far, as
 * along the seams of a Morton order). P0: the diagonal.
 *
 * The values come from what the search left per target cell (CellMasses):
 * nothing, the element mass of the whole cell (covered whole: to 1e-12 of
 * its measure), or the block of its covered part. Only the last are kept
 * as blocks (the cells on the edge of the covered region), so that M_tt
 * takes no memory during the search, when both meshes and their
 * neighbours are alive; the whole cells' blocks are formed again here from
 * the geometry. Each row sums its cells' blocks in the order of its cells
 * (increasing ids), whatever the number of tasks.
 */
#ifndef MeshProjection_Kernel_MassMatrix_h
#define MeshProjection_Kernel_MassMatrix_h

#include "Geometry/CellGeometry.h"
#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"
#include "Transfer/CsrMatrix.h"
#include "Transfer/Space.h"

#include <cmath>
#include <limits>
#include <vector>

namespace mp
{
/**
 * One task's blocks of target cells covered in part (or more than whole):
 * per cell its id and the upper triangle of its symmetric block, row by
 * row, on the cell's corners in the mesh's order (P1; P0: its one entry).
 */
struct PartialMasses
{
  std::vector<Index> Cells;   ///< kernel cell ids
  std::vector<double> Blocks; ///< Dofs (Dofs + 1) / 2 per cell
  /// Adds cell c's block m (on functions `dofs`, which are the cell's
  /// corners in any order for P1).
  template <int N>
  void Add(const MeshView& mesh, Index c, const Index (&dofs)[N], const double (&m)[N][N])
  {
    int place[N]; // dofs[i] is corner place[i] of the cell
    place[0] = 0;
    if (N > 1)
    {
      const CellCorners ids = mesh.Cell(c);
      for (int i = 0; i < N; ++i)
      {
        place[i] = 0;
        while (ids[place[i]] != dofs[i])
        {
          ++place[i];
        }
      }
    }
    double ordered[N][N];
    for (int i = 0; i < N; ++i)
    {
      for (int k = 0; k < N; ++k)
      {
        ordered[place[i]][place[k]] = m[i][k];
      }
    }
    this->Cells.push_back(c);
    for (int a = 0; a < N; ++a)
    {
      this->Blocks.insert(this->Blocks.end(), ordered[a] + a, ordered[a] + N);
    }
  }
};

/**
 * What M_tt takes from each target cell, left by the search: per kernel
 * cell a float, -infinity for none (no piece of positive measure), +infinity
 * for a block kept in Partial (covered in part, or more than whole), else
 * the cell covered whole: its covered measure is SimplexMeasure x (1 + the
 * float) (within 1e-12 of it: the float keeps that deviation to 1e-19), and
 * its block the element mass d!/(d+2)! (1 + delta_ik) times that measure
 * (P0: the measure), as MassFromMoments gives it (Space.h).
 */
struct CellMasses
{
  static constexpr float None = -std::numeric_limits<float>::infinity();
  static constexpr float Part = std::numeric_limits<float>::infinity();
  UninitializedLargeVector<float> State; ///< per kernel cell
  int Dofs = 0;                          ///< functions per cell
  PartialMasses Partial;                 ///< sorted by cell (Gather)

  /// The covered measure of kernel cell c, covered whole per State.
  static double Covered(const MeshView& mesh, Index c, float state)
  {
    return SimplexMeasure(mesh, c) * (1.0 + static_cast<double>(state));
  }
  /// The State of a cell of `covered` measure, or Part when not covered whole.
  static float StateOf(const MeshView& mesh, Index c, double covered)
  {
    const double whole = SimplexMeasure(mesh, c);
    return std::fabs(covered - whole) <= 1e-12 * whole ? static_cast<float>(covered / whole - 1.0)
                                                       : Part;
  }
  /// The tasks' blocks, appended in task order, then sorted by cell.
  void Gather(std::vector<PartialMasses>& tasks);
  /// The block of kernel cell c (state Part), as PartialMasses keeps it.
  const double* Find(Index c) const;
};

/// A value per cell of a mesh: Values[ByParent ? mesh.ParentOf(c) : c]
/// (null Values: none).
struct CellValues
{
  const double* Values = nullptr;
  bool ByParent = false;
};

/**
 * M_tt for `space` on `mesh` from `masses` (null: the pattern with zero
 * values). With `pointCover` and `cellValue`, for P1 with masses: per
 * point of `mesh`, the largest value of its cells (0 for a point no cell
 * uses), made by the same pass over the cells; else `pointCover` is left
 * empty.
 */
void AssembleTargetMass(SpaceType space, const MeshView& mesh, const CellMasses* masses,
  const TaskRunner& runner, CsrMatrix& matrix, const CellValues& cellValue = CellValues(),
  LargeVector<double>* pointCover = nullptr);

/// The CSR pattern of M_tt for `space` on `mesh`, with zero values.
void MassPattern(
  SpaceType space, const MeshView& mesh, const TaskRunner& runner, CsrMatrix& matrix);
} // namespace mp

#endif
