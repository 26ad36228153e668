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

/// A bit per point: those of the sampled cells set.
std::vector<std::uint64_t> MarkSampledPoints(const MeshView& mesh, Index samples)
{
  std::vector<std::uint64_t> marked(static_cast<size_t>(mesh.NumberOfPoints / 64 + 1), 0);
  const int corners = mesh.CornersPerCell();
  for (Index s = 0; s < samples; ++s)
  {
    const CellCorners ids = mesh.Cell(SampledCell(mesh.NumberOfCells, s, samples));
    for (int k = 0; k < corners; ++k)
    {
      marked[static_cast<size_t>(ids[k] >> 6)] |= std::uint64_t(1) << (ids[k] & 63);
    }
  }
  return marked;
}

/// (point, cell) for the marked points of cells [begin, end), `ids` the connectivity.
template <class Id>
void FindMarked(const Id* ids, int corners, Index begin, Index end,
  const std::vector<std::uint64_t>& marked, std::vector<std::pair<Index, Index>>& found)
{
  const std::uint64_t* bits = marked.data();
  auto isMarked = [bits](Index p) { return (bits[p >> 6] >> (p & 63)) & 1; };
  for (Index c = begin; c < end; ++c)
  {
    const Id* cell = ids + c * corners;
    std::uint64_t any = 0;
    for (int k = 0; k < corners; ++k)
    {
      any |= isMarked(static_cast<Index>(cell[k]));
    }
    for (int k = 0; any && k < corners; ++k)
    {
      if (isMarked(static_cast<Index>(cell[k])))
      {
        found.emplace_back(static_cast<Index>(cell[k]), c);
      }
    }
  }
}

/**
 * (point, cell) for every marked point of every cell, sorted: the cells
 * around each marked point. One pass over the connectivity, each task
 * keeping and sorting its range's pairs, then the sorted parts merged in
 * range order (the one sorted list, whatever the number of tasks).
 */
std::vector<std::pair<Index, Index>> CellsAroundMarked(
  const MeshView& mesh, const std::vector<std::uint64_t>& marked, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  const int corners = mesh.CornersPerCell();
  const int tasks = runner.TasksFor(n, 16384);
  std::vector<std::vector<std::pair<Index, Index>>> found(static_cast<size_t>(tasks));
  runner.RunAll(tasks, [&](int t) {
    const Index begin = RangeBegin(n, t, tasks);
    const Index end = RangeBegin(n, t + 1, tasks);
    if (mesh.Connectivity32)
    {
      FindMarked(mesh.Connectivity32, corners, begin, end, marked, found[t]);
    }
    else
    {
      FindMarked(mesh.Connectivity, corners, begin, end, marked, found[t]);
    }
    std::sort(found[t].begin(), found[t].end());
  });
  std::vector<std::pair<Index, Index>> around;
  for (const auto& part : found)
  {
    const auto middle = static_cast<std::ptrdiff_t>(around.size());
    around.insert(around.end(), part.begin(), part.end());
    std::inplace_merge(around.begin(), around.begin() + middle, around.end());
  }
  return around;
}

/// How many of cell a's corners cell b has.
int SharedCorners(const MeshView& mesh, Index a, Index b)
{
  const int corners = mesh.CornersPerCell();
  const CellCorners x = mesh.Cell(a);
  const CellCorners y = mesh.Cell(b);
  int shared = 0;
  for (int i = 0; i < corners; ++i)
  {
    for (int j = 0; j < corners; ++j)
    {
      shared += x[i] == y[j];
    }
  }
  return shared;
}

/// |c - o| for each cell o across a face of the sampled cells, each once.
std::vector<Index> NeighbourDistances(
  const MeshView& mesh, Index samples, const std::vector<std::pair<Index, Index>>& around)
{
  const int corners = mesh.CornersPerCell();
  std::vector<Index> distances;
  std::vector<Index> neighbours;
  for (Index s = 0; s < samples; ++s)
  {
    const Index c = SampledCell(mesh.NumberOfCells, s, samples);
    const CellCorners ids = mesh.Cell(c);
    neighbours.clear();
    for (int k = 0; k < corners; ++k)
    {
      auto at = std::lower_bound(around.begin(), around.end(), std::make_pair(ids[k], Index(0)));
      for (; at != around.end() && at->first == ids[k]; ++at)
      {
        if (at->second != c && SharedCorners(mesh, c, at->second) == corners - 1)
        {
          neighbours.push_back(at->second);
        }
      }
    }
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    for (Index o : neighbours)
    {
      distances.push_back(o > c ? o - c : c - o);
    }
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
  const std::vector<Index> distances = NeighbourDistances(
    mesh, samples, CellsAroundMarked(mesh, MarkSampledPoints(mesh, samples), runner));
  const double far = NumberingQuality::FarDistance * std::pow(static_cast<double>(n), layer);
  const auto count = std::count_if(
    distances.begin(), distances.end(), [far](Index d) { return static_cast<double>(d) > far; });
  quality.FarNeighbours =
    distances.empty() ? 0.0 : static_cast<double>(count) / static_cast<double>(distances.size());
  return quality;
}

} // namespace mp
