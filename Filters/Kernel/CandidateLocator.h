// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CandidateLocator.h
 * @brief Where the advancing front gets its starting candidates.
 *
 * The front needs a search only to start (and to restart on parts of the
 * target it cannot reach through neighbours): "which source cells may meet
 * this box?". The VTK filter answers with vtkStaticCellLocator; the kernel
 * ships BoxGridLocator, a uniform bin grid over the source cells' bounding
 * boxes, for callers without VTK.
 */
#ifndef MeshProjection_Kernel_CandidateLocator_h
#define MeshProjection_Kernel_CandidateLocator_h

#include "MeshView.h"

#include <memory>
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
   * A locator over the same cells for another thread: concurrent tasks each
   * query their own. It may share the (read-only) index with this one.
   */
  virtual std::unique_ptr<CandidateLocator> NewForThread() const = 0;
};

/// Uniform grid of bins, about 2^d cells per bin, over a mesh's cell boxes.
class BoxGridLocator : public CandidateLocator
{
public:
  explicit BoxGridLocator(const MeshView& mesh);
  void FindCandidates(const double box[6], std::vector<Index>& cells) override;
  std::unique_ptr<CandidateLocator> NewForThread() const override;

private:
  struct Bins
  {
    double Origin[3] = { 0, 0, 0 };
    double Spacing[3] = { 1, 1, 1 };
    int Divisions[3] = { 1, 1, 1 };
    std::vector<Index> BinStart; ///< CSR offsets into BinCells
    std::vector<Index> BinCells;
    void Range(const double box[6], int lo[3], int hi[3]) const;
  };
  BoxGridLocator(std::shared_ptr<const Bins> bins, Index cells);

  std::shared_ptr<const Bins> Grid; ///< shared by the locators of all threads
  std::vector<Index> Stamp;         ///< de-duplicates cells spanning several bins
  Index Query = 0;
};
} // namespace mp

#endif
