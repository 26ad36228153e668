// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SpatialOrder.h
 * @brief A numbering of a mesh's cells and points that follows space: cells
 *        along a Z-order (Morton) curve through their points, points in the
 *        order those cells first use them.
 *
 * Everything the projection does walks the mesh through space: the front
 * goes from a cell to its neighbours, the neighbours are matched around
 * points, the assembly sums into the rows of a cell's points, the solve
 * multiplies by a matrix whose pattern is the mesh's. When ids follow
 * space, each step reads memory that the previous ones brought into cache;
 * when they do not (a shuffled numbering, a partitioner's, a Delaunay
 * mesher's points in insertion order), nearly every step is a cache miss
 * and the same work takes several times longer. A renumbered copy costs a
 * few passes over the mesh and makes the time independent of the input's
 * numbering.
 *
 * A point's position on the curve is the interleaved bits of its
 * coordinates quantised to 2^16 (2D) or 2^10 (3D) steps per axis of the
 * points' bounding box (axes of zero extent left out: a planar mesh in any
 * plane is ordered in 2D); a cell's is the lowest of its corners'
 * positions, a 32-bit key sorted by a radix sort. A Hilbert curve keeps
 * neighbours slightly closer, but its key costs an unpredictable branch per
 * bit and axis, where the Morton key is a few shifts and masks without a
 * branch.
 */
#ifndef MeshProjection_Kernel_SpatialOrder_h
#define MeshProjection_Kernel_SpatialOrder_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

#include <cstdint>
#include <vector>

namespace mp
{
/**
 * The position along the Z-order curve of the grid cell with integer
 * coordinates x[0..dimension): their bits interleaved (dimension 1 or 2:
 * 32 bits each; 3: the low 21 bits each).
 */
std::uint64_t MortonIndex(const std::uint32_t* x, int dimension);

/// (Written whole by the functions below, not zeroed first.)
struct SpatialOrder
{
  UninitializedLargeVector<Index> Cells;    ///< new cell id -> old cell id
  UninitializedLargeVector<Index> Points;   ///< new point id -> old point id
  UninitializedLargeVector<Index> NewPoint; ///< old point id -> new point id
};

/**
 * The order of `mesh`'s cells along a Z-order curve, each at the lowest
 * position of its corners (ties kept in the old order): order.Cells (the identity for meshes of
 * 2^32 cells or more). Keys are computed in `runner`'s tasks.
 */
void OrderAlongCurve(
  const MeshView& mesh, SpatialOrder& order, const TaskRunner& runner = TaskRunner());

/**
 * `mesh` renumbered by order.Cells, into the caller's arrays: `points` (3
 * per point), `connectivity` (corners per cell, in new point ids) and
 * `parent` (per new cell, mesh.ParentOf of its old cell). The points are
 * numbered in the order the ordered cells first use them, those no cell
 * uses last in their old order (order.Points and order.NewPoint are set).
 * `parent` may be order.Cells itself: each entry is read before it is
 * overwritten. The cells are copied in `runner`'s tasks, which give the
 * same numbering as one task.
 */
void RenumberMesh(const MeshView& mesh, SpatialOrder& order, double* points, Index* connectivity,
  Index* parent, const TaskRunner& runner = TaskRunner());
/// The same with the new connectivity in 32 bits (a mesh of fewer than 2^31 points).
void RenumberMesh(const MeshView& mesh, SpatialOrder& order, double* points,
  std::int32_t* connectivity, Index* parent, const TaskRunner& runner = TaskRunner());

} // namespace mp

#endif
