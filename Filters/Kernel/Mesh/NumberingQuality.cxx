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
 * The sampled cells' points: a bit per point, and each marked point's rank
 * among them (its slot in CellsAround), from the marks before its word.
 */
struct MarkedPoints
{
  std::vector<std::uint64_t> Bits;
  std::vector<Index> Before; ///< per word, the marked points in the words before it
  Index Count = 0;

  bool Has(Index p) const { return (this->Bits[static_cast<size_t>(p >> 6)] >> (p & 63)) & 1; }
  Index Rank(Index p) const
  {
    const std::uint64_t below = (std::uint64_t(1) << (p & 63)) - 1;
    return this->Before[static_cast<size_t>(p >> 6)] +
      __builtin_popcountll(this->Bits[static_cast<size_t>(p >> 6)] & below);
  }
};

MarkedPoints MarkSampledPoints(const MeshView& mesh, Index samples)
{
  MarkedPoints marked;
  marked.Bits.assign(static_cast<size_t>(mesh.NumberOfPoints / 64 + 1), 0);
  const int corners = mesh.CornersPerCell();
  for (Index s = 0; s < samples; ++s)
  {
    const CellCorners ids = mesh.Cell(SampledCell(mesh.NumberOfCells, s, samples));
    for (int k = 0; k < corners; ++k)
    {
      marked.Bits[static_cast<size_t>(ids[k] >> 6)] |= std::uint64_t(1) << (ids[k] & 63);
    }
  }
  marked.Before.resize(marked.Bits.size());
  for (size_t w = 0; w < marked.Bits.size(); ++w)
  {
    marked.Before[w] = marked.Count;
    marked.Count += __builtin_popcountll(marked.Bits[w]);
  }
  return marked;
}

/**
 * The cells around the marked points, grouped by point (by rank), each
 * point's cells in increasing order, with the corners of every cell met:
 * the neighbour test reads them here, not in the connectivity, where the
 * cells around a point of a mesh numbered without order lie far apart.
 */
struct CellsAround
{
  std::vector<Index> Start; ///< point of rank r: entries Start[r] .. Start[r + 1]
  std::vector<Index> Cell;  ///< per entry, the cell
  std::vector<Index> Slot;  ///< per entry, where its corners start in Corners
  std::vector<Index> Corners;
};

/// One task's part of CellsAround: (rank, cell, slot) in cell order, and
/// the corners of its cells (slots from 0).
struct FoundCells
{
  std::vector<Index> Rank;
  std::vector<Index> Cell;
  std::vector<Index> Slot;
  std::vector<Index> Corners;
};

/// The marked points of cells [begin, end), `ids` the connectivity.
template <class Id>
void FindMarked(
  const Id* ids, int corners, Index begin, Index end, const MarkedPoints& marked, FoundCells& found)
{
  for (Index c = begin; c < end; ++c)
  {
    const Id* cell = ids + c * corners;
    bool any = false;
    for (int k = 0; k < corners; ++k)
    {
      any |= marked.Has(static_cast<Index>(cell[k]));
    }
    if (!any)
    {
      continue;
    }
    const Index slot = static_cast<Index>(found.Corners.size());
    for (int k = 0; k < corners; ++k)
    {
      const Index p = static_cast<Index>(cell[k]);
      found.Corners.push_back(p);
      if (marked.Has(p))
      {
        found.Rank.push_back(marked.Rank(p));
        found.Cell.push_back(c);
        found.Slot.push_back(slot);
      }
    }
  }
}

/**
 * CellsAround from one pass over the connectivity in `runner`'s tasks,
 * each keeping its range's entries, then placed by rank in range order
 * (a counting sort, stable: each point's cells in increasing order,
 * whatever the number of tasks).
 */
CellsAround CellsAroundMarked(
  const MeshView& mesh, const MarkedPoints& marked, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  const int corners = mesh.CornersPerCell();
  const int tasks = runner.TasksFor(n, 16384);
  std::vector<FoundCells> found(static_cast<size_t>(tasks));
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
  });
  CellsAround around;
  around.Start.assign(static_cast<size_t>(marked.Count) + 1, 0);
  for (const FoundCells& part : found)
  {
    for (Index r : part.Rank)
    {
      ++around.Start[static_cast<size_t>(r) + 1];
    }
  }
  for (size_t r = 0; r + 1 < around.Start.size(); ++r)
  {
    around.Start[r + 1] += around.Start[r];
  }
  around.Cell.resize(static_cast<size_t>(around.Start.back()));
  around.Slot.resize(around.Cell.size());
  std::vector<Index> next(around.Start.begin(), around.Start.end() - 1);
  for (const FoundCells& part : found)
  {
    const Index base = static_cast<Index>(around.Corners.size());
    for (size_t e = 0; e < part.Rank.size(); ++e)
    {
      const size_t at = static_cast<size_t>(next[static_cast<size_t>(part.Rank[e])]++);
      around.Cell[at] = part.Cell[e];
      around.Slot[at] = base + part.Slot[e];
    }
    around.Corners.insert(around.Corners.end(), part.Corners.begin(), part.Corners.end());
  }
  return around;
}

/// How many of the corners `a` the corners `b` share (`corners` each).
int SharedCorners(const CellCorners& a, const Index* b, int corners)
{
  int shared = 0;
  for (int i = 0; i < corners; ++i)
  {
    for (int j = 0; j < corners; ++j)
    {
      shared += a[i] == b[j];
    }
  }
  return shared;
}

/// |c - o| for each cell o across a face of the sampled cells, each once.
std::vector<Index> NeighbourDistances(
  const MeshView& mesh, Index samples, const MarkedPoints& marked, const CellsAround& around)
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
      const size_t r = static_cast<size_t>(marked.Rank(ids[k]));
      for (Index e = around.Start[r]; e < around.Start[r + 1]; ++e)
      {
        const Index o = around.Cell[static_cast<size_t>(e)];
        const Index* oc = around.Corners.data() + around.Slot[static_cast<size_t>(e)];
        if (o != c && SharedCorners(ids, oc, corners) == corners - 1)
        {
          neighbours.push_back(o);
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
  const MarkedPoints marked = MarkSampledPoints(mesh, samples);
  const std::vector<Index> distances =
    NeighbourDistances(mesh, samples, marked, CellsAroundMarked(mesh, marked, runner));
  const double far = NumberingQuality::FarDistance * std::pow(static_cast<double>(n), layer);
  const auto count = std::count_if(
    distances.begin(), distances.end(), [far](Index d) { return static_cast<double>(d) > far; });
  quality.FarNeighbours =
    distances.empty() ? 0.0 : static_cast<double>(count) / static_cast<double>(distances.size());
  return quality;
}

} // namespace mp
