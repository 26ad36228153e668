// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Progress.h"

#include "vtkAlgorithm.h"
#include "vtkSMPTools.h"

#include "Adapter/Threads.h"

#include <exception>

namespace mpvtk
{
Progress::Progress(vtkAlgorithm* filter)
  : Filter(filter)
  , PipelineThread(std::this_thread::get_id())
{}

bool Progress::operator()(double amount)
{
  if (std::this_thread::get_id() == this->PipelineThread)
  {
    this->Filter->UpdateProgress(amount);
  }
  else
  {
    // A task on another thread: Watch() passes it on from the pipeline's.
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      this->Reported = amount;
    }
    this->Changed.notify_one();
  }
  return this->Filter->GetAbortExecute() == 0;
}

void Progress::Watch(const std::function<void()>& work)
{
  if (vtkSMPTools::GetEstimatedNumberOfThreads() <= 1)
  {
    work(); // tasks run on this thread: progress goes straight to the GUI
    return;
  }
  {
    std::lock_guard<std::mutex> lock(this->Lock);
    this->Reported = -1; // what an unwatched run left
  }
  bool done = false;
  std::exception_ptr failure;
  mp::WorkerPool* pool = mpvtk::CurrentWorkers();
  std::thread worker([&]() {
    mpvtk::WorkerScope workers(pool); // the execution's threads, from this one
    try
    {
      work();
    }
    catch (...)
    {
      failure = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      done = true;
    }
    this->Changed.notify_one();
  });
  std::unique_lock<std::mutex> lock(this->Lock);
  for (;;)
  {
    this->Changed.wait(lock, [&]() { return done || this->Reported >= 0; });
    const double amount = this->Reported;
    this->Reported = -1;
    const bool finished = done;
    if (amount >= 0)
    {
      lock.unlock();
      this->Filter->UpdateProgress(amount); // may run the GUI's event loop: not under the lock
      lock.lock();
    }
    if (finished)
    {
      break;
    }
  }
  lock.unlock();
  worker.join();
  if (failure)
  {
    std::rethrow_exception(failure);
  }
}
} // namespace mpvtk
