// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LinearReconstruction.h
 * @brief Cell data made linear on each cell: second-order transfer of cell
 *        averages, with or without a limiter.
 *
 * A cell field (one value per original cell: the P0 space) is first order.
 * Reconstructed, it becomes on each cell P the linear function
 *
 *     u_P(x) = u_P + g_P . (x - c_P),
 *
 * c_P the centroid of P (of the simplices it is split into, weighted by
 * their measures), so that the mean of u_P over P is the cell's value: the
 * reconstruction moves no quantity between cells, and the projection of
 * the reconstructed field conserves the integrals as the constant one does.
 * The field is then handed to the operator in the DP1 space (Space.h): the
 * values of u_P at the corners of each of P's simplices.
 *
 * The gradient g_P: weighted least squares over the cells that share a
 * point with P (its vertex neighbours N; a point is its coordinates, so
 * that blocks of a composite dataset, or parts gathered from several
 * processes, that each have their own copy of a point are neighbours
 * there), fitting u_N - u_P by
 * g . (c_N - c_P) with weights 1 / |c_N - c_P|^2. The mean of a linear
 * field over a cell is its value at the centroid, so the cell averages of
 * a linear field give its gradient exactly, whatever the cells. Vertex
 * neighbours rather than face neighbours: a cell at a corner of the mesh,
 * one next to a hole of missing values, or a split cell whose faces are
 * shared by its own simplices still has neighbours on every side (a face
 * stencil leaves a corner triangle with one), and on several processes the
 * cells around a shared point are the layer the gradients need. Where the
 * neighbours do not span the cell's directions (a cell alone, a row of
 * cells), the gradient is the least-norm one: zero in the directions they
 * leave open. On surfaces and curves the gradient lies in the cell's own
 * plane (line): the neighbours' offsets are taken in a frame of the cell.
 *
 * With the limiter (Barth and Jespersen 1989), g_P is scaled by the largest
 * phi in [0, 1] such that u_P at every corner of P stays within the least
 * and greatest of u_P and its neighbours' values. A linear function's
 * extremes on a cell are at its corners, so the reconstructed field has no
 * value outside that range anywhere on P, and the projection's averages
 * over pieces create no new extrema. Each component is limited on its own.
 *
 * Cells without a value (`Defined` zero: the NaN holes of an array) are
 * neither fitted nor used as neighbours; their corner values are 0 (their
 * pieces are left out of the operator that reads them).
 */
#ifndef MeshProjection_Kernel_LinearReconstruction_h
#define MeshProjection_Kernel_LinearReconstruction_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

#include <vector>

namespace mp
{
enum class Reconstruction
{
  Constant = 0,  ///< P0 as it is (first order)
  Limited = 1,   ///< linear, Barth-Jespersen limited (second order, no new extrema)
  Unlimited = 2  ///< linear (second order, exact for linear fields)
};

/**
 * The geometry of a reconstruction on one mesh, made once (Prepare) and
 * used for any number of fields: the cells' centroids, measures and
 * frames, the simplices of each cell and the cells around each point.
 */
class LinearReconstruction
{
public:
  /**
   * Prepares the geometry of `mesh` (kept as a view: it must outlive the
   * calls). Cells are the mesh's parents (MeshView::Parent).
   */
  void Prepare(const MeshView& mesh, const TaskRunner& runner);

  /**
   * The DP1 values (cells x corners x components, row-major; Space.h) of the
   * reconstruction of `values` (parents x components, row-major).
   * `defined`: per parent, nonzero where the values exist (null: all). With
   * Reconstruction::Constant, every corner takes its cell's value.
   */
  void Reconstruct(const double* values, int components, const char* defined, Reconstruction mode,
    const TaskRunner& runner, double* corners) const;

  /// The measure-weighted centroid of parent p (SpaceDimension coordinates used).
  const double* Centroid(Index p) const { return &this->Centroids[3 * static_cast<size_t>(p)]; }
  /// The measure of parent p (length, area or volume).
  double Measure(Index p) const { return this->Measures[static_cast<size_t>(p)]; }
  /// Parents sharing a point (by coordinates) with parent p (p itself excluded), ascending.
  void NeighborsOf(Index p, std::vector<Index>& neighbors) const;
  std::size_t MemoryBytes() const;

private:
  // The steps of Prepare.
  void GroupSimplices();
  void MeasureParents(const TaskRunner& runner);
  void FindSites();
  void GatherAroundSites(const TaskRunner& runner);
  /// One task's working arrays (Reconstruct).
  struct Scratch
  {
    std::vector<Index> Neighbors;
    std::vector<Index> Used;        ///< the neighbours with values
    std::vector<double> Weighted;   ///< M per used neighbour: w d
    std::vector<double> Gradient;   ///< 3 per component, in space
    std::vector<double> Low, High;  ///< per component: the range of the cell and its neighbours
  };
  // The steps of Reconstruct, per parent p.
  template <int M>
  void FitGradients(Index p, const double* values, int components, const char* defined, Scratch& scratch) const;
  void Limit(Index p, const double* u, int components, Scratch& scratch) const;
  void WriteCorners(Index p, const double* u, int components, const Scratch& scratch, double* corners) const;
  template <int M>
  void ReconstructRange(Index begin, Index end, const double* values, int components,
    const char* defined, Reconstruction mode, double* corners) const;

  const MeshView* Mesh = nullptr;
  LargeVector<double> Centroids; ///< 3 per parent
  LargeVector<double> Measures;
  /// Per parent: an orthonormal frame of its plane (surfaces) or line
  /// (curves), CellDimension rows of 3; empty for volume meshes.
  LargeVector<double> Frames;
  std::vector<Index> SimplexStart; ///< parent p's simplices: Simplices[SimplexStart[p] ...]
  std::vector<Index> Simplices;
  /// Per point, its site: points at the same coordinates are one site
  /// (the cells around a point are those around its site).
  std::vector<Index> Site;
  Index Sites = 0;
  std::vector<Index> AroundStart;  ///< the parents around site q: Around[AroundStart[q] ...]
  std::vector<Index> Around;
};
} // namespace mp

#endif
