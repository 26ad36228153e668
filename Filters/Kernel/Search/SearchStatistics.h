// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SearchStatistics.h
 * @brief How pairs are searched, and what a search counted.
 */
#ifndef MeshProjection_Kernel_SearchStatistics_h
#define MeshProjection_Kernel_SearchStatistics_h

#include "Mesh/MeshView.h"

namespace mp
{
/// How intersecting cell pairs are found.
enum class SearchMethod
{
  AdvancingFront = 0, ///< Gander & Japhet's front over cell neighbours: linear complexity
  BruteForce = 1      ///< every target cell against every source cell: the O(n m) oracle
};

/// Counters filled by a pair search; useful in tests, benchmarks and summaries.
struct SearchStatistics
{
  Index IntersectionTests = 0;  ///< calls of the cell-cell intersection
  Index TouchingPairs = 0;      ///< pairs whose closed cells meet (possibly in a point or segment)
  Index Pieces = 0;             ///< pairs whose intersection has positive measure
  Index LocatorQueries = 0;     ///< candidate look-ups in the locator (seeds and re-seeds)
  Index FullLocatorQueries = 0; ///< of which among all source cells (the others: boundary cells)
  /// Target cells that met no boundary cell nearby, found outside the
  /// source by a ray (CandidateLocator::Outside) instead of a full query.
  Index OutsideCells = 0;
  Index SeedWalks = 0;    ///< walks through the source toward an unseeded target cell
  Index WalkRestarts = 0; ///< of those stopped on the way, made again from a sampled source cell
  Index WalkSteps = 0;    ///< source cells those walks (and their restarts) went through
  Index DegenerateTargetCells = 0; ///< target cells of zero measure, skipped
  /// Source cells of zero measure, skipped: those the front met (all, for
  /// the brute force); unmet ones could not have mattered.
  Index DegenerateSourceCells = 0;

  /// Adds the counts of another search (a concurrent range) to these,
  /// except DegenerateSourceCells, which the caller de-duplicates.
  SearchStatistics& operator+=(const SearchStatistics& o)
  {
    this->IntersectionTests += o.IntersectionTests;
    this->TouchingPairs += o.TouchingPairs;
    this->Pieces += o.Pieces;
    this->LocatorQueries += o.LocatorQueries;
    this->FullLocatorQueries += o.FullLocatorQueries;
    this->OutsideCells += o.OutsideCells;
    this->SeedWalks += o.SeedWalks;
    this->WalkRestarts += o.WalkRestarts;
    this->WalkSteps += o.WalkSteps;
    this->DegenerateTargetCells += o.DegenerateTargetCells;
    return *this;
  }
};
} // namespace mp

#endif
