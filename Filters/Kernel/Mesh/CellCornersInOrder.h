// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CellCornersInOrder.h
 * @brief A scatter from cells to their corners in concurrent tasks that
 *        applies, point by point, in the order of the serial loop.
 *
 * Values spread from cells to their points (a cell's covered measure
 * shared among its corners, say) are sums per point; summed in whatever
 * order tasks reach a point, they would differ in their last bits from run
 * to run and with the number of threads. ForCellCornersInOrder gives every
 * point its values in cell order, as the one loop would, so its sums are
 * the serial loop's bit for bit, while most of the work still runs in the
 * tasks: with a numbering that follows space, the points a range of cells
 * shares with earlier ranges are few, and only their values wait.
 *
 * In Mesh, the lowest room: it needs only a MeshView and the runner
 * (Tasks.h), and any room (or the VTK adapter) may scatter with it.
 */
#ifndef MeshProjection_Kernel_CellCornersInOrder_h
#define MeshProjection_Kernel_CellCornersInOrder_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace mp
{
/**
 * For every cell c of `view` in turn and each of its corners p, apply(p,
 * value(c)), skipping cells whose value is not positive: as that loop
 * would, in the order it would (sums come out bit for bit the same), but
 * in `runner`'s tasks over ranges of cells. A range applies directly to
 * the points no earlier range uses (ids above the largest id of the
 * earlier ranges' cells, so no two tasks write one point) and keeps the
 * others' values until every range is done, then applies them in cell
 * order. Numberings that follow space (a renumbered copy numbers points as
 * its cells first use them) keep few; a range that would keep more than a
 * sixteenth of its corners (ids with no such order) stops, and its
 * remaining cells are applied after the values kept, in one loop.
 *
 * `value(Index c)` returns a double and is called once per cell (twice
 * for the cell at which a range stops), from the tasks concurrently: it
 * must only read shared state and give the same value each time. `apply(Index p, double v)`
 * is called from the tasks concurrently too, but never for one point from
 * two tasks at once, and for each point in cell order; it may write
 * per-point state (e.g. sum[p] += v). Fewer than 2 x 16384 cells (or a
 * serial runner): the plain loop.
 *
 * For example a cell measure shared among the corners:
 *   ForCellCornersInOrder(view, runner, [&](Index c) { return measure[c] / corners; },
 *     [&](Index p, double share) { w[p] += share; });
 */
template <class Value, class Apply>
void ForCellCornersInOrder(
  const MeshView& view, const TaskRunner& runner, const Value& value, const Apply& apply)
{
  const Index n = view.NumberOfCells;
  const int corners = view.CornersPerCell();
  auto serial = [&](Index begin, Index end) {
    for (Index c = begin; c < end; ++c)
    {
      const double v = value(c);
      if (v > 0.0)
      {
        const CellCorners ids = view.Cell(c);
        for (int k = 0; k < corners; ++k)
        {
          apply(ids[k], v);
        }
      }
    }
  };
  const int tasks = runner.TasksFor(n, 16384);
  if (tasks < 2)
  {
    serial(0, n);
    return;
  }
  auto range = [&](int k) {
    return std::make_pair(RangeBegin(n, k, tasks), RangeBegin(n, k + 1, tasks));
  };
  // Ids below first[k] may be used by the cells of an earlier range.
  std::vector<Index> first(static_cast<size_t>(tasks), 0);
  runner.RunAll(tasks, [&](int k) {
    Index top = -1;
    for (Index i = corners * range(k).first; i < corners * range(k).second; ++i)
    {
      top = std::max(top, view.Corner(i));
    }
    first[k] = top;
  });
  Index top = 0;
  for (int k = 0; k < tasks; ++k)
  {
    const Index largest = first[k];
    first[k] = top;
    top = std::max(top, largest + 1);
  }
  // Each range applies directly what it can and keeps the rest, up to a
  // sixteenth of its corners: a range that would keep more stops at that
  // cell (ids with no such order), and its remaining cells are applied in
  // one loop after the values kept by it and the ranges before it (points
  // of later ranges' direct values are none of its points).
  std::vector<Index> stopped(static_cast<size_t>(tasks), -1);
  std::vector<std::vector<std::pair<Index, double>>> kept(static_cast<size_t>(tasks));
  runner.RunAll(tasks, [&](int k) {
    std::vector<std::pair<Index, double>>& mine = kept[k];
    const size_t room = static_cast<size_t>(corners * (range(k).second - range(k).first) / 16);
    for (Index c = range(k).first; c < range(k).second; ++c)
    {
      const double v = value(c);
      if (v > 0.0)
      {
        const CellCorners ids = view.Cell(c);
        if (mine.size() + corners > room)
        {
          stopped[k] = c;
          return;
        }
        for (int j = 0; j < corners; ++j)
        {
          if (ids[j] >= first[k])
          {
            apply(ids[j], v);
          }
          else
          {
            mine.emplace_back(ids[j], v);
          }
        }
      }
    }
  });
  for (int k = 0; k < tasks; ++k)
  {
    for (const auto& entry : kept[k])
    {
      apply(entry.first, entry.second);
    }
    if (stopped[k] >= 0)
    {
      serial(stopped[k], range(k).second);
    }
  }
}
} // namespace mp

#endif
