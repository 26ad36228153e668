// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/MassMatrix.h"

#include "Mesh/CellNeighbors.h"
#include "Mesh/SortEight.h"
#include "Mesh/Vec3.h"

#include <algorithm>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

namespace mp
{
namespace
{
/// Points per task of M_tt's values (P1Values), at least: as the
/// pattern's (a task reads only the cells of its points, TaskCells, so
/// that a 3D mesh of 10^5 cells, some 17,000 points, is split too).
constexpr Index ValuesGrain = 4096;

/// M_tt's values (as many as its pattern's entries) set to zero, by
/// concurrent tasks (each the first to touch its pages).
void ZeroValues(CsrMatrix& matrix, const TaskRunner& runner)
{
  matrix.Values.resize(matrix.ColumnIndex.size());
  runner.Fill(matrix.Values.data(), static_cast<Index>(matrix.Values.size()), 0.0, 1 << 18);
}

/**
 * The cells around each point of a mesh (BuildPointCells' lists), with ids
 * of type Id: 32 bits when they fit, half the memory. The pattern reads
 * them; the values only each task's set of cells (TaskCells).
 */
template <class Id>
struct AroundPoints
{
  UninitializedLargeVector<Id> Start;
  UninitializedLargeVector<Id> Cells;

  /// Those the neighbours' construction kept (mesh.Around, emptied), when
  /// there are; else built.
  AroundPoints(const MeshView& mesh, const TaskRunner& runner)
  {
    if constexpr (std::is_same<Id, std::int32_t>::value)
    {
      if (mesh.Around && mesh.Around->Fit(mesh))
      {
        this->Start.swap(mesh.Around->Start);
        this->Cells.swap(mesh.Around->Cells);
        return;
      }
    }
    BuildPointCells(mesh, this->Start, this->Cells, runner);
  }
};

/**
 * Per task of the values (P1Values: a range of points each), the cells
 * using its points, as bits over the span of their ids [Low, High] (none:
 * Low > High), from the lists of the cells around the points (each task
 * reads its own points' lists). On a mesh numbered along space
 * (SpatialOrder.h) the cells using a range of points lie mostly in a range
 * of ids of about their share, but not all: the points along a seam of the
 * curve are used by cells far along it too, and the span of the first
 * range's cells reaches nearly to the last cell. A task reads only the
 * cells whose bits are set, not its whole span. (Where the bits would take
 * more than 2 bytes per entry of the task's lists, as on a mesh in no
 * order split in many tasks, there are none: the task reads its span.)
 */
struct TaskCells
{
  using Word = std::uint64_t;
  std::vector<Index> Low;
  std::vector<Index> High;
  std::vector<UninitializedLargeVector<Word>> Bits;

  TaskCells() = default;
  template <class Id>
  TaskCells(const AroundPoints<Id>& around, Index points, int tasks, const TaskRunner& runner)
    : Low(static_cast<size_t>(tasks))
    , High(static_cast<size_t>(tasks))
    , Bits(static_cast<size_t>(tasks))
  {
    runner.RunAll(tasks, [&](int k) {
      const Index begin = around.Start[RangeBegin(points, k, tasks)];
      const Index end = around.Start[RangeBegin(points, k + 1, tasks)];
      Index low = std::numeric_limits<Index>::max();
      Index high = -1;
      for (Index i = begin; i < end; ++i)
      {
        low = std::min<Index>(low, around.Cells[i]);
        high = std::max<Index>(high, around.Cells[i]);
      }
      this->Low[k] = low;
      this->High[k] = high;
      if (high < low || high - low >= 16 * (end - begin))
      {
        return;
      }
      UninitializedLargeVector<Word>& bits = this->Bits[k];
      bits.resize(static_cast<size_t>((high - low) / 64 + 1));
      std::fill(bits.begin(), bits.end(), Word(0));
      for (Index i = begin; i < end; ++i)
      {
        const Index c = around.Cells[i] - low;
        bits[static_cast<size_t>(c >> 6)] |= Word(1) << (c & 63);
      }
    });
  }

  /// Calls visit(c) for each cell of task k (without bits: each of its
  /// span), in increasing order.
  template <class Visit>
  void ForEach(int k, const Visit& visit) const
  {
    const UninitializedLargeVector<Word>& bits = this->Bits[k];
    if (bits.empty())
    {
      for (Index c = this->Low[k]; c <= this->High[k]; ++c)
      {
        visit(c);
      }
      return;
    }
    for (size_t w = 0; w < bits.size(); ++w)
    {
      for (Word b = bits[w]; b != 0; b &= b - 1)
      {
        visit(this->Low[k] + 64 * static_cast<Index>(w) + __builtin_ctzll(b));
      }
    }
  }
};

/// The CSR pattern of the point graph of a simplicial mesh (every pair of
/// points sharing a cell, and every point with itself), from the cells
/// around each point; rows in concurrent tasks over point ranges when a
/// runner is given, each into a block of its own, then moved into place.
template <class Id>
void PointGraph(const MeshView& mesh, const AroundPoints<Id>& around, const TaskRunner& runner,
  LargeVector<Index>& start, UninitializedLargeVector<Column>& columns)
{
  const UninitializedLargeVector<Id>& cellStart = around.Start;
  const UninitializedLargeVector<Id>& cells = around.Cells;
  const int n = mesh.CornersPerCell();
  const Index points = mesh.NumberOfPoints;
  // Each task marks candidates in an array over all points (`seen` below):
  // at most as many tasks as uses of a point by cells, so that the marks
  // take no more memory than the point-cell lists.
  const Index uses = points > 0 ? mesh.NumberOfCells * n / points : 0;
  const int tasks =
    static_cast<int>(std::min<Index>(runner.TasksFor(points, 4096), std::max<Index>(1, uses)));
  start.assign(static_cast<size_t>(points) + 1, 0);
  // The first task writes its rows straight into `columns`, reserved for
  // all rows at the usual count (pages of a reservation cost nothing until
  // written), the others into blocks of their own, moved in after it.
  const size_t perRow = n == 3 ? 7 : 15;
  std::vector<UninitializedLargeVector<Column>> blocks(static_cast<size_t>(tasks));
  auto rows = [&](int k) {
    UninitializedLargeVector<Column>& block = k == 0 ? columns : blocks[k];
    block.clear();
    block.reserve(static_cast<size_t>(k == 0 ? points + 1 : points / tasks + 1) * perRow);
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
        const CellCorners ids = mesh.Cell(cells[i]);
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
    // (Past the reservation on unusual meshes: the first task's rows are
    // moved with the rest, as a vector grows.) The other blocks are copied
    // in after them by ranges of the columns (each range from the blocks it
    // overlaps: the copy shared by every thread, not one block per task).
    columns.resize(static_cast<size_t>(start[points]));
    const Index moved = start[RangeBegin(points, 1, tasks)];
    runner.ForRanges(
      start[points] - moved,
      [&](Index begin, Index end) {
        for (int k = 1; k < tasks; ++k)
        {
          const Index from = start[RangeBegin(points, k, tasks)] - moved;
          const Index to = start[RangeBegin(points, k + 1, tasks)] - moved;
          const Index a = std::max(begin, from);
          const Index b = std::min(end, to);
          if (a < b)
          {
            const Column* block = blocks[k].data();
            std::copy(block + (a - from), block + (b - from), columns.data() + moved + a);
          }
        }
        return 0;
      },
      Index(1) << 16);
    std::vector<UninitializedLargeVector<Column>>().swap(blocks);
  }
}

/**
 * M_tt's values for P1, its pattern made (the cells around the points,
 * which the pattern needed, are gone by now: the values take their room;
 * `cells` is what they left, when there are several tasks). Each task owns
 * a range of rows and goes through the cells using its points (its
 * TaskCells; one task: every cell), in order, adding the rows of its range
 * of each cell's block: a row sums its cells' blocks in cell order,
 * whatever the number of tasks. With `cover`, each point of the task's range also
 * takes the largest of `cellValue` over its cells (a reading of cells the
 * loop makes anyway, by the task owning the point: no two tasks write
 * one).
 */
void P1Values(const MeshView& mesh, const TaskCells& cells, const CellMasses& masses,
  const TaskRunner& runner, CsrMatrix& matrix, const CellValues& cellValue, double* cover)
{
  const int n = mesh.CornersPerCell();
  const Index points = mesh.NumberOfPoints;
  // The element mass of a whole cell: unit (1 + delta_ik) times its measure.
  const double unit = 1.0 / ((mesh.CellDimension + 1) * (mesh.CellDimension + 2));
  const int tasks = runner.TasksFor(points, ValuesGrain);
  const Index* rowStart = matrix.RowStart.data();
  const Column* columns = matrix.ColumnIndex.data();
  double* values = matrix.Values.data();
  const Index entries = rowStart[points];
  // Adds block row `a` of a cell on functions `dofs` into row dofs[a]. Each
  // column is found among the row's first 8 (2D: most rows have 7 entries)
  // or 16 entries (3D: about 15) by vector compares, with no branch to
  // mispredict; else by a scan.
  auto addRow = [=](const Index* dofs, int a, const double* row) {
    const Index begin = rowStart[dofs[a]];
    const Index length = rowStart[dofs[a] + 1] - begin;
    const int width =
      length <= 8 && begin + 8 <= entries ? 8 : (length <= 16 && begin + 16 <= entries ? 16 : 0);
    for (int b = 0; b < n; ++b)
    {
      const auto q = static_cast<Column>(dofs[b]);
#if defined(__SSE2__)
      if (width > 0)
      {
        const __m128i want = _mm_set1_epi32(q);
        auto match = [&](int at) {
          const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(columns + begin + at));
          return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(v, want))))
            << at;
        };
        unsigned mask = match(0) | match(4);
        if (width == 16)
        {
          mask |= match(8) | match(12);
        }
        values[begin + __builtin_ctz(mask)] += row[b];
        continue;
      }
#endif
      Index p = begin;
      while (columns[p] != q)
      {
        ++p;
      }
      values[p] += row[b];
    }
  };
  runner.RunAll(tasks, [&](int k) {
    const Index first = RangeBegin(points, k, tasks);
    const Index last = RangeBegin(points, k + 1, tasks);
    auto mine = [first, last](Index p) { return p >= first && p < last; };
    const Index high = tasks > 1 ? cells.High[k] : mesh.NumberOfCells - 1;
    // (Inlined at both of its calls: a call per cell costs the one-task loop.)
    auto add = [&](Index c) __attribute__((always_inline))
    {
      const float state = masses.State[static_cast<size_t>(c)];
      if (state == CellMasses::None && !cover)
      {
        return;
      }
      const CellCorners ids = mesh.Cell(c);
      Index dofs[4];
      bool any = false;
      for (int a = 0; a < n; ++a)
      {
        dofs[a] = ids[a];
        any = any || mine(dofs[a]);
      }
      if (!any)
      {
        return;
      }
      if (cover)
      {
        // (Uncovered cells too: a parent may be covered by its other cells.
        // By parent, the values are in the dataset's order: a cache miss a
        // cell unless asked for ahead.)
        if (cellValue.ByParent && c + 16 <= high)
        {
          __builtin_prefetch(cellValue.Values + mesh.ParentOf(c + 16));
        }
        const double f = cellValue.Values[cellValue.ByParent ? mesh.ParentOf(c) : c];
        for (int a = 0; a < n; ++a)
        {
          if (mine(dofs[a]))
          {
            cover[dofs[a]] = std::max(cover[dofs[a]], f);
          }
        }
        if (state == CellMasses::None)
        {
          return;
        }
      }
      if (state != CellMasses::Part)
      {
        const double m = unit * CellMasses::Covered(mesh, c, state);
        for (int a = 0; a < n; ++a)
        {
          if (mine(dofs[a]))
          {
            double row[4] = { m, m, m, m };
            row[a] = 2.0 * m;
            addRow(dofs, a, row);
          }
        }
        return;
      }
      // The upper triangle kept, row by row.
      const double* b = masses.Find(c);
      double block[4][4];
      for (int a = 0; a < n; ++a)
      {
        for (int j = a; j < n; ++j)
        {
          block[a][j] = block[j][a] = *b++;
        }
      }
      for (int a = 0; a < n; ++a)
      {
        if (mine(dofs[a]))
        {
          addRow(dofs, a, block[a]);
        }
      }
    };
    if (tasks > 1)
    {
      cells.ForEach(k, add);
      return;
    }
    for (Index c = 0; c <= high; ++c)
    {
      add(c);
    }
  });
}

/**
 * M_tt for P1 (AssembleTargetMass): the point graph, zeros, then with
 * `masses` the values (and with `cover`, of mesh.NumberOfPoints, the point
 * cover), from one set of lists of the cells around the points (gone
 * before the values: they take their room).
 */
template <class Id>
void P1Matrix(const MeshView& mesh, const CellMasses* masses, const TaskRunner& runner,
  CsrMatrix& matrix, const CellValues& cellValue, LargeVector<double>* cover)
{
  TaskCells cells;
  {
    const AroundPoints<Id> around(mesh, runner);
    PointGraph(mesh, around, runner, matrix.RowStart, matrix.ColumnIndex);
    const int tasks = runner.TasksFor(mesh.NumberOfPoints, ValuesGrain);
    if (masses && tasks > 1)
    {
      cells = TaskCells(around, mesh.NumberOfPoints, tasks, runner);
    }
  }
  ZeroValues(matrix, runner);
  if (!masses)
  {
    return;
  }
  double* coverData = nullptr;
  if (cover && cellValue.Values)
  {
    cover->resize(static_cast<size_t>(mesh.NumberOfPoints));
    runner.Fill(cover->data(), mesh.NumberOfPoints, 0.0, 1 << 18);
    coverData = cover->data();
  }
  P1Values(mesh, cells, *masses, runner, matrix, cellValue, coverData);
}

} // namespace

void CellMasses::Gather(std::vector<PartialMasses>& tasks)
{
  PartialMasses all;
  for (PartialMasses& t : tasks)
  {
    all.Cells.insert(all.Cells.end(), t.Cells.begin(), t.Cells.end());
    all.Blocks.insert(all.Blocks.end(), t.Blocks.begin(), t.Blocks.end());
    t = PartialMasses();
  }
  // Sorted by cell (each cell once: it is flushed once).
  std::vector<Index> order(all.Cells.size());
  for (size_t i = 0; i < order.size(); ++i)
  {
    order[i] = static_cast<Index>(i);
  }
  std::sort(
    order.begin(), order.end(), [&](Index x, Index y) { return all.Cells[x] < all.Cells[y]; });
  const size_t n = static_cast<size_t>(this->Dofs * (this->Dofs + 1) / 2);
  PartialMasses& sorted = this->Partial;
  sorted = PartialMasses();
  sorted.Cells.reserve(order.size());
  sorted.Blocks.reserve(order.size() * n);
  for (Index i : order)
  {
    sorted.Cells.push_back(all.Cells[i]);
    sorted.Blocks.insert(
      sorted.Blocks.end(), all.Blocks.begin() + i * n, all.Blocks.begin() + (i + 1) * n);
  }
}

const double* CellMasses::Find(Index c) const
{
  const auto at = std::lower_bound(this->Partial.Cells.begin(), this->Partial.Cells.end(), c);
  const size_t i = static_cast<size_t>(at - this->Partial.Cells.begin());
  return this->Partial.Blocks.data() + i * static_cast<size_t>(this->Dofs * (this->Dofs + 1) / 2);
}

void AssembleTargetMass(SpaceType space, const MeshView& mesh, const CellMasses* masses,
  const TaskRunner& runner, CsrMatrix& matrix, const CellValues& cellValue,
  LargeVector<double>* pointCover)
{
  if (pointCover)
  {
    pointCover->clear();
  }
  matrix = CsrMatrix();
  const Index n = SpaceSize(space, mesh);
  matrix.Rows = matrix.Columns = n;
  if (space == SpaceType::P1)
  {
    if (mesh.NumberOfCells * mesh.CornersPerCell() < std::numeric_limits<std::int32_t>::max())
    {
      P1Matrix<std::int32_t>(mesh, masses, runner, matrix, cellValue, pointCover);
    }
    else
    {
      P1Matrix<Index>(mesh, masses, runner, matrix, cellValue, pointCover);
    }
    return;
  }
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
  ZeroValues(matrix, runner);
  if (!masses)
  {
    return;
  }
  // P0: each cell's measure (whole) or covered measure into its original
  // cell's row, in cell order; in tasks when each row has one cell.
  double* values = matrix.Values.data();
  auto add = [&mesh, masses, values](Index begin, Index end) {
    for (Index c = begin; c < end; ++c)
    {
      const float state = masses->State[static_cast<size_t>(c)];
      if (state == CellMasses::None)
      {
        continue;
      }
      if (state != CellMasses::Part)
      {
        values[mesh.ParentOf(c)] += CellMasses::Covered(mesh, c, state);
      }
      else
      {
        values[mesh.ParentOf(c)] += *masses->Find(c);
      }
    }
    return 0;
  };
  if (!mesh.Parent || mesh.OneCellPerParent)
  {
    runner.ForRanges(mesh.NumberOfCells, add, Index(1) << 16);
  }
  else
  {
    add(0, mesh.NumberOfCells);
  }
}

void MassPattern(SpaceType space, const MeshView& mesh, const TaskRunner& runner, CsrMatrix& matrix)
{
  AssembleTargetMass(space, mesh, nullptr, runner, matrix);
}
} // namespace mp
