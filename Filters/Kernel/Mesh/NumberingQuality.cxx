// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/NumberingQuality.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace mp
{
namespace
{
/// Sampled cell s of n cells sampled `samples` times.
Index SampledCell(Index n, Index s, Index samples)
{
  return n * s / samples;
}

/// The value at fraction q (0..1] of the sorted `values` (reordered), or 0.
double Quantile(std::vector<Index>& values, double q)
{
  if (values.empty())
  {
    return 0.0;
  }
  const auto at = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + at, values.end());
  return static_cast<double>(values[at]);
}

/**
 * The sampled cells: their corners, a bit per point for the points they
 * use, and per such point (by its rank among the marked points, from the
 * marks before its word) the samples that use it.
 */
struct Samples
{
  Index Count = 0;
  int Corners = 0;
  std::vector<Index> Ids; ///< sample s's corners at s * Corners
  std::vector<std::uint64_t> Bits;
  std::vector<Index> Before; ///< per word, the marked points in the words before it
  std::vector<Index> Start;  ///< marked point of rank r: UsedBy[Start[r] .. Start[r + 1])
  std::vector<Index> UsedBy; ///< samples, increasing for each point

  bool Marked(Index p) const { return (this->Bits[static_cast<size_t>(p >> 6)] >> (p & 63)) & 1; }
  Index Rank(Index p) const
  {
    const std::uint64_t below = (std::uint64_t(1) << (p & 63)) - 1;
    return this->Before[static_cast<size_t>(p >> 6)] +
      __builtin_popcountll(this->Bits[static_cast<size_t>(p >> 6)] & below);
  }
};

Samples SampleCells(const MeshView& mesh, Index count)
{
  Samples samples;
  samples.Count = count;
  samples.Corners = mesh.CornersPerCell();
  const int corners = samples.Corners;
  samples.Ids.resize(static_cast<size_t>(count * corners));
  samples.Bits.assign(static_cast<size_t>(mesh.NumberOfPoints / 64 + 1), 0);
  for (Index s = 0; s < count; ++s)
  {
    const CellCorners ids = mesh.Cell(SampledCell(mesh.NumberOfCells, s, count));
    for (int k = 0; k < corners; ++k)
    {
      samples.Ids[static_cast<size_t>(s * corners + k)] = ids[k];
      samples.Bits[static_cast<size_t>(ids[k] >> 6)] |= std::uint64_t(1) << (ids[k] & 63);
    }
  }
  Index marked = 0;
  samples.Before.resize(samples.Bits.size());
  for (size_t w = 0; w < samples.Bits.size(); ++w)
  {
    samples.Before[w] = marked;
    marked += __builtin_popcountll(samples.Bits[w]);
  }
  // The samples of each marked point, by a counting sort (samples in order).
  samples.Start.assign(static_cast<size_t>(marked) + 1, 0);
  for (Index p : samples.Ids)
  {
    ++samples.Start[static_cast<size_t>(samples.Rank(p)) + 1];
  }
  for (size_t r = 0; r + 1 < samples.Start.size(); ++r)
  {
    samples.Start[r + 1] += samples.Start[r];
  }
  samples.UsedBy.resize(samples.Ids.size());
  std::vector<Index> next(samples.Start.begin(), samples.Start.end() - 1);
  for (Index s = 0; s < count; ++s)
  {
    for (int k = 0; k < corners; ++k)
    {
      const Index p = samples.Ids[static_cast<size_t>(s * corners + k)];
      samples.UsedBy[static_cast<size_t>(next[static_cast<size_t>(samples.Rank(p))]++)] = s;
    }
  }
  return samples;
}

/**
 * Whether cell `o` (its corners) lies across a face of sample s (another
 * cell with all of s's corners but one) and its corner k is the first of
 * its corners that s has: each neighbour is then found once, through the
 * first marked point it shares with s, not once per shared point.
 */
template <class Id>
bool FirstAcrossAFace(const Samples& samples, Index s, const Id* o, int k)
{
  const int corners = samples.Corners;
  const Index* a = samples.Ids.data() + s * corners;
  int shared = 0;
  int first = corners;
  for (int j = corners - 1; j >= 0; --j)
  {
    int here = 0;
    for (int i = 0; i < corners; ++i)
    {
      here += a[i] == static_cast<Index>(o[j]);
    }
    shared += here;
    first = here > 0 ? j : first;
  }
  return shared == corners - 1 && first == k;
}

/**
 * (sample, cell) for the cells of [begin, end) across a face of a sample,
 * `ids` the connectivity. A face neighbour shares a marked point with the sample, so
 * only the cells using a marked point are tested, against the samples
 * that use that point, with the corners just read: no cell is read at
 * random.
 */
template <class Id>
void FindNeighbours(const Id* ids, const Samples& samples, Index begin, Index end, Index n,
  std::vector<std::pair<Index, Index>>& found)
{
  const int corners = samples.Corners;
  for (Index c = begin; c < end; ++c)
  {
    const Id* cell = ids + c * corners;
    bool any = false;
    for (int k = 0; k < corners; ++k)
    {
      any |= samples.Marked(static_cast<Index>(cell[k]));
    }
    for (int k = 0; any && k < corners; ++k)
    {
      const Index p = static_cast<Index>(cell[k]);
      if (!samples.Marked(p))
      {
        continue;
      }
      const size_t r = static_cast<size_t>(samples.Rank(p));
      for (Index e = samples.Start[r]; e < samples.Start[r + 1]; ++e)
      {
        const Index s = samples.UsedBy[static_cast<size_t>(e)];
        if (SampledCell(n, s, samples.Count) != c && FirstAcrossAFace(samples, s, cell, k))
        {
          found.emplace_back(s, c);
        }
      }
    }
  }
}

/**
 * |c - o| for each cell o across a face of each sampled cell c, each once:
 * one pass over the connectivity (FindNeighbours, in `runner`'s tasks),
 * then the (sample, cell) pairs sorted and their repeats dropped (the same
 * distances whatever the number of tasks).
 */
std::vector<Index> NeighbourDistances(
  const MeshView& mesh, const Samples& samples, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  const int tasks = runner.TasksFor(n, 16384);
  std::vector<std::vector<std::pair<Index, Index>>> found(static_cast<size_t>(tasks));
  runner.RunAll(tasks, [&](int t) {
    const Index begin = RangeBegin(n, t, tasks);
    const Index end = RangeBegin(n, t + 1, tasks);
    if (mesh.Connectivity32)
    {
      FindNeighbours(mesh.Connectivity32, samples, begin, end, n, found[t]);
    }
    else
    {
      FindNeighbours(mesh.Connectivity, samples, begin, end, n, found[t]);
    }
  });
  std::vector<std::pair<Index, Index>> pairs;
  for (const auto& part : found)
  {
    pairs.insert(pairs.end(), part.begin(), part.end());
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<Index> distances;
  distances.reserve(pairs.size());
  for (const auto& pair : pairs)
  {
    const Index c = SampledCell(n, pair.first, samples.Count);
    const Index o = pair.second;
    distances.push_back(o > c ? o - c : c - o);
  }
  return distances;
}
} // namespace

NumberingQuality MeasureNumbering(const MeshView& mesh, const TaskRunner& runner, Index samples)
{
  NumberingQuality quality;
  const Index n = mesh.NumberOfCells;
  const Index np = mesh.NumberOfPoints;
  if (n < 2 || np < 2 || samples < 1)
  {
    return quality;
  }
  samples = std::min(samples, n);
  const int corners = mesh.CornersPerCell();
  const double layer = (mesh.CellDimension - 1.0) / mesh.CellDimension;
  std::vector<Index> spread(static_cast<size_t>(samples));
  for (Index s = 0; s < samples; ++s)
  {
    const CellCorners ids = mesh.Cell(SampledCell(n, s, samples));
    Index low = ids[0];
    Index high = ids[0];
    for (int k = 1; k < corners; ++k)
    {
      low = std::min(low, ids[k]);
      high = std::max(high, ids[k]);
    }
    spread[s] = high - low;
  }
  quality.PointSpread = Quantile(spread, 0.5) / std::pow(static_cast<double>(np), layer);
  const std::vector<Index> distances = NeighbourDistances(mesh, SampleCells(mesh, samples), runner);
  const double far = NumberingQuality::FarDistance * std::pow(static_cast<double>(n), layer);
  const auto count = std::count_if(
    distances.begin(), distances.end(), [far](Index d) { return static_cast<double>(d) > far; });
  quality.FarNeighbours =
    distances.empty() ? 0.0 : static_cast<double>(count) / static_cast<double>(distances.size());
  return quality;
}

} // namespace mp
