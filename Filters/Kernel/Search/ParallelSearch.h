// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ParallelSearch.h
 * @brief The pair search over ranges of target cells in concurrent tasks,
 *        and what a search needs of its inputs.
 *
 * Task k searches the target cells [cells k / n, cells (k + 1) / n) with a
 * front of its own (PairSearch.h: a front stays inside its range), its own
 * locator (CandidateLocator::NewForThread) and its own visitor; together the
 * tasks find exactly the pairs of one search over all cells.
 */
#ifndef MeshProjection_Kernel_ParallelSearch_h
#define MeshProjection_Kernel_ParallelSearch_h

#include "Mesh/Tasks.h"
#include "Search/CandidateLocator.h"
#include "Search/PairSearch.h"
#include "Search/SearchStatistics.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace mp
{
/// Whether `method` walks over face neighbours and asks a locator (the
/// front) or needs neither (the brute force).
inline bool SearchNeedsNeighbors(SearchMethod method)
{
  return method == SearchMethod::AdvancingFront;
}

/**
 * What a search needs of a mesh it searches: points and connectivity, and
 * for the front fewer than 2^31 cells and face neighbours. Returns an empty
 * string, or the reason (`name` says which mesh).
 */
inline std::string CheckSearchMesh(const MeshView& mesh, const char* name, SearchMethod method)
{
  const bool front = SearchNeedsNeighbors(method);
  if (mesh.NumberOfCells > 0 && (!mesh.Points || !mesh.HasConnectivity()))
  {
    return std::string(name) + ": missing points or connectivity";
  }
  if (front && mesh.NumberOfCells > std::numeric_limits<NeighborId>::max())
  {
    return std::string(name) + " has " + std::to_string(mesh.NumberOfCells) +
      " cells; the advancing front supports at most 2^31 - 1";
  }
  if (front && mesh.NumberOfCells > 0 && !mesh.Neighbors)
  {
    return std::string(name) + ": the advancing front needs cell neighbours";
  }
  return std::string();
}

/**
 * Searches target cells in visitors.size() ranges, range k visited by
 * visitors[k] (concurrently through `runner`). `locator` (the front's
 * seeds) may be null for the brute force. Statistics are summed in range
 * order; source cells of zero measure are counted once.
 */
template <class Intersector, class Visitor>
bool SearchInRanges(SearchMethod method, const MeshView& target, const MeshView& source,
  CandidateLocator* locator, const TaskRunner& runner, std::vector<Visitor>& visitors,
  SearchStatistics& statistics, const ProgressHook& progress = ProgressHook())
{
  const int tasks = static_cast<int>(visitors.size());
  const Index cells = target.NumberOfCells;
  std::vector<SearchStatistics> stats(static_cast<size_t>(tasks));
  std::vector<std::vector<Index>> degenerate(static_cast<size_t>(tasks));
  std::vector<std::unique_ptr<CandidateLocator>> locators(static_cast<size_t>(tasks));
  for (int k = 0; locator && tasks > 1 && k < tasks; ++k)
  {
    locators[k] = locator->NewForThread();
  }
  // With a progress hook, the searches poll every ProgressChunk target
  // cells: task 0 reports its share done, and every task stops once the
  // hook has asked to stop.
  std::atomic<bool> stop{ false };
  runner.RunAll(tasks, [&](int k) {
    const Index begin = RangeBegin(cells, k, tasks);
    const Index end = RangeBegin(cells, k + 1, tasks);
    std::function<bool(Index)> poll;
    if (progress)
    {
      poll = [&, k, begin, end](Index done) {
        if (k == 0 && !progress(static_cast<double>(done) / std::max<Index>(1, end - begin)))
        {
          stop = true;
        }
        return !stop.load(std::memory_order_relaxed);
      };
    }
    if (method == SearchMethod::AdvancingFront)
    {
      CandidateLocator& seeds = tasks > 1 ? *locators[k] : *locator;
      AdvancingFrontSearch<Intersector>(
        target, source, seeds, visitors[k], stats[k], begin, end, &degenerate[k], poll);
    }
    else
    {
      BruteForceSearch<Intersector>(
        target, source, visitors[k], stats[k], begin, end, &degenerate[k], poll);
    }
  });
  std::vector<Index> all;
  for (int k = 0; k < tasks; ++k)
  {
    statistics += stats[k];
    all.insert(all.end(), degenerate[k].begin(), degenerate[k].end());
  }
  std::sort(all.begin(), all.end());
  statistics.DegenerateSourceCells =
    static_cast<Index>(std::unique(all.begin(), all.end()) - all.begin());
  return !stop;
}
} // namespace mp

#endif
