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
 * The gradient g_P: weighted least squares over P's face neighbours N
 * (the cells across the faces of its simplices that are not its own),
 * fitting u_N - u_P by g . (c_N - c_P) with weights 1 / |c_N - c_P|^2. The
 * mean of a linear field over a cell is its value at the centroid, so the
 * cell averages of a linear field give its gradient exactly, whatever the
 * cells. Where the face neighbours with values do not span the cell's
 * directions well (a corner of the mesh, a cell next to a hole of missing
 * values, a thin strip), the fit takes every cell that shares a point with
 * P instead, and where those do not either (a corner cell with a single
 * neighbour), the cells around those too; where even they leave a
 * direction open (a cell alone, a row of cells), the least-norm gradient:
 * zero in that direction. On surfaces
 * and curves the gradient lies in the cell's own plane (line): the
 * neighbours' offsets are taken in a frame of the cell.
 *
 * With the limiter (Barth and Jespersen 1989), g_P is scaled by the
 * largest phi in [0, 1] such that u_P at every corner of P stays within the
 * least and greatest value of the cells around P's corners (P and all the
 * cells that share a point with it). A linear function's extremes on a
 * cell are at its corners, so u_P nowhere leaves the range of P and its
 * neighbours, and the projection's averages over pieces create no new
 * extrema in cells. Bounds from all the cells around P rather than from its
 * face neighbours alone leave a linear field alone inside the mesh (each
 * corner lies among the centroids around P): the limiter clips at jumps,
 * at extrema and in some cells along the mesh's boundary, not everywhere.
 * Each component is limited on its own.
 *
 * Cells of zero measure (no part of any integral) are no one's neighbours.
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
  Constant = 0, ///< P0 as it is (first order)
  Limited = 1,  ///< linear, Barth-Jespersen limited (second order, no new extrema)
  Unlimited = 2 ///< linear (second order, exact for linear fields)
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
   * calls). Cells are the mesh's parents (MeshView::Parent). Points at the
   * same coordinates are one point (a mesh made of parts that each have
   * their own copies of the points between them: a composite dataset's
   * blocks, the parts of several processes, unmerged points). The mesh's
   * face neighbours (MeshView::Neighbors), when it has them, serve.
   */
  void Prepare(const MeshView& mesh, const TaskRunner& runner);
  /**
   * Serves `mesh`, a view of the same mesh Prepare was given (the same
   * points and cells, in the same order: a later execution's), without
   * preparing again.
   */
  void Rebind(const MeshView& mesh) { this->Mesh = &mesh; }
  /// Whether Prepare found points at the same coordinates and joined them.
  bool JoinsCopies() const { return this->JoinCopies; }

  /**
   * The DP1 values (cells x corners x components, row-major; Space.h) of the
   * reconstruction of `values` (parents x components, row-major).
   * `defined`: per parent, nonzero where the values exist (null: all). With
   * Reconstruction::Constant, every corner takes its cell's value.
   */
  void Reconstruct(const double* values, int components, const char* defined, Reconstruction mode,
    const TaskRunner& runner, double* corners) const;

  /// The measure-weighted centroid of parent p (SpaceDimension coordinates used).
  const double* Centroid(Index p) const { return this->CentroidAt(this->SlotOf[p]); }
  /// Parents sharing a point (a site) with parent p (p itself excluded), ascending.
  void NeighborsOf(Index p, std::vector<Index>& neighbors) const;
  std::size_t MemoryBytes() const;

private:
  const double* CentroidAt(Index slot) const
  {
    return &this->Centroids[3 * static_cast<size_t>(slot)];
  }
  /// The slots sharing a point with slot p (p excluded), ascending.
  void SlotNeighbors(Index p, std::vector<Index>& neighbors) const;
  // The steps of Prepare.
  void GroupSimplices();
  void MeasureParents(const TaskRunner& runner);
  void FindSites(const NeighborId* across);
  void MatchFacesOnSites(const TaskRunner& runner, std::vector<NeighborId>& across) const;
  void GatherAroundSites(const TaskRunner& runner);
  void FindFaceNeighbors(const NeighborId* across, const TaskRunner& runner);
  /// One task's working arrays (Reconstruct).
  struct Scratch
  {
    std::vector<Index> Neighbors;
    std::vector<Index> Used;      ///< the neighbours with values
    std::vector<double> Weighted; ///< M per used neighbour: w d
    std::vector<double> Gradient; ///< 3 per component, in space
    double Normal[9];             ///< the normal matrix A = sum w d d^T (M x M, column-major)
  };
  // The steps of Reconstruct, per parent p.
  /// The neighbours of p with values (ring 0: across its faces; 1: all the
  /// cells around it; 2: and the cells around those), with their weighted
  /// offsets and normal matrix, in `scratch`.
  template <int M>
  void Stencil(Index p, const char* defined, int ring, Scratch& scratch) const;
  template <int M>
  void FitGradients(
    Index p, const double* values, int components, const char* defined, Scratch& scratch) const;
  void Limit(
    Index p, const double* u, int components, const double* ranges, Scratch& scratch) const;
  /// Per site and component, the least and greatest value of the cells around it with values.
  std::vector<double> SiteRanges(
    const double* values, int components, const char* defined, const TaskRunner& runner) const;
  /// What Reconstruct was given (and the site ranges of the limiter).
  struct Input
  {
    const double* Values;
    int Components;
    const char* Defined;
    Reconstruction Mode;
    const double* Ranges;
  };
  void WriteCorners(
    Index p, const double* u, int components, const Scratch& scratch, double* corners) const;
  template <int M>
  void ReconstructRange(Index begin, Index end, const Input& in, double* corners) const;

  const MeshView* Mesh = nullptr;
  LargeVector<double> Centroids; ///< 3 per parent
  std::vector<char> Flat;        ///< per slot: no measure (no neighbour of any cell)
  /// Per parent: an orthonormal frame of its plane (surfaces) or line
  /// (curves), CellDimension rows of 3; empty for volume meshes.
  LargeVector<double> Frames;
  /// Parents are kept in slots, in the order of their first simplex; the
  /// arrays below and the private functions' `p` are by slot.
  std::vector<Index> SlotOf;
  std::vector<Index> ParentOfSlot;
  bool SlotsAreParents = true;
  std::vector<Index> SimplexStart; ///< slot p's simplices: Simplices[SimplexStart[p] ...]
  std::vector<Index> Simplices;
  bool JoinCopies = false;
  /// Per point, its site: itself, or for a copy of a point (the same
  /// coordinates) the first of them (the cells around a point are those
  /// around its site; sites not used have none).
  std::vector<Index> Site;
  Index Sites = 0;
  std::vector<Index> AroundStart; ///< the parents around site q: Around[AroundStart[q] ...]
  std::vector<Index> Around;
  std::vector<Index> FaceStart; ///< parent p's face neighbours: Faces[FaceStart[p] ...]
  std::vector<Index> Faces;
};
} // namespace mp

#endif
