// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CandidateLocator.h
 * @brief Where the advancing front gets its starting candidates.
 *
 * The front needs a search only to start (and to restart on parts of the
 * target it cannot reach through neighbours): "which source cells may meet
 * this box?". Two questions, in the order the front asks them (PairSearch.h):
 * first only among the source cells at the boundary of the source mesh, a
 * small set (about n^(1/2) of n triangles, n^(2/3) of n tetrahedra) that
 * settles every target cell whose walk met that boundary; then, rarely,
 * among all source cells. Implementations index the boundary cells at once
 * and all cells only when first asked, so that the usual projection (a
 * front started by a walk, re-seeded at the boundary) never pays for an
 * index over the whole source. The kernel ships BoxGridLocator, uniform bin
 * grids over the cells' bounding boxes; the VTK filter uses it too, over
 * the source's points in space (mpvtk::SourceLocator). (VTK 9.2's
 * vtkStaticCellLocator, used before, de-duplicates each answer with
 * vtkIdList::InsertUniqueId, quadratic in the cells found: a visible part
 * of a 3D projection went there.)
 */
#ifndef MeshProjection_Kernel_CandidateLocator_h
#define MeshProjection_Kernel_CandidateLocator_h

#include "Mesh/MeshView.h"

#include <memory>
#include <mutex>
#include <vector>

namespace mp
{
class CandidateLocator
{
public:
  virtual ~CandidateLocator() = default;
  /**
   * Replaces `cells` with the source cells whose bounding boxes may overlap
   * `box` (xmin, xmax, ymin, ymax, zmin, zmax). Extra candidates are
   * harmless; a missing one loses intersections.
   */
  virtual void FindCandidates(const double box[6], std::vector<Index>& cells) = 0;

  /**
   * Replaces `cells` with at least the boundary cells of the source (cells
   * with a face without neighbour, see BoundaryCells()) whose bounding boxes
   * may overlap `box`. Other cells are harmless; the default answers with
   * FindCandidates().
   */
  virtual void FindBoundaryCandidates(const double box[6], std::vector<Index>& cells)
  {
    this->FindCandidates(box, cells);
  }

  /**
   * True when face `face` (mesh-local) of source cell `cell`, a face
   * without neighbour, supports the source: the whole source lies on the
   * cell's side of its plane (SupportingFaces.h). A target cell whose inner
   * front met the boundary only at such faces needs no boundary query.
   * False says nothing (the default).
   */
  virtual bool Supports(Index cell, int face) const
  {
    (void)cell;
    (void)face;
    return false;
  }

  /**
   * True when point `q` (x, y) of a plane source of triangles lies in no
   * source cell: proven, with exact predicates, by the winding number of
   * the boundary faces (faces without neighbour) about q, each face turned
   * as its cell (by the sign of the cell's area), counted where a ray from
   * q toward +x crosses them. On a source whose neighbours lie on opposite
   * sides of their shared faces that number is how many source cells hold
   * q, so layers that overlap (unmerged overset blocks) count twice where
   * they do, not zero as a parity would; on a source with a fold or a cell
   * of zero area it is not, and the answer is false. Only for a point on
   * no boundary face (the caller knows it: a corner of a target cell that
   * meets no boundary cell). A target cell meeting no boundary cell lies
   * wholly inside the source or wholly outside; one corner outside settles
   * it without a query among all cells. False says nothing (the default;
   * other meshes; a ray along a boundary face).
   */
  virtual bool Outside(const double* q)
  {
    (void)q;
    return false;
  }

  /**
   * A locator over the same cells for another thread: concurrent tasks each
   * query their own. It may share the (read-only) index with this one.
   */
  virtual std::unique_ptr<CandidateLocator> NewForThread() const = 0;
};

/**
 * Uniform grids of bins (about 2^d cells per bin) over the cells' bounding
 * boxes: one over the boundary cells, built at once from the mesh's
 * neighbours (over all cells when the mesh has none), and one over all
 * cells, built on the first FindCandidates() by whichever thread asks first.
 * The mesh's arrays must outlive the locator.
 */
class BoxGridLocator : public CandidateLocator
{
public:
  explicit BoxGridLocator(const MeshView& mesh);
  void FindCandidates(const double box[6], std::vector<Index>& cells) override;
  void FindBoundaryCandidates(const double box[6], std::vector<Index>& cells) override;
  bool Supports(Index cell, int face) const override;
  bool Outside(const double* q) override;
  std::unique_ptr<CandidateLocator> NewForThread() const override;

private:
  struct Bins
  {
    double Origin[3] = { 0, 0, 0 };
    double Spacing[3] = { 1, 1, 1 };
    int Divisions[3] = { 1, 1, 1 };
    std::vector<Index> BinStart; ///< CSR offsets into BinCells
    std::vector<Index> BinCells; ///< positions in the binned cells (= cell ids for all cells)
    /// For a subset: its cells, and their boxes (6 per cell), computed once
    /// instead of at every query. Empty for all cells (the memory of a box
    /// per cell of the mesh; that grid is built only without neighbours).
    std::vector<Index> Cells;
    std::vector<double> Boxes;
    /// How a cell's box is computed (for the mesh's kind of cells).
    void (*CellBox)(const MeshView& mesh, Index cell, double box[6]) = nullptr;
    /// Bins over `cells` of `mesh` (every cell when `cells` is null).
    Bins(const MeshView& mesh, const std::vector<Index>* cells);
    /// The box of the binned cell at `position`: stored, or computed into `scratch`.
    const double* BoxOf(const MeshView& mesh, Index position, double scratch[6]) const;
    /// The mesh's id of the binned cell at `position`.
    Index CellOf(Index position) const
    {
      return this->Cells.empty() ? position : this->Cells[position];
    }
    void Range(const double box[6], int lo[3], int hi[3]) const;
  };
  /// What the locators of all threads share.
  struct Shared
  {
    MeshView Mesh;
    std::unique_ptr<const Bins> Boundary;
    /// Of each cell: bit k set when face k is a boundary face supporting
    /// the mesh (SupportingFaces.h; tetrahedra in space only, else empty),
    /// set once, under SupportingBuilt, on the first Supports().
    std::once_flag SupportingBuilt;
    std::vector<unsigned char> Supporting;
    std::once_flag AllBuilt;
    std::unique_ptr<const Bins> All; ///< set once, under AllBuilt
    /// Whether the boundary faces' winding number counts the cells holding
    /// a point (plane triangles, no fold, no cell of zero area), set once,
    /// under CountsBuilt, on the first Outside() that needs it.
    std::once_flag CountsBuilt;
    bool WindingCounts = false;
  };
  explicit BoxGridLocator(std::shared_ptr<Shared> shared);
  void Collect(const Bins& bins, const double box[6], std::vector<Index>& cells);

  std::shared_ptr<Shared> Grids;
  std::vector<Index> RayCells; ///< Outside()'s boundary cells in the ray's row of bins
};
} // namespace mp

#endif
