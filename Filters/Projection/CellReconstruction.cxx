// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/CellReconstruction.h"

#include "Adapter/SimplexMesh.h"
#include "Adapter/Threads.h"
#include "Projection/OperatorCache.h"
#include "Projection/Settings.h"
#include "Projection/SourceFields.h"

#include "Transfer/LinearReconstruction.h"

#include <string>
#include <vector>

namespace mpvtk
{
namespace
{
/// `block`'s values as DP1 functions (`defined`: per Source cell, or null for all).
void Reconstruct(const mp::LinearReconstruction& reconstruction, const mp::MeshView& source,
  const char* defined, mp::Reconstruction mode, FieldBlock& block)
{
  block.Corners.resize(
    static_cast<size_t>(source.NumberOfCells) * source.CornersPerCell() * block.Components);
  if (block.Components > 0)
  {
    reconstruction.Reconstruct(
      block.Values.data(), block.Components, defined, mode, SMPTaskRunner(), block.Corners.data());
  }
  block.Reconstructed = true;
}
} // namespace

void ReconstructCellFields(const Settings& settings, SimplexMesh& sourceMesh,
  std::uint64_t sourcePrint, GatheredFields& cells, KeptReconstruction& kept)
{
  const mp::MeshView& source = sourceMesh.View();
  cells.Reconstructed = false;
  if (!settings.ReconstructsCellData() || (cells.Components == 0 && cells.Groups.empty()))
  {
    kept = KeptReconstruction(); // (held for nothing)
    return;
  }
  const mp::Reconstruction mode = settings.CellDataReconstruction;
  const mp::TaskRunner runner = SMPTaskRunner();
  // The geometry: kept from the last execution while Source is the same.
  if (kept.Geometry && kept.SourcePrint == sourcePrint)
  {
    kept.Geometry->Rebind(source);
  }
  else
  {
    if (!source.Neighbors)
    {
      // The Source's face neighbours, which the search would build later
      // (LeafSearch::Prepare uses them then).
      sourceMesh.BuildNeighbors();
    }
    kept.Geometry.reset(new mp::LinearReconstruction);
    kept.Geometry->Prepare(source, runner);
    kept.SourcePrint = sourcePrint;
  }
  const mp::LinearReconstruction& reconstruction = *kept.Geometry;
  Reconstruct(reconstruction, source, nullptr, mode, cells);
  cells.Key +=
    "/reconstruction " + std::to_string(static_cast<int>(settings.CellDataReconstruction));
  for (NaNGroup& group : cells.Groups)
  {
    std::vector<char> defined = LeftOutCells(source, group);
    for (char& d : defined)
    {
      d = !d;
    }
    Reconstruct(reconstruction, source, defined.data(), mode, group);
  }
  kept.Store(settings);
}
} // namespace mpvtk
