// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CsrBuilder.h
 * @brief Compressed rows built one way: count each row's entries, turn the
 *        counts into starts, fill.
 *
 * Every compressed-row structure of the transfer (a CsrMatrix, a graph's
 * rows, items grouped by a key) is built by these steps:
 *
 * - CountsToStarts: per-row counts (start[i + 1] holding row i's) become
 *   the rows' starts (start[0] = 0, start[rows] the number of entries).
 * - GroupInRows: entries listed by a visit grouped by their row, each row's
 *   in the order the visit lists them (a stable counting sort: a
 *   relation's inverse, the items by a key). The visit is called twice
 *   (count, then place) and must list the same entries both times.
 * - BuildCsr: a CsrMatrix from each row's length and a fill of each row
 *   (the fills in a runner's tasks when given: each row written once by
 *   one call, the same matrix whatever the tasks).
 * - CsrFromRowLists: a CsrMatrix from per-row lists of (column, value).
 * - Transposed: A^T by a counting sort (a row of A^T holds its entries in
 *   the order of A's rows).
 * - RowAccumulator: a row's terms summed per column (each column's terms
 *   added in the order given, starting from 0), the sums handed out in
 *   ascending columns or in the order the columns were first met.
 *
 * None reorders what it is given: a structure built here holds the same
 * entries in the same order, and the same sums of the same terms, as the
 * loops a caller would write by hand.
 */
#ifndef MeshProjection_Kernel_CsrBuilder_h
#define MeshProjection_Kernel_CsrBuilder_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"
#include "Transfer/CsrMatrix.h"

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace mp
{
/// start[i + 1] holding row i's count on entry, the rows' starts on return (start[0] must be 0).
template <class Starts>
void CountsToStarts(Starts& start)
{
  for (std::size_t i = 1; i < start.size(); ++i)
  {
    start[i] += start[i - 1];
  }
}

/**
 * Compressed rows (`start`: rows + 1 starts; `entries`) of the entries
 * `visit(put)` lists by calling put(row, entry) for each: row r holds its
 * entries in the order they were put. `visit` runs twice and must put the
 * same entries in the same order both times.
 */
template <class Starts, class Entries, class Visit>
void GroupInRows(Index rows, Visit visit, Starts& start, Entries& entries)
{
  using Entry = typename Entries::value_type;
  start.assign(static_cast<std::size_t>(rows) + 1, 0);
  visit([&](Index row, const Entry&) { ++start[static_cast<std::size_t>(row) + 1]; });
  CountsToStarts(start);
  entries.resize(static_cast<std::size_t>(start.back()));
  std::vector<Index> next(start.begin(), start.end() - 1);
  visit([&](Index row, const Entry& entry) {
    entries[static_cast<std::size_t>(next[static_cast<std::size_t>(row)]++)] = entry;
  });
}

/**
 * The rows x columns matrix whose row i holds length(i) entries, written by
 * fill(i, columns, values) (columns and values: the row's first entry).
 * With `runner`, the rows are filled in its tasks (fill must then write
 * only its row).
 */
template <class Length, class Fill>
CsrMatrix BuildCsr(
  Index rows, Index columns, Length length, Fill fill, const TaskRunner* runner = nullptr)
{
  CsrMatrix m;
  m.Rows = rows;
  m.Columns = columns;
  m.RowStart.assign(static_cast<std::size_t>(rows) + 1, 0);
  for (Index i = 0; i < rows; ++i)
  {
    m.RowStart[i + 1] = m.RowStart[i] + length(i);
  }
  m.ColumnIndex.resize(static_cast<std::size_t>(m.NonZeros()));
  m.Values.resize(static_cast<std::size_t>(m.NonZeros()));
  auto fillRange = [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i)
    {
      fill(i, m.ColumnIndex.data() + m.RowStart[i], m.Values.data() + m.RowStart[i]);
    }
    return 0;
  };
  if (runner)
  {
    runner->ForRanges(rows, fillRange);
  }
  else
  {
    fillRange(0, rows);
  }
  return m;
}

/// A row's entries as (column, value) pairs, in the row's order.
using RowList = std::vector<std::pair<Column, double>>;

/// The matrix of `lists.size()` rows x `columns` whose row i holds lists[i] as it is.
inline CsrMatrix CsrFromRowLists(Index columns, const std::vector<RowList>& lists)
{
  return BuildCsr(
    static_cast<Index>(lists.size()), columns,
    [&](Index i) { return static_cast<Index>(lists[static_cast<std::size_t>(i)].size()); },
    [&](Index i, Column* column, double* value) {
      for (const auto& entry : lists[static_cast<std::size_t>(i)])
      {
        *column++ = entry.first;
        *value++ = entry.second;
      }
    });
}

/// A^T: row k holds the entries (i, v) of A's column k, in ascending i (sorted when A's rows are).
inline CsrMatrix Transposed(const CsrMatrix& a)
{
  std::vector<Index> start;
  std::vector<std::pair<Column, double>> entries;
  GroupInRows(
    a.Columns,
    [&](auto put) {
      for (Index i = 0; i < a.Rows; ++i)
      {
        for (Index q = a.RowStart[i]; q < a.RowStart[i + 1]; ++q)
        {
          put(a.ColumnIndex[q], std::pair<Column, double>(static_cast<Column>(i), a.Values[q]));
        }
      }
    },
    start, entries);
  return BuildCsr(
    a.Columns, a.Rows, [&](Index k) { return start[k + 1] - start[k]; },
    [&](Index k, Column* column, double* value) {
      for (Index q = start[k]; q < start[k + 1]; ++q)
      {
        *column++ = entries[static_cast<std::size_t>(q)].first;
        *value++ = entries[static_cast<std::size_t>(q)].second;
      }
    });
}

/**
 * One row's terms summed per column in a dense accumulator over `columns`
 * columns (a row's distinct columns are few: they are listed as first met,
 * so that handing the sums out costs what the row holds, not `columns`).
 */
class RowAccumulator
{
public:
  explicit RowAccumulator(Index columns)
    : Sum(static_cast<std::size_t>(columns), 0.0)
    , Touched(static_cast<std::size_t>(columns), 0)
  {}
  /// Adds v to column k's sum.
  void Add(Index k, double v)
  {
    if (!this->Touched[static_cast<std::size_t>(k)])
    {
      this->Touched[static_cast<std::size_t>(k)] = 1;
      this->Used.push_back(static_cast<Column>(k));
    }
    this->Sum[static_cast<std::size_t>(k)] += v;
  }
  /// Whether no term was added since the last Take.
  bool Empty() const { return this->Used.empty(); }
  /**
   * Calls emit(k, sum) for every column met, in ascending k (`sorted`) or
   * in the order first met, and starts an empty row.
   */
  template <class Emit>
  void Take(bool sorted, Emit emit)
  {
    if (sorted)
    {
      std::sort(this->Used.begin(), this->Used.end());
    }
    for (const Column k : this->Used)
    {
      emit(k, this->Sum[static_cast<std::size_t>(k)]);
      this->Sum[static_cast<std::size_t>(k)] = 0.0;
      this->Touched[static_cast<std::size_t>(k)] = 0;
    }
    this->Used.clear();
  }
  /// Take into a row list (appended).
  void TakeInto(bool sorted, RowList& row)
  {
    row.reserve(row.size() + this->Used.size());
    this->Take(sorted, [&row](Column k, double v) { row.emplace_back(k, v); });
  }

private:
  std::vector<double> Sum;
  std::vector<char> Touched;
  std::vector<Column> Used;
};
} // namespace mp

#endif
