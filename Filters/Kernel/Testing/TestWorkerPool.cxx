// SPDX-License-Identifier: BSD-3-Clause
// The filter's threads (Mesh/WorkerPool.h): every task of a job runs once,
// jobs follow each other within microseconds or after the workers fell
// asleep, a task's exception reaches the caller, calls from inside a task
// or from a second thread run in turn, and sums come out as in one thread.
#include "Mesh/WorkerPool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace
{
/// Runs `count` tasks on `pool`, each adding one to its own counter, and
/// checks that each ran exactly once.
void EachOnce(mp::WorkerPool& pool, int count)
{
  std::vector<std::atomic<int>> runs(static_cast<size_t>(count));
  for (auto& r : runs)
  {
    r = 0;
  }
  pool.Run(count, [&](int k) { runs[static_cast<size_t>(k)].fetch_add(1); });
  for (int k = 0; k < count; ++k)
  {
    ASSERT_EQ(runs[static_cast<size_t>(k)].load(), 1) << "task " << k << " of " << count;
  }
}
} // namespace

TEST(WorkerPool, EveryTaskOnceInJobsInQuickSuccession)
{
  for (int threads : { 1, 2, 3, 5 })
  {
    mp::WorkerPool pool(threads);
    EXPECT_EQ(pool.Threads(), std::max(1, threads));
    for (int job = 0; job < 3000; ++job)
    {
      EachOnce(pool, 1 + job % 17);
    }
    pool.Run(0, [](int) { FAIL() << "a job of no task ran one"; });
  }
}

/// Whether two tasks that each wait for the other (up to 20 s) both finish:
/// only if the pool runs them at once.
static bool RunAtOnce(mp::WorkerPool& pool)
{
  std::atomic<int> arrived(0);
  std::atomic<bool> together(true);
  pool.Run(2, [&](int) {
    arrived.fetch_add(1);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (arrived.load() < 2)
    {
      if (std::chrono::steady_clock::now() > until)
      {
        together = false;
        return;
      }
      std::this_thread::yield();
    }
  });
  return together.load();
}

TEST(WorkerPool, TasksRunOnSeveralThreads)
{
  mp::WorkerPool pool(2);
  EXPECT_FALSE(mp::WorkerPool::InsideTask());
  EXPECT_TRUE(RunAtOnce(pool));
  EXPECT_FALSE(mp::WorkerPool::InsideTask());
}

TEST(WorkerPool, JobsAfterTheWorkersFellAsleepAndLongTasks)
{
  mp::WorkerPool pool(3);
  for (int job = 0; job < 4; ++job)
  {
    // Longer than the workers' spinning: they wait asleep, and are woken.
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EachOnce(pool, 6);
    // Tasks that outlast the caller's spinning: it waits asleep for the last.
    std::atomic<int> done(0);
    pool.Run(3, [&](int k) {
      if (k != 0)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(3));
      }
      done.fetch_add(1);
    });
    EXPECT_EQ(done.load(), 3);
  }
}

TEST(WorkerPool, AnExceptionReachesTheCallerOnceEveryTaskEnded)
{
  mp::WorkerPool pool(3);
  std::atomic<int> ran(0);
  EXPECT_THROW(pool.Run(9,
                 [&](int k) {
                   ran.fetch_add(1);
                   if (k % 4 == 1)
                   {
                     throw std::runtime_error("task failed");
                   }
                 }),
    std::runtime_error);
  EXPECT_EQ(ran.load(), 9);
  EachOnce(pool, 9); // and the pool goes on, its caller not left "inside a task"
  EXPECT_FALSE(mp::WorkerPool::InsideTask());
  EXPECT_TRUE(RunAtOnce(pool));
  // A job run in turn (from inside a task) runs every task too before its
  // exception goes on.
  std::atomic<int> inner(0);
  EXPECT_THROW(pool.Run(2,
                 [&](int) {
                   EXPECT_TRUE(mp::WorkerPool::InsideTask());
                   pool.Run(3, [&](int k) {
                     inner.fetch_add(1);
                     if (k == 0)
                     {
                       throw std::runtime_error("inner task failed");
                     }
                   });
                 }),
    std::runtime_error);
  EXPECT_EQ(inner.load(), 6);
  EXPECT_TRUE(RunAtOnce(pool));
}

TEST(WorkerPool, NestedAndConcurrentCallsRunInTurn)
{
  mp::WorkerPool pool(3);
  // A job inside a task: its tasks on that task's thread.
  std::atomic<int> inner(0);
  pool.Run(4, [&](int) {
    const std::thread::id self = std::this_thread::get_id();
    pool.Run(5, [&](int) {
      EXPECT_EQ(std::this_thread::get_id(), self);
      inner.fetch_add(1);
    });
  });
  EXPECT_EQ(inner.load(), 20);
  // Two threads using the pool at once: every task of both runs once.
  std::vector<std::thread> callers;
  std::atomic<int> total(0);
  for (int c = 0; c < 2; ++c)
  {
    callers.emplace_back([&]() {
      for (int job = 0; job < 500; ++job)
      {
        std::vector<std::atomic<int>> runs(7);
        for (auto& r : runs)
        {
          r = 0;
        }
        pool.Run(7, [&](int k) { runs[static_cast<size_t>(k)].fetch_add(1); });
        for (auto& r : runs)
        {
          total.fetch_add(r.load() == 1 ? 1 : 1000);
        }
      }
    });
  }
  for (std::thread& t : callers)
  {
    t.join();
  }
  EXPECT_EQ(total.load(), 2 * 500 * 7);
}

TEST(WorkerPool, RunnerSumsAsInOneThread)
{
  mp::WorkerPool pool(3);
  const mp::TaskRunner runner = pool.Runner(3);
  EXPECT_EQ(runner.Tasks, 3);
  const mp::Index n = 100000;
  std::vector<double> x(static_cast<size_t>(n));
  for (mp::Index i = 0; i < n; ++i)
  {
    x[static_cast<size_t>(i)] = 1.0 / static_cast<double>(i + 1);
  }
  auto sum = [&](mp::Index begin, mp::Index end) {
    double s = 0.0;
    for (mp::Index i = begin; i < end; ++i)
    {
      s += x[static_cast<size_t>(i)];
    }
    return s;
  };
  // The same ranges added in the same order: the same bits as one thread
  // running the ranges in turn.
  double inTurn = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    inTurn += sum(mp::RangeBegin(n, k, 3), mp::RangeBegin(n, k + 1, 3));
  }
  for (int repeat = 0; repeat < 50; ++repeat)
  {
    EXPECT_EQ(runner.ForRanges(n, sum), inTurn);
  }
}
