// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/WorkerPool.h"

#include <algorithm>
#include <chrono>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mp
{
namespace
{
/// Set while this thread runs a task of a pool: a Run from inside a task
/// runs its tasks on this thread.
thread_local bool InTask = false;

/// InTask set for a scope, then put back as it was.
struct TaskScope
{
  bool Outer = InTask;
  TaskScope() { InTask = true; }
  ~TaskScope() { InTask = this->Outer; }
};

/// How long a thread waits spinning (for the next job, for the job's last
/// task) before it waits asleep.
constexpr std::chrono::microseconds SpinTime(200);

inline void Relax()
{
#if defined(__SSE2__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

/// Spins until `done()` or SpinTime has passed; true if done.
template <class Done>
bool SpinUntil(const Done& done)
{
  const auto until = std::chrono::steady_clock::now() + SpinTime;
  for (unsigned k = 1;; ++k)
  {
    if (done())
    {
      return true;
    }
    Relax();
    if ((k & 63) == 0 && std::chrono::steady_clock::now() > until)
    {
      return false;
    }
  }
}
} // namespace

WorkerPool::WorkerPool(int threads)
{
  try
  {
    this->Workers.reserve(static_cast<size_t>(std::max(0, threads - 1)));
    for (int k = 1; k < threads; ++k)
    {
      this->Workers.emplace_back([this]() { this->Work(); });
    }
  }
  catch (...)
  {
    this->Join(); // the workers started (a thread the system refused: no pool)
    throw;
  }
}

WorkerPool::~WorkerPool()
{
  this->Join();
}

bool WorkerPool::InsideTask()
{
  return InTask;
}

void WorkerPool::Join()
{
  {
    std::lock_guard<std::mutex> lock(this->Lock);
    this->Stop = true;
    this->Stopping.store(true, std::memory_order_relaxed);
  }
  this->Wake.notify_all();
  for (std::thread& t : this->Workers)
  {
    t.join();
  }
  this->Workers.clear();
}

TaskRunner WorkerPool::Runner(int tasks)
{
  TaskRunner runner;
  runner.Tasks = tasks;
  runner.Run = [this](int count, const std::function<void(int)>& task) { this->Run(count, task); };
  return runner;
}

void WorkerPool::Keep(std::exception_ptr failure)
{
  std::lock_guard<std::mutex> lock(this->FailureLock);
  if (!this->Failure)
  {
    this->Failure = failure;
  }
}

void WorkerPool::Take(const std::function<void(int)>* task, int count)
{
  const TaskScope scope;
  for (int i = this->Next.fetch_add(1, std::memory_order_relaxed); i < count;
       i = this->Next.fetch_add(1, std::memory_order_relaxed))
  {
    try
    {
      (*task)(i);
    }
    catch (...)
    {
      this->Keep(std::current_exception());
    }
    // The last task's end wakes a caller waiting asleep (it set
    // CallerWaiting under Lock before it looked at Finished).
    if (this->Finished.fetch_add(1, std::memory_order_acq_rel) + 1 == count)
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      if (this->CallerWaiting)
      {
        this->Done.notify_one();
      }
    }
  }
}

void WorkerPool::Work()
{
  std::uint64_t seen = 0;
  for (;;)
  {
    SpinUntil([&]() {
      return this->Published.load(std::memory_order_acquire) != seen ||
        this->Stopping.load(std::memory_order_relaxed);
    });
    std::unique_lock<std::mutex> lock(this->Lock);
    if (this->Generation == seen && !this->Stop)
    {
      ++this->Sleeping;
      this->Wake.wait(lock, [&]() { return this->Generation != seen || this->Stop; });
      --this->Sleeping;
    }
    if (this->Stop)
    {
      return;
    }
    // The job as published (it may be over already: then no task is left
    // to take, and its function is never called).
    seen = this->Generation;
    const std::function<void(int)>* task = this->Task;
    const int count = this->Count;
    ++this->Inside;
    lock.unlock();
    this->Take(task, count);
    lock.lock();
    --this->Inside;
  }
}

void WorkerPool::Run(int count, const std::function<void(int)>& task)
{
  if (count <= 0)
  {
    return;
  }
  if (count == 1)
  {
    task(0);
    return;
  }
  if (this->Workers.empty() || InTask || !this->Running.try_lock())
  {
    // In turn on this thread (as tasks of this pool: a Run inside runs in
    // turn too), every task even after one threw, as the workers would.
    const TaskScope scope;
    std::exception_ptr failure;
    for (int i = 0; i < count; ++i)
    {
      try
      {
        task(i);
      }
      catch (...)
      {
        failure = failure ? failure : std::current_exception();
      }
    }
    if (failure)
    {
      std::rethrow_exception(failure);
    }
    return;
  }
  std::lock_guard<std::mutex> running(this->Running, std::adopt_lock);
  {
    std::unique_lock<std::mutex> lock(this->Lock);
    // A worker still inside the last job is only finding no task left: the
    // job's fields change once it is out.
    while (this->Inside > 0)
    {
      lock.unlock();
      std::this_thread::yield();
      lock.lock();
    }
    {
      std::lock_guard<std::mutex> failure(this->FailureLock);
      this->Failure = nullptr;
    }
    this->Task = &task;
    this->Count = count;
    this->Next.store(0, std::memory_order_relaxed);
    this->Finished.store(0, std::memory_order_relaxed);
    ++this->Generation;
    this->Published.store(this->Generation, std::memory_order_release);
    if (this->Sleeping > 0)
    {
      this->Wake.notify_all();
    }
  }
  this->Take(&task, count);
  auto finished = [&]() { return this->Finished.load(std::memory_order_acquire) >= count; };
  if (!SpinUntil(finished))
  {
    std::unique_lock<std::mutex> lock(this->Lock);
    this->CallerWaiting = true;
    this->Done.wait(lock, finished);
    this->CallerWaiting = false;
  }
  std::exception_ptr failure;
  {
    std::lock_guard<std::mutex> lock(this->FailureLock);
    failure = this->Failure;
    this->Failure = nullptr;
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
}
} // namespace mp
