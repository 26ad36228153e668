// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Threads.h
 * @brief How the kernel tests run the kernel's tasks concurrently: each
 *        task on a std::thread of its own (the filter uses vtkSMPTools).
 */
#ifndef MeshProjection_Testing_Threads_h
#define MeshProjection_Testing_Threads_h

#include "Mesh/Tasks.h"

#include <functional>
#include <thread>
#include <vector>

namespace mptest
{
/// Runs task(0..count-1) on threads of their own.
inline void RunInThreads(int count, const std::function<void(int)>& task)
{
  std::vector<std::thread> pool;
  for (int k = 0; k < count; ++k)
  {
    pool.emplace_back(task, k);
  }
  for (std::thread& t : pool)
  {
    t.join();
  }
}

/// A runner of `tasks` concurrent tasks on threads of their own.
inline mp::TaskRunner ThreadRunner(int tasks)
{
  mp::TaskRunner runner;
  runner.Tasks = tasks;
  runner.Run = RunInThreads;
  return runner;
}
} // namespace mptest

#endif
