// SPDX-License-Identifier: BSD-3-Clause
// Runs the advancing front and the brute force on the same pair of meshes
// and compares them: the kernel tests' main oracle, for any intersector.
#ifndef MeshProjection_Testing_SearchComparison_h
#define MeshProjection_Testing_SearchComparison_h

#include "Search/PairSearch.h"
#include "Search/SearchStatistics.h"
#include "GeneratedMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <tuple>
#include <vector>

namespace mptest
{
/// Every (target, source, measure) the search visits.
template <class Intersector>
struct PairRecorder
{
  std::vector<std::tuple<Index, Index, double>> Pairs;
  template <class SourceCell> // Intersector::Cell, or a volume's for traces
  void operator()(
    const typename Intersector::Cell& t, const SourceCell& s, const typename Intersector::Piece& p)
  {
    this->Pairs.emplace_back(t.Id, s.Id, Intersector::Measure(p));
  }
};

template <class Intersector>
struct SearchComparison
{
  PairRecorder<Intersector> Front;
  PairRecorder<Intersector> Brute;
  mp::SearchStatistics FrontStats;
  mp::SearchStatistics BruteStats;

  SearchComparison(const TestMesh& target, const TestMesh& source)
  {
    mp::BoxGridLocator locator(source.View());
    mp::AdvancingFrontSearch<Intersector>(
      target.View(), source.View(), locator, this->Front, this->FrontStats);
    mp::BruteForceSearch<Intersector>(target.View(), source.View(), this->Brute, this->BruteStats);
    std::sort(this->Front.Pairs.begin(), this->Front.Pairs.end());
    std::sort(this->Brute.Pairs.begin(), this->Brute.Pairs.end());
  }

  /// Both searches found the same pairs. With a `minimum` (>= 0) only the
  /// pairs of a larger measure count: traces report cells that only touch
  /// the target as pairs without measure, to pass the front on, and a curve
  /// along an edge of the source has slivers of rounding size there; which
  /// of those a search meets depends on its path.
  void ExpectSamePairs(const std::string& what, double minimum = -1.0) const
  {
    if (minimum >= 0.0)
    {
      SearchComparison positive = *this;
      for (auto* pairs : { &positive.Front.Pairs, &positive.Brute.Pairs })
      {
        pairs->erase(std::remove_if(pairs->begin(), pairs->end(),
                       [minimum](const std::tuple<Index, Index, double>& p) {
                         return !(std::get<2>(p) > minimum);
                       }),
          pairs->end());
      }
      positive.ExpectSamePairs(what);
      return;
    }
    if (this->Front.Pairs.size() != this->Brute.Pairs.size())
    {
      std::vector<std::tuple<Index, Index, double>> missing;
      std::set_symmetric_difference(this->Front.Pairs.begin(), this->Front.Pairs.end(),
        this->Brute.Pairs.begin(), this->Brute.Pairs.end(), std::back_inserter(missing));
      for (size_t i = 0; i < missing.size() && i < 5; ++i)
      {
        ADD_FAILURE() << what << ": pair (" << std::get<0>(missing[i]) << ", "
                      << std::get<1>(missing[i]) << ") of measure " << std::get<2>(missing[i])
                      << " found by one search only";
      }
    }
    ASSERT_EQ(this->Front.Pairs.size(), this->Brute.Pairs.size()) << what;
    for (size_t i = 0; i < this->Front.Pairs.size(); ++i)
    {
      // Same pair, and bit-identical geometry: both call the same intersector.
      ASSERT_EQ(this->Front.Pairs[i], this->Brute.Pairs[i]) << what << " pair " << i;
    }
  }

  /// Per target cell, the summed measure of its pieces.
  std::vector<double> CoveredMeasure(const TestMesh& target) const
  {
    std::vector<double> measure(static_cast<size_t>(target.NumberOfCells()), 0.0);
    for (const auto& p : this->Front.Pairs)
      measure[std::get<0>(p)] += std::get<2>(p);
    return measure;
  }

  /// The pieces of every target cell add up to the cell (relative 1e-12 by default).
  void ExpectCompleteCover(
    const TestMesh& target, const std::string& what, double tolerance = 1e-12) const
  {
    const std::vector<double> measure = this->CoveredMeasure(target);
    for (Index c = 0; c < target.NumberOfCells(); ++c)
    {
      ASSERT_NEAR(measure[c], target.CellArea(c), tolerance * target.CellArea(c))
        << what << " cell " << c;
    }
  }
};
} // namespace mptest

#endif
