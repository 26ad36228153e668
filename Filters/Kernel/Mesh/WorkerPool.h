// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file WorkerPool.h
 * @brief Threads kept for many short parallel loops: a TaskRunner's Run
 *        whose workers are started once, not once per loop.
 *
 * The kernel's loops never start threads: they call the runner they are
 * given (Tasks.h). A runner that starts threads for every call pays for it
 * every time: VTK 9.2's STDThread backend starts a new set of threads for
 * each vtkSMPTools::For; a projection runs many such loops, short ones
 * among them (each of the solver's iterations is three), so the starts
 * add up. A WorkerPool keeps `threads - 1` workers for its lifetime; the
 * caller of Run is the last thread. Between loops the workers wait
 * spinning for a short while (loops follow each other within microseconds
 * in the solver), then asleep.
 */
#ifndef MeshProjection_Kernel_WorkerPool_h
#define MeshProjection_Kernel_WorkerPool_h

#include "Mesh/Tasks.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace mp
{
class WorkerPool
{
public:
  /// `threads` in all, the caller of Run included (1 or less: no workers).
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// The threads in all, the caller of Run included.
  int Threads() const { return static_cast<int>(this->Workers.size()) + 1; }

  /**
   * Runs task(0), ..., task(count - 1) on the workers and the calling
   * thread, each index once, and returns when all have returned. A call
   * from inside a task, or while another thread's call is running, runs
   * its tasks one after the other on its own thread. The first exception a
   * task throws is thrown again here, once every task has ended (either
   * way).
   */
  void Run(int count, const std::function<void(int)>& task);

  /// A runner of `tasks` concurrent tasks on this pool (which must outlive
  /// the runner's calls).
  TaskRunner Runner(int tasks);

  /// Whether this thread is running a task of a pool (where a loop had
  /// better run in turn than start threads of its own).
  static bool InsideTask();

private:
  void Work();
  /// Stops and joins the workers.
  void Join();
  /// Keeps `failure` unless an earlier one is kept.
  void Keep(std::exception_ptr failure);
  /// Takes and runs the current job's tasks until none is left.
  void Take(const std::function<void(int)>* task, int count);

  std::vector<std::thread> Workers;
  std::mutex Running; ///< held by the one Run that uses the workers

  // The current job, written by Run under Lock while no worker is inside
  // a job (Inside == 0); read by workers under Lock.
  std::mutex Lock;
  std::condition_variable Wake; ///< workers: a job, or the end
  std::condition_variable Done; ///< Run's caller: its job's last task ended
  const std::function<void(int)>* Task = nullptr;
  int Count = 0;
  std::uint64_t Generation = 0; ///< one more per job
  int Inside = 0;               ///< workers taking tasks of the current job
  int Sleeping = 0;             ///< workers waiting on Wake
  bool CallerWaiting = false;   ///< Run's caller waiting on Done
  bool Stop = false;
  // Lock-free mirrors for the workers' spinning and the job's progress.
  std::atomic<std::uint64_t> Published{ 0 };
  std::atomic<bool> Stopping{ false };
  std::atomic<int> Next{ 0 };     ///< next task index to take
  std::atomic<int> Finished{ 0 }; ///< tasks of the current job done
  std::mutex FailureLock;
  std::exception_ptr Failure;
};
} // namespace mp

#endif
