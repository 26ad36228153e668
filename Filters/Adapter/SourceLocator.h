// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SourceLocator.h
 * @brief The kernel's candidate search over a source SimplexMesh: seeds
 *        for the advancing front and for the cells it cannot reach.
 *
 * mp::BoxGridLocator's bins over the cells' boxes in space (the source's
 * own coordinates, so that the leaves of a composite Input may see it in
 * different plane frames), one over the boundary cells, built at once, and
 * one over the whole source, built on the first question that needs it
 * (see CandidateLocator.h: on meshes of the same domain, never). The
 * kernel asks with boxes in the frame it sees the mesh in; they are taken
 * back into space before the bins are asked. Ghost cells are not the
 * kernel's and never found.
 */
#ifndef MeshProjection_Adapter_SourceLocator_h
#define MeshProjection_Adapter_SourceLocator_h

#include "Adapter/SimplexMesh.h"
#include "Search/CandidateLocator.h"

#include <memory>
#include <vector>

namespace mpvtk
{
class SourceLocator : public mp::CandidateLocator
{
public:
  /// `mesh` must have its neighbours (SimplexMesh::BuildNeighbors) and
  /// outlive the locator.
  explicit SourceLocator(const SimplexMesh& mesh);
  ~SourceLocator() override;
  void FindCandidates(const double box[6], std::vector<mp::Index>& cells) override;
  void FindBoundaryCandidates(const double box[6], std::vector<mp::Index>& cells) override;
  /// The bins' answer (faces in space: a 3D mesh's own).
  bool Supports(mp::Index cell, int face) const override
  {
    return this->Bins->Supports(cell, face);
  }
  /// The bins' answer where they hold the kernel's own coordinates (a
  /// mesh in a plane z = constant, seen as it is); else no verdict.
  bool Outside(const double* q) override;
  /// Shares the bins (read only, the lazy one built once); no locks.
  std::unique_ptr<mp::CandidateLocator> NewForThread() const override;

private:
  SourceLocator(const SimplexMesh& mesh, std::unique_ptr<mp::CandidateLocator> bins, bool flat);
  /// The kernel's box (in the mesh's frame) in space.
  void ToSpace(const double box[6], double bounds[6]) const;

  const SimplexMesh& Mesh;
  std::unique_ptr<mp::CandidateLocator> Bins;
  bool Flat = false; ///< bins in (x, y) only: a mesh in z = constant
};
} // namespace mpvtk

#endif
