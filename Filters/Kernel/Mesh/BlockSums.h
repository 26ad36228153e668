// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BlockSums.h
 * @brief Sums of many terms that come out bit for bit the same for any
 *        number of tasks.
 *
 * Floating-point addition is not associative: a sum split into one range
 * per task depends on how many tasks there are (TaskRunner::ForRanges is
 * deterministic only for a given number). Integrals the filter reports
 * (the source's and the target's, to check conservation) must not change
 * with the machine's number of threads, so they are summed in blocks of a
 * fixed size instead: each block from zero on its own, then the blocks'
 * sums one after the other in block order. Which task sums which block
 * then changes nothing.
 *
 * In Mesh, the lowest room: it needs only the runner (Tasks.h), and any
 * room (or the VTK adapter) may sum with it.
 */
#ifndef MeshProjection_Kernel_BlockSums_h
#define MeshProjection_Kernel_BlockSums_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

#include <algorithm>
#include <vector>

namespace mp
{
/// The items of one block of SumInBlocks (2^14): part of its result, as
/// the rounding depends on where the blocks end.
constexpr Index SumBlockItems = Index(1) << 14;

/**
 * Per component k < nc, the sum of term(i, k) over i in [0, n): each block
 * of SumBlockItems items summed on its own (from 0.0, i in increasing
 * order, the nc components side by side), then the blocks' sums added in
 * block order (to 0.0). The blocks run in `runner`'s tasks, a range of
 * whole blocks each; the sums are the same bit for bit for any number of
 * tasks (and with a default, serial runner).
 *
 * `term(Index i, int k)` returns a double; it is called once per (i, k),
 * from the runner's tasks concurrently (for different i), so it must only
 * read shared state. Returns nc sums (zeros when n <= 0).
 *
 * For example the integral of a field given per function i with weights w:
 *   SumInBlocks(n, nc, runner, [&](Index i, int k) { return w[i] * u[i * nc + k]; })
 */
template <class Term>
std::vector<double> SumInBlocks(Index n, int nc, const TaskRunner& runner, const Term& term)
{
  const Index blocks = n > 0 ? (n + SumBlockItems - 1) / SumBlockItems : 0;
  std::vector<double> partial(static_cast<size_t>(blocks * nc), 0.0);
  const int tasks = runner.TasksFor(blocks, 1);
  runner.RunAll(tasks, [&](int task) {
    std::vector<double> sum(static_cast<size_t>(nc));
    for (Index b = RangeBegin(blocks, task, tasks); b < RangeBegin(blocks, task + 1, tasks); ++b)
    {
      std::fill(sum.begin(), sum.end(), 0.0);
      const Index last = std::min(n, (b + 1) * SumBlockItems);
      for (Index i = b * SumBlockItems; i < last; ++i)
      {
        for (int k = 0; k < nc; ++k)
        {
          sum[static_cast<size_t>(k)] += term(i, k);
        }
      }
      std::copy(sum.begin(), sum.end(), partial.begin() + b * nc);
    }
  });
  std::vector<double> total(static_cast<size_t>(nc), 0.0);
  for (Index b = 0; b < blocks; ++b)
  {
    for (int k = 0; k < nc; ++k)
    {
      total[static_cast<size_t>(k)] += partial[static_cast<size_t>(b * nc + k)];
    }
  }
  return total;
}
} // namespace mp

#endif
