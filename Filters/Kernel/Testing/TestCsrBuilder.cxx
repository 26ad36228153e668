// SPDX-License-Identifier: BSD-3-Clause
// CsrBuilder (Transfer/CsrBuilder.h): counts become starts and the rows are
// filled where they start; GroupInRows is a stable counting sort; the
// transpose and the accumulated rows match dense references entry for
// entry (the same additions in the same order: equal, not close).
#include "Transfer/CsrBuilder.h"

#include "Threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

namespace
{
using mp::Column;
using mp::CsrMatrix;
using mp::Index;

using Dense = std::vector<std::vector<double>>;

Dense ToDense(const CsrMatrix& m)
{
  Dense d(static_cast<size_t>(m.Rows), std::vector<double>(static_cast<size_t>(m.Columns), 0.0));
  for (Index i = 0; i < m.Rows; ++i)
  {
    for (Index q = m.RowStart[i]; q < m.RowStart[i + 1]; ++q)
    {
      d[i][m.ColumnIndex[q]] += m.Values[q];
    }
  }
  return d;
}

/// A random matrix with sorted, unique columns (some rows empty), as row lists.
std::vector<mp::RowList> RandomRows(Index rows, Index columns, unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<mp::RowList> lists(static_cast<size_t>(rows));
  for (Index i = 0; i < rows; ++i)
  {
    for (Index k = 0; k < columns; ++k)
    {
      if (rng() % 4 == 0)
      {
        lists[i].emplace_back(
          static_cast<Column>(k), std::uniform_real_distribution<double>(-2.0, 2.0)(rng));
      }
    }
  }
  return lists;
}
} // namespace

TEST(CsrBuilder, CountsBecomeStartsAndRowsAreFilledWhereTheyStart)
{
  std::vector<Index> start{ 0, 3, 0, 2, 5 };
  mp::CountsToStarts(start);
  EXPECT_EQ(start, (std::vector<Index>{ 0, 3, 3, 5, 10 }));

  // Row i holds i % 4 entries: columns i, i + 1, ..., values 10 i + column.
  const Index rows = 37;
  const Index columns = 45;
  auto length = [](Index i) { return i % 4; };
  auto fill = [](Index i, Column* column, double* value) {
    for (Index k = 0; k < i % 4; ++k)
    {
      column[k] = static_cast<Column>(i + k);
      value[k] = 10.0 * i + static_cast<double>(i + k);
    }
  };
  const CsrMatrix serial = mp::BuildCsr(rows, columns, length, fill);
  const mp::TaskRunner runner = mptest::ThreadRunner(3);
  const CsrMatrix tasks = mp::BuildCsr(rows, columns, length, fill, &runner);
  for (const CsrMatrix* m : { &serial, &tasks })
  {
    ASSERT_EQ(m->Rows, rows);
    ASSERT_EQ(m->Columns, columns);
    ASSERT_EQ(m->RowStart.size(), static_cast<size_t>(rows) + 1);
    Index expected = 0;
    for (Index i = 0; i < rows; ++i)
    {
      EXPECT_EQ(m->RowStart[i], expected);
      for (Index k = 0; k < i % 4; ++k)
      {
        EXPECT_EQ(m->ColumnIndex[expected + k], i + k);
        EXPECT_EQ(m->Values[expected + k], 10.0 * i + static_cast<double>(i + k));
      }
      expected += i % 4;
    }
    EXPECT_EQ(m->NonZeros(), expected);
  }
  // From row lists: the dense matrix the lists give.
  const std::vector<mp::RowList> lists = RandomRows(23, 17, 5);
  const CsrMatrix fromLists = mp::CsrFromRowLists(17, lists);
  Dense reference(23, std::vector<double>(17, 0.0));
  for (size_t i = 0; i < lists.size(); ++i)
  {
    for (const auto& entry : lists[i])
    {
      reference[i][entry.first] = entry.second;
    }
  }
  EXPECT_EQ(ToDense(fromLists), reference);
}

TEST(CsrBuilder, GroupInRowsIsAStableCountingSort)
{
  // Items with keys, grouped by key: the same as a stable sort by key.
  std::mt19937 rng(7);
  const Index keys = 13;
  std::vector<std::pair<Index, Index>> items; // (key, id)
  for (Index id = 0; id < 200; ++id)
  {
    items.emplace_back(static_cast<Index>(rng() % (keys - 2)), id); // the last two keys empty
  }
  std::vector<Index> start;
  std::vector<Index> grouped;
  int visits = 0;
  mp::GroupInRows(
    keys,
    [&](auto put) {
      ++visits;
      for (const auto& item : items)
      {
        put(item.first, item.second);
      }
    },
    start, grouped);
  EXPECT_EQ(visits, 2);
  std::vector<std::pair<Index, Index>> sorted(items);
  std::stable_sort(sorted.begin(), sorted.end(),
    [](const std::pair<Index, Index>& a, const std::pair<Index, Index>& b) {
      return a.first < b.first;
    });
  ASSERT_EQ(start.size(), static_cast<size_t>(keys) + 1);
  ASSERT_EQ(grouped.size(), items.size());
  for (size_t j = 0; j < sorted.size(); ++j)
  {
    EXPECT_EQ(grouped[j], sorted[j].second);
  }
  for (Index k = 0; k < keys; ++k)
  {
    const auto count = std::count_if(items.begin(), items.end(),
      [k](const std::pair<Index, Index>& item) { return item.first == k; });
    EXPECT_EQ(start[k + 1] - start[k], count) << "key " << k;
  }
}

TEST(CsrBuilder, TransposeMatchesTheDenseTranspose)
{
  const CsrMatrix a = mp::CsrFromRowLists(31, RandomRows(19, 31, 3));
  const CsrMatrix t = mp::Transposed(a);
  ASSERT_EQ(t.Rows, 31);
  ASSERT_EQ(t.Columns, 19);
  const Dense da = ToDense(a);
  const Dense dt = ToDense(t);
  for (Index i = 0; i < 19; ++i)
  {
    for (Index k = 0; k < 31; ++k)
    {
      EXPECT_EQ(dt[k][i], da[i][k]);
    }
  }
  // A^T's rows are sorted (A's rows in order), and (A^T)^T is A, entry for entry.
  for (Index k = 0; k < t.Rows; ++k)
  {
    EXPECT_TRUE(std::is_sorted(
      t.ColumnIndex.begin() + t.RowStart[k], t.ColumnIndex.begin() + t.RowStart[k + 1]));
  }
  const CsrMatrix back = mp::Transposed(t);
  EXPECT_EQ(std::vector<Index>(back.RowStart.begin(), back.RowStart.end()),
    std::vector<Index>(a.RowStart.begin(), a.RowStart.end()));
  EXPECT_TRUE(std::equal(back.ColumnIndex.begin(), back.ColumnIndex.end(), a.ColumnIndex.begin()));
  EXPECT_TRUE(std::equal(back.Values.begin(), back.Values.end(), a.Values.begin()));
  EXPECT_EQ(back.NonZeros(), a.NonZeros());
}

TEST(CsrBuilder, AccumulatedRowsMatchADenseSum)
{
  // Rows of terms with repeated columns, summed per column: the dense sums
  // (added in the same order), columns ascending or in the order first met.
  std::mt19937 rng(11);
  const Index columns = 29;
  mp::RowAccumulator sum(columns);
  std::vector<mp::RowList> sorted;
  std::vector<mp::RowList> met;
  Dense reference;
  std::vector<std::vector<Column>> firstMet;
  for (int row = 0; row < 12; ++row)
  {
    std::vector<std::pair<Column, double>> terms;
    for (int t = 0; t < row * 5; ++t)
    {
      terms.emplace_back(
        static_cast<Column>(rng() % 9 * 3), std::uniform_real_distribution<double>(-1.0, 1.0)(rng));
    }
    std::vector<double> dense(static_cast<size_t>(columns), 0.0);
    std::vector<Column> order;
    for (const auto& term : terms)
    {
      if (std::find(order.begin(), order.end(), term.first) == order.end())
      {
        order.push_back(term.first);
      }
      dense[term.first] += term.second;
    }
    reference.push_back(dense);
    firstMet.push_back(order);
    for (bool ascending : { true, false })
    {
      for (const auto& term : terms)
      {
        sum.Add(term.first, term.second);
      }
      EXPECT_EQ(sum.Empty(), terms.empty());
      (ascending ? sorted : met).emplace_back();
      sum.TakeInto(ascending, (ascending ? sorted : met).back());
      EXPECT_TRUE(sum.Empty());
    }
  }
  const CsrMatrix m = mp::CsrFromRowLists(columns, sorted);
  EXPECT_EQ(ToDense(m), reference);
  for (size_t i = 0; i < sorted.size(); ++i)
  {
    ASSERT_EQ(met[i].size(), firstMet[i].size());
    for (size_t j = 0; j < met[i].size(); ++j)
    {
      EXPECT_EQ(met[i][j].first, firstMet[i][j]);
      EXPECT_EQ(met[i][j].second, reference[i][firstMet[i][j]]);
    }
    std::vector<Column> ascending(firstMet[i]);
    std::sort(ascending.begin(), ascending.end());
    ASSERT_EQ(sorted[i].size(), ascending.size());
    for (size_t j = 0; j < ascending.size(); ++j)
    {
      EXPECT_EQ(sorted[i][j].first, ascending[j]);
    }
  }
}
