// SPDX-License-Identifier: BSD-3-Clause
#include "CellNeighbors.h"

#include <algorithm>
#include <array>

namespace mp
{
Index BuildFaceNeighbors(const MeshView& mesh, std::vector<Index>& neighbors)
{
  const int corners = mesh.CornersPerCell();
  const int faceSize = corners - 1; // 2 or 3 point ids
  struct Face
  {
    std::array<Index, 3> Key; // sorted point ids, unused slots -1
    Index Cell;
    int Local;
  };
  std::vector<Face> faces;
  faces.reserve(static_cast<size_t>(mesh.NumberOfCells) * corners);
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const Index* ids = mesh.Cell(c);
    for (int k = 0; k < corners; ++k)
    {
      Face f{ { -1, -1, -1 }, c, k };
      int m = 0;
      for (int j = 0; j < corners; ++j)
      {
        if (j != k)
        {
          f.Key[m++] = ids[j];
        }
      }
      std::sort(f.Key.begin(), f.Key.begin() + faceSize);
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
    return a.Key != b.Key ? a.Key < b.Key : a.Cell < b.Cell;
  });
  neighbors.assign(faces.size(), -1);
  Index nonManifold = 0;
  for (size_t i = 0; i < faces.size();)
  {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].Key == faces[i].Key)
    {
      ++j;
    }
    if (j - i == 2)
    {
      neighbors[faces[i].Cell * corners + faces[i].Local] = faces[i + 1].Cell;
      neighbors[faces[i + 1].Cell * corners + faces[i + 1].Local] = faces[i].Cell;
    }
    else if (j - i > 2)
    {
      ++nonManifold;
    }
    i = j;
  }
  return nonManifold;
}
} // namespace mp
