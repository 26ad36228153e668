// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MeshView.h
 * @brief Non-owning view of a simplicial mesh given as flat arrays.
 *
 * The kernel never owns mesh data: callers (the VTK filter, tests, a future
 * numpy binding) hand it pointers to their own arrays. A mesh of dimension d
 * holds simplices with d+1 corners (triangles for d = 2, tetrahedra for
 * d = 3), stored cell after cell in `Connectivity`. Points are always stored
 * with three coordinates (x, y, z), as VTK does; 2D meshes ignore z.
 *
 * Face k of a cell is the face opposite its corner k. `Neighbors`, when set,
 * holds for every cell and every face the cell across that face, or -1.
 */
#ifndef MeshProjection_Kernel_MeshView_h
#define MeshProjection_Kernel_MeshView_h

namespace mp
{
/// Cell and point ids: 64-bit, and the same type as VTK's vtkIdType and
/// vtkTypeInt64 (long long), so VTK's arrays can be viewed without a copy.
using Index = long long;
static_assert(sizeof(Index) == 8, "mp::Index must be a 64-bit integer");

/// Cell ids in the neighbour table: 32 bits (half the memory of the table,
/// which is as large as the connectivity), so meshes searched by the
/// advancing front have fewer than 2^31 cells.
using NeighborId = int;
static_assert(sizeof(NeighborId) == 4, "mp::NeighborId must be a 32-bit integer");

struct MeshView
{
  int Dimension = 2;                   ///< 2: triangles, 3: tetrahedra
  const double* Points = nullptr;      ///< 3 * NumberOfPoints coordinates
  Index NumberOfPoints = 0;
  const Index* Connectivity = nullptr; ///< (Dimension + 1) * NumberOfCells point ids
  Index NumberOfCells = 0;
  const NeighborId* Neighbors = nullptr; ///< (Dimension + 1) * NumberOfCells cell ids or -1

  int CornersPerCell() const { return this->Dimension + 1; }
  const Index* Cell(Index c) const { return this->Connectivity + c * this->CornersPerCell(); }
  const double* Point(Index p) const { return this->Points + 3 * p; }
  Index Neighbor(Index c, int face) const
  {
    return this->Neighbors[c * this->CornersPerCell() + face];
  }
};

/// How intersecting cell pairs are found.
enum class SearchMethod
{
  AdvancingFront = 0, ///< Gander & Japhet's front over cell neighbours: linear complexity
  BruteForce = 1      ///< every target cell against every source cell: the O(n m) oracle
};

/// Counters filled by a pair search; useful in tests, benchmarks and summaries.
struct SearchStatistics
{
  Index IntersectionTests = 0; ///< calls of the cell-cell intersection
  Index TouchingPairs = 0;     ///< pairs whose closed cells meet (possibly in a point or segment)
  Index Pieces = 0;            ///< pairs whose intersection has positive measure
  Index LocatorQueries = 0;    ///< candidate look-ups in the locator (seeds and re-seeds)
  Index FullLocatorQueries = 0; ///< of which among all source cells (the others: boundary cells)
  Index SeedWalks = 0;         ///< walks through the source toward an unseeded target cell
  Index WalkSteps = 0;         ///< source cells those walks went through
  Index DegenerateTargetCells = 0; ///< target cells of zero measure, skipped
  /// Source cells of zero measure, skipped: those the front met (all, for
  /// the brute force); unmet ones could not have mattered.
  Index DegenerateSourceCells = 0;
};
} // namespace mp

#endif
