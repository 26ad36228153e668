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
 * list apart. So two numbers are measured, both in units of n^((d-1)/d)
 * for n points or cells of dimension d, the id distance across one layer
 * of a sweep (a row in 2D, a plane in 3D), which is about 1 for a mesh
 * numbered along a sweep or a Z-order curve and grows as n^(1/d) when the
 * numbering does not follow space:
 *  - PointSpread: the median, over the sampled cells, of the largest
 *    distance between the ids of a cell's points;
 *  - NeighbourDistance: the 90th percentile, over the face neighbours of
 *    the sampled cells, of the distance between their ids. A percentile,
 *    not the median: most of a Qhull mesh's neighbours are made together
 *    and close, the third that are not is what costs; a Z-order curve's
 *    few long jumps (between quadrants) stay below it.
 *
 * The face neighbours of the sampled cells are found without the mesh's
 * point -> cell map (the filter builds it only after this decision): the
 * sampled cells' points are marked in a bit per point, and one pass over
 * the connectivity (in `runner`'s tasks) keeps the cells that use a marked
 * point. Cost: that pass and np / 8 bytes for the marks, O(samples) after
 * it, small beside any projection on the mesh.
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
  double PointSpread = 0.0;       ///< median point id spread of a cell / np^((d-1)/d)
  double NeighbourDistance = 0.0; ///< 90th percentile of face neighbours' id distance / n^((d-1)/d)

  /**
   * The largest value of either measure that still counts as following
   * space: a sweep's is about 1 (1.4 for a 2D grid's triangles, 1.8 for a
   * 3D grid's six tetrahedra per cube), a Z-order curve's well below 1; a
   * Qhull-ordered Delaunay mesh's cells give 5 and more, a shuffled or
   * block-interleaved mesh n^(1/d) times more.
   */
  static constexpr double TidyLimit = 3.0;
  /// Whether both numberings follow space.
  bool Tidy() const { return this->PointSpread <= TidyLimit && this->NeighbourDistance <= TidyLimit; }
};

/**
 * `mesh`'s NumberingQuality, from up to `samples` cells evenly spread over
 * its ids (meshes of fewer than 2 cells or points: 0, 0). Reads the
 * connectivity once, in `runner`'s tasks; the result does not depend on
 * their number.
 */
NumberingQuality MeasureNumbering(const MeshView& mesh, const TaskRunner& runner = TaskRunner(),
  Index samples = 1024);

} // namespace mp

#endif
