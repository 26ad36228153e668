// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/MassMatrix.h"

#include "Mesh/CellNeighbors.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace mp
{
namespace
{
/// The CSR pattern of the point graph of a simplicial mesh (every pair of
/// points sharing a cell, and every point with itself), from the cells
/// around each point (with ids of type Id: 32 bits when they fit, half the
/// memory); rows in concurrent tasks over point ranges when a runner is
/// given, each into a block of its own, then moved into place.
template <class Id>
void PointGraph(const MeshView& mesh, const TaskRunner& runner, LargeVector<Index>& start,
  LargeVector<Column>& columns)
{
  LargeVector<Id> cellStart;
  LargeVector<Id> cells;
  BuildPointCells(mesh, cellStart, cells, runner);
  const int n = mesh.CornersPerCell();
  const Index points = mesh.NumberOfPoints;
  const int tasks = runner.TasksFor(points, 4096);
  start.assign(static_cast<size_t>(points) + 1, 0);
  // One task writes its rows straight into `columns`.
  std::vector<LargeVector<Column>> blocks(static_cast<size_t>(tasks > 1 ? tasks : 0));
  auto rows = [&](int k) {
    LargeVector<Column>& block = tasks > 1 ? blocks[k] : columns;
    block.clear();
    block.reserve(static_cast<size_t>(points / tasks + 1) * (n == 3 ? 7 : 15));
    std::vector<Column> row;
    // Short rows are gathered in a buffer on the stack and insertion-sorted:
    // the point itself and the other corners of its cells (in 2D about 13
    // entries before duplicates go). Longer ones (most points in 3D: about
    // 70) take the vector and std::sort below.
    constexpr Index Small = 64;
    Column small[Small];
    for (Index p = RangeBegin(points, k, tasks); p < RangeBegin(points, k + 1, tasks); ++p)
    {
      if (1 + (n - 1) * (cellStart[p + 1] - cellStart[p]) <= Small)
      {
        Index size = 0;
        small[size++] = static_cast<Column>(p);
        for (Index i = cellStart[p]; i < cellStart[p + 1]; ++i)
        {
          const Index* ids = mesh.Cell(cells[i]);
          for (int c = 0; c < n; ++c)
          {
            if (ids[c] != p)
            {
              small[size++] = static_cast<Column>(ids[c]);
            }
          }
        }
        for (Index i = 1; i < size; ++i)
        {
          const Column v = small[i];
          Index j = i;
          for (; j > 0 && small[j - 1] > v; --j)
          {
            small[j] = small[j - 1];
          }
          small[j] = v;
        }
        const Index unique = std::unique(small, small + size) - small;
        block.insert(block.end(), small, small + unique);
        start[p + 1] = unique;
        continue;
      }
      row.assign(1, static_cast<Column>(p));
      for (Index i = cellStart[p]; i < cellStart[p + 1]; ++i)
      {
        const Index* ids = mesh.Cell(cells[i]);
        for (int c = 0; c < n; ++c)
        {
          row.push_back(static_cast<Column>(ids[c]));
        }
      }
      // Rows are short (7 entries in 2D, 15 in 3D on average): insertion
      // sort, unless a point has very many cells around it.
      if (row.size() > 64)
      {
        std::sort(row.begin(), row.end());
      }
      else
      {
        for (size_t i = 1; i < row.size(); ++i)
        {
          const Column v = row[i];
          size_t j = i;
          for (; j > 0 && row[j - 1] > v; --j)
          {
            row[j] = row[j - 1];
          }
          row[j] = v;
        }
      }
      const Index size = std::unique(row.begin(), row.end()) - row.begin();
      block.insert(block.end(), row.begin(), row.begin() + size);
      start[p + 1] = size;
    }
  };
  runner.RunAll(tasks, rows);
  for (Index p = 0; p < points; ++p)
  {
    start[p + 1] += start[p];
  }
  if (tasks > 1)
  {
    columns.resize(static_cast<size_t>(start[points]));
    runner.RunAll(tasks, [&](int k) {
      std::copy(blocks[k].begin(), blocks[k].end(), columns.begin() + start[RangeBegin(points, k, tasks)]);
      LargeVector<Column>().swap(blocks[k]);
    });
  }
}

void PointGraph(const MeshView& mesh, const TaskRunner& runner, LargeVector<Index>& start,
  LargeVector<Column>& columns)
{
  if (mesh.NumberOfCells * mesh.CornersPerCell() < std::numeric_limits<std::int32_t>::max())
  {
    PointGraph<std::int32_t>(mesh, runner, start, columns);
  }
  else
  {
    PointGraph<Index>(mesh, runner, start, columns);
  }
}

} // namespace

void MassPattern(SpaceType space, const MeshView& mesh, const TaskRunner& runner, CsrMatrix& matrix)
{
  matrix = CsrMatrix();
  const Index n = SpaceSize(space, mesh);
  matrix.Rows = matrix.Columns = n;
  if (space == SpaceType::P1)
  {
    PointGraph(mesh, runner, matrix.RowStart, matrix.ColumnIndex);
  }
  else
  {
    // P0: the functions do not overlap; the matrix is diagonal.
    matrix.RowStart.resize(static_cast<size_t>(n) + 1);
    matrix.ColumnIndex.resize(static_cast<size_t>(n));
    for (Index i = 0; i <= n; ++i)
    {
      matrix.RowStart[i] = i;
    }
    for (Index i = 0; i < n; ++i)
    {
      matrix.ColumnIndex[i] = static_cast<Column>(i);
    }
  }
  matrix.Values.assign(matrix.ColumnIndex.size(), 0.0);
}
} // namespace mp
