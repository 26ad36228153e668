// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Threads.h
 * @brief The filter's threads: where its loops and the kernel's tasks run.
 *
 * VTK 9.2's STDThread backend starts new threads for every
 * vtkSMPTools::For, and a projection runs many short loops, each of which
 * would pay for starting threads again. So while a WorkerScope is alive on
 * a thread and STDThread is the backend in use, that thread's loops
 * (SMPTaskRunner, For and FirstWhere below) run on an mp::WorkerPool of as
 * many threads as the backend would use, started once. Other backends
 * (TBB, OpenMP: their own lasting pools) are used as they are.
 *
 * Contract: a loop run inside a task of a pool (on one of its workers,
 * which have no scope) runs in turn on that thread, never waits for the
 * pool it is part of.
 */
#ifndef MeshProjection_Adapter_Threads_h
#define MeshProjection_Adapter_Threads_h

#include "Mesh/Tasks.h"
#include "Mesh/WorkerPool.h"

#include "vtkSMPTools.h"
#include "vtkType.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>

namespace mpvtk
{
/// The filter's threads for one execution (see the file's comment).
class WorkerScope
{
public:
  /// A pool of `threads` threads (this one included) for this thread's
  /// loops, when the backend is STDThread and `threads` > 1.
  explicit WorkerScope(int threads);
  /// Another thread of the same execution sharing `pool` (null: none).
  explicit WorkerScope(mp::WorkerPool* pool);
  ~WorkerScope();
  WorkerScope(const WorkerScope&) = delete;
  WorkerScope& operator=(const WorkerScope&) = delete;

private:
  std::unique_ptr<mp::WorkerPool> Owned;
  mp::WorkerPool* Previous = nullptr;
};

/// The pool of the WorkerScope alive on this thread, or null.
mp::WorkerPool* CurrentWorkers();

/// The kernel's task runner: one task per thread of the backend in use
/// (the filter's own scope, see NumberOfThreads), run on the calling
/// thread's WorkerScope when it has one (looked up at each call: a kept
/// operator's runner outlives the execution that made it), else by
/// vtkSMPTools.
mp::TaskRunner SMPTaskRunner();

/**
 * body(begin, end) over [first, last) in ranges of `grain` items (0: about
 * four ranges per thread), concurrently: on the calling thread's
 * WorkerScope when it has one, else by vtkSMPTools::For; in one call on
 * this thread inside a task of a pool (whose workers have no scope).
 */
template <class Body>
void For(vtkIdType first, vtkIdType last, vtkIdType grain, const Body& body)
{
  mp::WorkerPool* pool = CurrentWorkers();
  const vtkIdType n = last - first;
  if (n > 0 && mp::WorkerPool::InsideTask())
  {
    body(first, last); // inside a task of the pool: in turn, no threads of its own
    return;
  }
  if (!pool)
  {
    vtkSMPTools::For(first, last, grain, body);
    return;
  }
  if (n <= 0)
  {
    return;
  }
  if (grain <= 0)
  {
    grain = std::max<vtkIdType>(1, n / (4 * pool->Threads()));
  }
  // (At most as many ranges as an int counts.)
  grain = std::max(grain, n / std::numeric_limits<int>::max() + 1);
  const vtkIdType count = (n + grain - 1) / grain;
  pool->Run(static_cast<int>(count), [&](int k) {
    const vtkIdType begin = first + static_cast<vtkIdType>(k) * grain;
    body(begin, std::min(last, begin + grain));
  });
}
template <class Body>
void For(vtkIdType first, vtkIdType last, const Body& body)
{
  For(first, last, 0, body);
}

/**
 * The smallest i in [0, n) for which wrong(i) holds, or n, found in the
 * filter's threads: each range stops at its first (or once a smaller one is
 * known), and the smallest reported wins, so the answer does not depend on
 * how the ranges were shared out. `wrong` is called concurrently.
 */
template <typename Wrong>
vtkIdType FirstWhere(vtkIdType n, const Wrong& wrong)
{
  std::atomic<vtkIdType> first(n);
  For(0, n, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end && i < first; ++i)
    {
      if (wrong(i))
      {
        vtkIdType seen = first;
        while (i < seen && !first.compare_exchange_weak(seen, i))
        {}
        return;
      }
    }
  });
  return first;
}
} // namespace mpvtk

#endif
