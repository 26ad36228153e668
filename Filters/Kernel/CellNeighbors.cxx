// SPDX-License-Identifier: BSD-3-Clause
#include "CellNeighbors.h"

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
  const int corners = mesh.CornersPerCell();
  std::vector<Id> start;
  std::vector<Id> around;
  BuildPointCells(mesh, start, around);
  neighbors.assign(static_cast<size_t>(mesh.NumberOfCells) * corners, -1);
  Index nonManifold = 0;
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const Index* ids = mesh.Cell(c);
    for (int k = 0; k < corners; ++k)
    {
      if (neighbors[c * corners + k] >= 0)
      {
        continue; // found from the other side
      }
      // The other cells around the face's first corner holding all its corners.
      const Index first = ids[(k + 1) % corners];
      const Index second = ids[(k + 2) % corners];
      const Index third = corners == 4 ? ids[(k + 3) % corners] : second;
      Index found = -1;
      int matches = 0;
      for (Index i = start[first]; i < start[first + 1]; ++i)
      {
        const Index other = around[i];
        const Index* o = mesh.Cell(other);
        bool shares = (o[0] == second) | (o[1] == second) | (o[2] == second);
        bool shares3 = (o[0] == third) | (o[1] == third) | (o[2] == third);
        if (corners == 4)
        {
          shares |= o[3] == second;
          shares3 |= o[3] == third;
        }
        if (shares & shares3 & (other != c))
        {
          found = other;
          ++matches;
        }
      }
      if (matches == 1)
      {
        neighbors[c * corners + k] = static_cast<NeighborId>(found);
        // The same face seen from the neighbour: the corner of `found` that
        // is not on it.
        const Index* o = mesh.Cell(found);
        for (int l = 0; l < corners; ++l)
        {
          if (o[l] != first && o[l] != second && o[l] != third)
          {
            neighbors[found * corners + l] = static_cast<NeighborId>(c);
          }
        }
      }
      else if (matches > 1)
      {
        ++nonManifold;
      }
    }
  }
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
