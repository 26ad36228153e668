// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Progress.h
 * @brief Progress and the user's stop, from any thread to the pipeline's.
 *
 * The GUI takes progress events only from the thread that runs the
 * pipeline, but with several SMP threads the task that reports need not
 * run there (VTK's STDThread backend runs every task on threads of its own;
 * the execution's WorkerScope on any of its threads). So a report from
 * another thread goes to a mailbox, and Watch() runs long work on a thread
 * of its own while the pipeline's thread waits and passes on what arrives.
 * The abort flag is read from any thread.
 */
#ifndef MeshProjection_Projection_Progress_h
#define MeshProjection_Projection_Progress_h

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

class vtkAlgorithm;

namespace mpvtk
{
class Progress
{
public:
  /// Reports for `filter`, whose pipeline runs on the calling thread.
  explicit Progress(vtkAlgorithm* filter);
  /// Reports `amount` of the whole execution (0 to 1); false when the user asked to stop.
  bool operator()(double amount);
  /**
   * Runs `work` (whose loops report through this object) so that its
   * progress reaches the pipeline's thread; an exception in `work` is
   * thrown again here.
   */
  void Watch(const std::function<void()>& work);

private:
  vtkAlgorithm* Filter;
  std::thread::id PipelineThread;
  std::mutex Lock;
  std::condition_variable Changed;
  double Reported = -1; ///< negative: nothing new
};

/// A share [From, From + Span) of the progress bar (one leaf's).
struct ProgressShare
{
  Progress* Bar = nullptr;
  double From = 0;
  double Span = 1;
  /// Reports `fraction` of this share; false when the user asked to stop.
  bool operator()(double fraction) const
  {
    return (*this->Bar)(this->From + this->Span * fraction);
  }
};
} // namespace mpvtk

#endif
