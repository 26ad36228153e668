// SPDX-License-Identifier: BSD-3-Clause
#include "Adapter/Threads.h"

#include <exception>
#include <functional>
#include <string>

namespace mpvtk
{
namespace
{
/// This thread's WorkerScope's pool (each thread of an execution sets its own).
thread_local mp::WorkerPool* Workers = nullptr;
} // namespace

WorkerScope::WorkerScope(int threads)
  : Previous(Workers)
{
  if (threads > 1 && std::string(vtkSMPTools::GetBackend()) == "STDThread")
  {
    try
    {
      this->Owned.reset(new mp::WorkerPool(threads));
      Workers = this->Owned.get();
    }
    catch (const std::exception&)
    {
      // No threads to be had: the loops go to vtkSMPTools as without a scope.
    }
  }
}

WorkerScope::WorkerScope(mp::WorkerPool* pool)
  : Previous(Workers)
{
  Workers = pool;
}

WorkerScope::~WorkerScope()
{
  Workers = this->Previous;
}

mp::WorkerPool* CurrentWorkers()
{
  return Workers;
}

mp::TaskRunner SMPTaskRunner()
{
  mp::TaskRunner runner;
  runner.Tasks = vtkSMPTools::GetEstimatedNumberOfThreads();
  runner.Run = [](int count, const std::function<void(int)>& task) {
    if (mp::WorkerPool* pool = Workers)
    {
      pool->Run(count, task);
      return;
    }
    if (mp::WorkerPool::InsideTask())
    {
      for (int k = 0; k < count; ++k)
      {
        task(k); // inside a task of a pool (on one of its workers): in turn
      }
      return;
    }
    vtkSMPTools::For(0, count, 1, [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType k = begin; k < end; ++k)
      {
        task(static_cast<int>(k));
      }
    });
  };
  return runner;
}
} // namespace mpvtk
