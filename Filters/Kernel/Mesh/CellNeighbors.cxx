// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/CellNeighbors.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace mp
{
namespace
{
template <class Id>
Index FaceNeighbors(const MeshView& mesh, std::vector<NeighborId>& neighbors)
{
  std::vector<Id> start;
  std::vector<Id> around;
  BuildPointCells(mesh, start, around);
  neighbors.assign(static_cast<size_t>(mesh.NumberOfCells) * mesh.CornersPerCell(), -1);
  const Index nonManifold = MatchFaces(
    mesh,
    [&](Index p, const auto& visit) {
      for (Id i = start[p]; i < start[p + 1]; ++i)
      {
        visit(static_cast<Index>(around[i]));
      }
    },
    neighbors.data(), 0, mesh.NumberOfCells);
  return nonManifold / 2;
}
} // namespace

Index BuildFaceNeighbors(const MeshView& mesh, std::vector<NeighborId>& neighbors)
{
  // The point-to-cell lists with 32-bit ids when they fit: half the memory.
  if (mesh.NumberOfCells * mesh.CornersPerCell() < std::numeric_limits<std::int32_t>::max())
  {
    return FaceNeighbors<std::int32_t>(mesh, neighbors);
  }
  return FaceNeighbors<Index>(mesh, neighbors);
}
void BoundaryCells(const MeshView& mesh, std::vector<Index>& cells)
{
  cells.clear();
  const int corners = mesh.CornersPerCell();
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const NeighborId* n = mesh.Neighbors + c * corners;
    bool boundary = false;
    for (int k = 0; k < corners; ++k)
    {
      boundary |= n[k] < 0;
    }
    if (boundary)
    {
      cells.push_back(c);
    }
  }
}
} // namespace mp
