// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/CellNeighbors.h"
#include "Mesh/LargeArray.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace mp
{
namespace
{
template <class Id>
Index FaceNeighbors(
  const MeshView& mesh, NeighborId* neighbors, const TaskRunner& runner, PointCells* keep)
{
  // (The cell lists are written whole by BuildPointCells' tasks: not zeroed first.)
  UninitializedLargeVector<Id> start;
  UninitializedLargeVector<Id> around;
  BuildPointCells(mesh, start, around, runner);
  const int corners = mesh.CornersPerCell();
  const Index size = mesh.NumberOfCells * corners;
  runner.Fill(neighbors, size, NeighborId(-1));
  std::atomic<bool> repeated(false);
  // MatchFacesAtPoints packs two point ids + 1 into 32 bits each.
  const bool packable = mesh.AllPoints() < (Index(1) << 32) - 1;
  const Index nonManifold =
    !packable ? 0 : runner.ForRanges(mesh.AllPoints(), [&](Index begin, Index end) {
      Index count = 0;
      switch (corners)
      {
        case 2:
          count = MatchFacesAtPoints<2>(mesh, start.data(), around.data(), neighbors, begin, end);
          break;
        case 3:
          count = MatchFacesAtPoints<3>(mesh, start.data(), around.data(), neighbors, begin, end);
          break;
        default:
          count = MatchFacesAtPoints<4>(mesh, start.data(), around.data(), neighbors, begin, end);
      }
      if (count < 0)
      {
        repeated = true;
        return Index(0);
      }
      return count;
    });
  // (For the target mass matrix's pattern: the same lists.)
  auto kept = [&] {
    if constexpr (std::is_same<Id, std::int32_t>::value)
    {
      if (keep)
      {
        keep->Start.swap(start);
        keep->Cells.swap(around);
      }
    }
  };
  if (packable && !repeated)
  {
    kept();
    return nonManifold / 2;
  }
  // A cell names a point twice (or the ids do not pack): the face
  // matcher's own rule, from the start.
  std::fill(neighbors, neighbors + size, NeighborId(-1));
  const Index matched = MatchFaces(
                          mesh,
                          [&](Index p, const auto& visit) {
                            for (Id i = start[p]; i < start[p + 1]; ++i)
                            {
                              visit(static_cast<Index>(around[i]));
                            }
                          },
                          neighbors, 0, mesh.NumberOfCells) /
    2;
  kept();
  return matched;
}
} // namespace

Index BuildFaceNeighbors(
  const MeshView& mesh, NeighborId* neighbors, const TaskRunner& runner, PointCells* keep)
{
  if (keep)
  {
    *keep = PointCells();
  }
  // The point-to-cell lists with 32-bit ids when they fit: half the memory.
  if (mesh.NumberOfCells * mesh.CornersPerCell() < std::numeric_limits<std::int32_t>::max())
  {
    return FaceNeighbors<std::int32_t>(mesh, neighbors, runner, keep);
  }
  return FaceNeighbors<Index>(mesh, neighbors, runner, keep);
}

Index BuildFaceNeighbors(const MeshView& mesh, std::vector<NeighborId>& neighbors)
{
  neighbors.resize(static_cast<size_t>(mesh.NumberOfCells) * mesh.CornersPerCell());
  return BuildFaceNeighbors(mesh, neighbors.data(), TaskRunner());
}

Index MisorientedEdges(const MeshView& mesh)
{
  if (mesh.CellDimension != 2 || !mesh.Neighbors)
  {
    return 0;
  }
  Index count = 0;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const CellCorners ids = mesh.Cell(c);
    for (int k = 0; k < 3; ++k)
    {
      const Index n = mesh.Neighbor(c, k);
      if (n <= c)
      {
        continue; // each edge once (and boundary edges not at all)
      }
      // Face k runs from corner k + 1 to corner k + 2; the neighbour should
      // run through it the other way.
      const Index from = ids[(k + 1) % 3];
      const Index to = ids[(k + 2) % 3];
      const CellCorners other = mesh.Cell(n);
      for (int j = 0; j < 3; ++j)
      {
        count += other[j] == from && other[(j + 1) % 3] == to;
      }
    }
  }
  return count;
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
