// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file NumberingQuality.h
 * @brief Whether a mesh's numbering follows space, for the points and for
 *        the cells, from a sample: the test that decides whether the
 *        filter renumbers a mesh (SpatialOrder.h) before projecting.
 *
 * The projection walks the mesh through space (SpatialOrder.h): its front
 * steps from a cell to the cells across its faces, the assembly sums a
 * cell into its points' rows. Memory follows when both numberings do: a
 * cell's points have nearby ids, and so do the cells across its faces.
 * Either alone is not enough. Meshers that number points along a grid or a
 * sweep but list cells as they made them (Qhull, and so scipy.spatial's
 * Delaunay, lists a point's new cells when it inserts the point, the
 * points in no spatial order) give cells whose own point ids are close
 * while about a third of their face neighbours are anywhere in the list;
 * meshes whose cells are listed by kind or block (all lower triangles of
 * a grid, then all upper ones) put every pair of face neighbours half the
 * list apart. So two numbers are measured, with distances in units of
 * n^((d-1)/d) for n points or cells of dimension d, the id distance across
 * one layer of a sweep (a row in 2D, a plane in 3D):
 *  - PointSpread: the median, over the sampled cells, of the largest
 *    distance between the ids of a cell's points: about 1 for a mesh
 *    numbered along a sweep or a Z-order curve, growing as n^(1/d) when the
 *    points are numbered without order;
 *  - FarNeighbours: the fraction of the sampled cells' face neighbours more
 *    than FarDistance layers away in the list. Sweeps, and meshers that
 *    sweep bands a few cells wide, put neighbours at most a few layers
 *    apart: none is that far. A Z-order curve's jumps between quadrants
 *    leave 1-2% that far; Qhull's order 6-20% of a 3D mesh's neighbours
 *    (10^4 to 10^5 cells) and a third of a 2D mesh's; shuffled or block-listed
 *    meshes nearly all. A fraction, not a percentile of the distances:
 *    what costs is how many steps leave the cache, however far they go,
 *    and a band's few-layer steps do not.
 *
 * The face neighbours of the sampled cells are found without the mesh's
 * point -> cell map (the filter builds it only after this decision): the
 * sampled cells' points are marked in a bit per point, and one pass over
 * the connectivity (in `runner`'s tasks) tests each cell that uses a marked
 * point against the sampled cells that use that point, with the corners it
 * has just read (no cell is read at random: the cells around a point of a
 * mesh numbered without order lie far apart). Cost: that pass, np / 8
 * bytes for the marks, O(samples) around it, small beside any projection
 * on the mesh.
 */
#ifndef MeshProjection_Kernel_NumberingQuality_h
#define MeshProjection_Kernel_NumberingQuality_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

namespace mp
{
/// How far a mesh's numbering is from following space (see the file's comment).
struct NumberingQuality
{
  double PointSpread = 0.0;   ///< median point id spread of a cell / np^((d-1)/d)
  double FarNeighbours = 0.0; ///< fraction of face neighbours more than FarDistance layers apart

  /// In layers (n^((d-1)/d) ids): beyond any sweep's or band's neighbours.
  static constexpr double FarDistance = 8.0;
  /// The largest PointSpread that follows space (a sweep's is about 1).
  static constexpr double PointSpreadLimit = 4.0;
  /// The largest FarNeighbours that follows space (a Z-order curve's is at
  /// most 0.02, a Qhull-ordered mesh's 0.06 and more).
  static constexpr double FarNeighboursLimit = 0.04;
  /// Whether both numberings follow space.
  bool Tidy() const
  {
    return this->PointSpread <= PointSpreadLimit && this->FarNeighbours <= FarNeighboursLimit;
  }
};

/**
 * `mesh`'s NumberingQuality, from up to `samples` cells evenly spread over
 * its ids (meshes of fewer than 2 cells or points: 0, 0). Reads the
 * connectivity once, in `runner`'s tasks; the result does not depend on
 * their number.
 */
NumberingQuality MeasureNumbering(
  const MeshView& mesh, const TaskRunner& runner = TaskRunner(), Index samples = 1024);

} // namespace mp

#endif
