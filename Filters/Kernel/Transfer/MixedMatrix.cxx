// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/MixedMatrix.h"

#include <algorithm>

namespace mp
{
void AssembleMixedMatrix(std::vector<MixedBlocks>& blocks, Index rows, Index columns,
  const TaskRunner& runner, CsrMatrix& matrix)
{
  matrix = CsrMatrix();
  matrix.Rows = rows;
  matrix.Columns = columns;
  // Where each row's parts are: references (global block, row in block)
  // encoded as global block * per + row, in CSR by row (a counting sort).
  const int per = blocks.empty() ? 1 : blocks[0].RowsPerBlock;
  std::vector<Index> base(blocks.size() + 1, 0);
  for (size_t t = 0; t < blocks.size(); ++t)
  {
    base[t + 1] = base[t] + blocks[t].Size();
  }
  LargeVector<Index> refStart(static_cast<size_t>(rows) + 1, 0);
  for (const MixedBlocks& b : blocks)
  {
    for (Index r : b.Rows)
    {
      ++refStart[r + 1];
    }
  }
  for (Index r = 0; r < rows; ++r)
  {
    refStart[r + 1] += refStart[r];
  }
  LargeVector<Index> refs(static_cast<size_t>(refStart[rows]));
  {
    LargeVector<Index> fill(refStart.begin(), refStart.end() - 1);
    for (size_t t = 0; t < blocks.size(); ++t)
    {
      const LargeVector<Index>& r = blocks[t].Rows;
      for (size_t k = 0; k < r.size(); ++k)
      {
        refs[fill[r[k]]++] = base[t] * per + static_cast<Index>(k);
      }
    }
  }

  // Each range of rows merges its rows into buffers of its own.
  const int tasks = runner.TasksFor(rows, 4096);
  struct Range
  {
    LargeVector<Column> Columns;
    LargeVector<double> Values;
  };
  std::vector<Range> ranges(static_cast<size_t>(tasks));
  matrix.RowStart.assign(static_cast<size_t>(rows) + 1, 0);
  runner.RunAll(tasks, [&](int k) {
    Range& out = ranges[k];
    // At most every part's columns; untouched reserved pages cost nothing.
    Index bound = 0;
    for (const MixedBlocks& b : blocks)
    {
      bound += static_cast<Index>(b.Columns.size()) * b.RowsPerBlock;
    }
    bound = bound / tasks + 1;
    out.Columns.reserve(static_cast<size_t>(bound));
    out.Values.reserve(static_cast<size_t>(bound));
    std::vector<double> sum(static_cast<size_t>(columns), 0.0);
    std::vector<Index> seen(static_cast<size_t>(columns), -1);
    std::vector<Column> row;
    for (Index r = RangeBegin(rows, k, tasks); r < RangeBegin(rows, k + 1, tasks); ++r)
    {
      row.clear();
      for (Index q = refStart[r]; q < refStart[r + 1]; ++q)
      {
        const Index block = refs[q] / per;
        const int i = static_cast<int>(refs[q] % per);
        const size_t t =
          static_cast<size_t>(std::upper_bound(base.begin(), base.end(), block) - base.begin() - 1);
        const MixedBlocks& b = blocks[t];
        const Index local = block - base[t];
        for (Index p = b.Start[local]; p < b.Start[local + 1]; ++p)
        {
          const Column c = b.Columns[p];
          if (seen[c] != r)
          {
            seen[c] = r;
            sum[c] = 0.0;
            row.push_back(c);
          }
          sum[c] += b.Values[per * p + i];
        }
      }
      std::sort(row.begin(), row.end());
      for (Column c : row)
      {
        out.Columns.push_back(c);
        out.Values.push_back(sum[c]);
      }
      matrix.RowStart[r + 1] = static_cast<Index>(row.size());
    }
  });
  std::vector<MixedBlocks>().swap(blocks);
  for (Index r = 0; r < rows; ++r)
  {
    matrix.RowStart[r + 1] += matrix.RowStart[r];
  }
  matrix.ColumnIndex.resize(static_cast<size_t>(matrix.RowStart[rows]));
  matrix.Values.resize(static_cast<size_t>(matrix.RowStart[rows]));
  runner.RunAll(tasks, [&](int k) {
    const Index at = matrix.RowStart[RangeBegin(rows, k, tasks)];
    std::copy(ranges[k].Columns.begin(), ranges[k].Columns.end(), matrix.ColumnIndex.begin() + at);
    std::copy(ranges[k].Values.begin(), ranges[k].Values.end(), matrix.Values.begin() + at);
    LargeVector<Column>().swap(ranges[k].Columns);
    LargeVector<double>().swap(ranges[k].Values);
  });
}
} // namespace mp
