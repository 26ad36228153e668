// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SourceSide.h
 * @brief What an execution makes of Source once, for every leaf of Input:
 *        Source as one dataset (this process's part and the cells it needs
 *        from others), wrapped as the kernel's mesh, its fingerprint, its
 *        fields, and the search structures (neighbours, locator) built by
 *        the first leaf that searches.
 */
#ifndef MeshProjection_Projection_SourceSide_h
#define MeshProjection_Projection_SourceSide_h

#include "Projection/SourceFields.h"
#include "Adapter/SimplexMesh.h"

#include "Search/CandidateLocator.h"

#include "vtkSmartPointer.h"

#include <cstdint>
#include <memory>

class vtkDataArraySelection;
class vtkDataObject;
class vtkDataSet;

namespace mpvtk
{
struct Settings;
struct Statistics;
class StageClock;
class Messages;
class Parts;
struct Verdict;

struct SourceSide
{
  vtkSmartPointer<vtkDataSet> Data;
  bool Composite = false; ///< Source came as a composite dataset (appended)
  SimplexMesh Mesh;
  std::uint64_t Print = 0;  ///< Fingerprint of Mesh
  GatheredFields Fields[2]; ///< 0: point arrays (P1), 1: cell arrays (P0)
  bool TimeVarying = false; ///< an input advertises several time steps
  /// Neighbours and locator, built by the first leaf that searches.
  bool SearchReady = false;
  std::unique_ptr<mp::CandidateLocator> Locator;

  /// Whether any field goes anywhere (else only masks and coverage are made).
  bool AnyTransfer(const Settings& settings) const;
};

/**
 * Stage 1: Source as one mesh (a composite appended; on several processes
 * gathered), wrapped and checked, in its own plane when planar; its
 * fingerprint. Fills `side`; a failure is agreed by every process. On
 * several processes it first lists the labels of this process's piece of
 * the label arrays `selections` (points, cells) enable (ListPieceLabels).
 */
Verdict PrepareSourceMesh(vtkDataObject* sourceObject, vtkDataObject* input,
  const Settings& settings, vtkDataArraySelection* const selections[2], Parts& parts,
  Messages& messages, Statistics& stats, SourceSide& side);
} // namespace mpvtk

#endif
