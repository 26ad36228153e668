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
/// Per Source cell (parent), whether a NaN group's arrays have values there.
std::vector<char> DefinedCells(const mp::MeshView& source, const NaNGroup& group)
{
  std::vector<char> defined(static_cast<size_t>(source.Parents()), 1);
  for (mp::Index c = 0; c < source.NumberOfCells; ++c)
  {
    if (group.Excluded[static_cast<size_t>(c)])
    {
      defined[static_cast<size_t>(source.ParentOf(c))] = 0;
    }
  }
  return defined;
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
  const auto mode = static_cast<mp::Reconstruction>(settings.CellDataReconstruction);
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
  const size_t corners = static_cast<size_t>(source.NumberOfCells) * source.CornersPerCell();
  cells.Corners.resize(corners * cells.Components);
  if (cells.Components > 0)
  {
    reconstruction.Reconstruct(
      cells.Values.data(), cells.Components, nullptr, mode, runner, cells.Corners.data());
  }
  cells.Reconstructed = true;
  cells.Key += "/reconstruction " + std::to_string(settings.CellDataReconstruction);
  for (NaNGroup& group : cells.Groups)
  {
    const std::vector<char> defined = DefinedCells(source, group);
    group.Corners.resize(corners * group.Components);
    reconstruction.Reconstruct(
      group.Values.data(), group.Components, defined.data(), mode, runner, group.Corners.data());
    group.Reconstructed = true;
  }
  if (!settings.CacheOperator)
  {
    kept = KeptReconstruction();
  }
}
} // namespace mpvtk
