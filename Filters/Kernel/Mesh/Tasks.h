// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Tasks.h
 * @brief How the kernel runs concurrent tasks: a runner the caller injects.
 *
 * The kernel's loops start no threads. Their callers hand them a runner
 * (the VTK filter passes its WorkerPool, or vtkSMPTools::For on backends
 * other than STDThread; the tests std::thread, or a WorkerPool) and a
 * number of tasks;
 * the kernel splits its loops into that many ranges. Sums over ranges are
 * added in range order, so a given number of tasks always gives the same
 * result.
 */
#ifndef MeshProjection_Kernel_Tasks_h
#define MeshProjection_Kernel_Tasks_h

#include "Mesh/LargeArray.h"
#include "Mesh/MeshView.h"

#include <algorithm>
#include <functional>
#include <vector>

namespace mp
{
/// First item of range k when n items are split into `tasks` ranges: the
/// one rule every split of the kernel follows (the search's ranges of
/// target cells and the assembly's shared rows must agree on it).
inline Index RangeBegin(Index n, int k, int tasks)
{
  return n * k / tasks;
}

/**
 * Reports progress of a long loop and asks whether to go on: called with
 * the fraction done (0..1] of the first task's share, from the thread that
 * runs task 0, between chunks of at least ProgressChunk items. Returning
 * false stops the loop at the next chunk boundary of every task (the
 * caller then discards the partial result). Empty: no chunks, no reports.
 */
using ProgressHook = std::function<bool(double fraction)>;
constexpr Index ProgressChunk = 8192;

struct TaskRunner
{
  /// How many concurrent tasks to split work into (1: serial).
  int Tasks = 1;
  /// Runs task(0), ..., task(count - 1), concurrently if it can. Empty:
  /// one after the other.
  std::function<void(int count, const std::function<void(int)>& task)> Run;

  /// Tasks for `n` items of work, at least `grain` items per task (run one
  /// after the other when there is no Run).
  int TasksFor(Index n, Index grain) const
  {
    return static_cast<int>(std::max<Index>(1, std::min<Index>(this->Tasks, n / grain)));
  }
  /// Runs task(0..count-1), through Run when count > 1.
  void RunAll(int count, const std::function<void(int)>& task) const
  {
    if (count > 1 && this->Run)
    {
      this->Run(count, task);
      return;
    }
    for (int k = 0; k < count; ++k)
    {
      task(k);
    }
  }
  /**
   * Runs body(begin, end) over [0, n) split into ranges of at least `grain`
   * items, and returns the sum of what the calls return, added in range
   * order.
   */
  template <class Body>
  auto ForRanges(Index n, const Body& body, Index grain = 4096) const
    -> decltype(body(Index(0), Index(0)))
  {
    using Sum = decltype(body(Index(0), Index(0)));
    const int tasks = this->TasksFor(n, grain);
    if (tasks == 1)
    {
      return body(Index(0), n);
    }
    std::vector<Sum> partial(static_cast<size_t>(tasks));
    this->RunAll(tasks,
      [&](int k) { partial[k] = body(RangeBegin(n, k, tasks), RangeBegin(n, k + 1, tasks)); });
    Sum sum = partial[0];
    for (int k = 1; k < tasks; ++k)
    {
      sum += partial[k];
    }
    return sum;
  }
  /// Sets data[0..n) to `value` in ranges of at least `grain` items (each
  /// task the first to touch its pages of a fresh array: see LargeArray.h).
  template <class T>
  void Fill(T* data, Index n, T value, Index grain = 4096) const
  {
    this->ForRanges(
      n,
      [data, value](Index begin, Index end) {
        std::fill(data + begin, data + end, value);
        return 0;
      },
      grain);
  }
};

/// Sums the tasks' arrays (in task order, element by element: the same bits
/// on any number of threads) into `sum` (empty when there are none); the
/// first part's storage becomes the sum.
inline void SumTaskArrays(
  std::vector<LargeVector<double>>& parts, const TaskRunner& runner, LargeVector<double>& sum)
{
  sum.clear();
  if (parts.empty())
  {
    return;
  }
  sum.swap(parts[0]);
  for (size_t k = 1; k < parts.size(); ++k)
  {
    const double* part = parts[k].data();
    double* to = sum.data();
    runner.ForRanges(
      static_cast<Index>(sum.size()),
      [=](Index begin, Index end) {
        for (Index i = begin; i < end; ++i)
        {
          to[i] += part[i];
        }
        return 0;
      },
      Index(1) << 16);
  }
}
} // namespace mp

#endif
