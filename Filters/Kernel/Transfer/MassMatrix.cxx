// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/MassMatrix.h"

#include "Mesh/CellNeighbors.h"
#include "Mesh/SortEight.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace mp
{
namespace
{
/// The CSR pattern of the point graph of a simplicial mesh (every pair of
/// points sharing a cell, and every point with itself), from the cells
/// around each point (with ids of type Id: 32 bits when they fit, half the
/// memory; those the neighbours' construction kept, mesh.Around, when
/// there are, emptied once read); rows in concurrent tasks over point
/// ranges when a runner is given, each into a block of its own, then moved
/// into place.
template <class Id>
void PointGraph(const MeshView& mesh, const TaskRunner& runner, LargeVector<Index>& start,
  UninitializedLargeVector<Column>& columns)
{
  UninitializedLargeVector<Id> cellStart;
  UninitializedLargeVector<Id> cells;
  if constexpr (std::is_same<Id, std::int32_t>::value)
  {
    if (mesh.Around && mesh.Around->Fit(mesh))
    {
      cellStart.swap(mesh.Around->Start);
      cells.swap(mesh.Around->Cells);
    }
  }
  if (cellStart.empty())
  {
    BuildPointCells(mesh, cellStart, cells, runner);
  }
  const int n = mesh.CornersPerCell();
  const Index points = mesh.NumberOfPoints;
  // Each task marks candidates in an array over all points (`seen` below):
  // at most as many tasks as uses of a point by cells, so that the marks
  // take no more memory than the point-cell lists.
  const Index uses = points > 0 ? mesh.NumberOfCells * n / points : 0;
  const int tasks = static_cast<int>(
    std::min<Index>(runner.TasksFor(points, 4096), std::max<Index>(1, uses)));
  start.assign(static_cast<size_t>(points) + 1, 0);
  // One task writes its rows straight into `columns`.
  std::vector<UninitializedLargeVector<Column>> blocks(static_cast<size_t>(tasks > 1 ? tasks : 0));
  auto rows = [&](int k) {
    UninitializedLargeVector<Column>& block = tasks > 1 ? blocks[k] : columns;
    block.clear();
    block.reserve(static_cast<size_t>(points / tasks + 1) * (n == 3 ? 7 : 15));
    // A row is the point itself and the other corners of its cells (in 2D
    // about 12 candidates for 7 columns, in 3D about 70 for 15). Each
    // candidate is written and kept unless seen[q] already names this row:
    // no branch, no sort of the repeats. The distinct ones are then sorted:
    // up to 8 by a fixed network of branch-free exchanges, else by
    // insertion or std::sort.
    LargeVector<Column> seen(static_cast<size_t>(points), Column(-1));
    std::vector<Column> row(16);
    for (Index p = RangeBegin(points, k, tasks); p < RangeBegin(points, k + 1, tasks); ++p)
    {
      const Index candidates = 1 + n * (cellStart[p + 1] - cellStart[p]);
      if (static_cast<Index>(row.size()) < std::max<Index>(candidates, 8))
      {
        row.resize(static_cast<size_t>(std::max<Index>(candidates, 8)));
      }
      Column* r = row.data();
      const auto self = static_cast<Column>(p);
      r[0] = self;
      seen[p] = self;
      Index size = 1;
      for (Index i = cellStart[p]; i < cellStart[p + 1]; ++i)
      {
        const Index* ids = mesh.Cell(cells[i]);
        for (int c = 0; c < n; ++c)
        {
          const auto q = static_cast<Column>(ids[c]);
          r[size] = q;
          size += seen[q] != self;
          seen[q] = self;
        }
      }
      if (size <= 8)
      {
        for (Index i = size; i < 8; ++i)
        {
          r[i] = std::numeric_limits<Column>::max();
        }
        SortEight(r);
      }
      else if (size <= 32)
      {
        for (Index i = 1; i < size; ++i)
        {
          const Column v = r[i];
          Index j = i;
          for (; j > 0 && r[j - 1] > v; --j)
          {
            r[j] = r[j - 1];
          }
          r[j] = v;
        }
      }
      else
      {
        std::sort(r, r + size);
      }
      block.insert(block.end(), r, r + size);
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
      UninitializedLargeVector<Column>().swap(blocks[k]);
    });
  }
}

void PointGraph(const MeshView& mesh, const TaskRunner& runner, LargeVector<Index>& start,
  UninitializedLargeVector<Column>& columns)
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
  // Zeros written by concurrent tasks (each the first to touch its pages).
  matrix.Values.resize(matrix.ColumnIndex.size());
  runner.Fill(matrix.Values.data(), static_cast<Index>(matrix.Values.size()), 0.0, 1 << 18);
}
} // namespace mp
