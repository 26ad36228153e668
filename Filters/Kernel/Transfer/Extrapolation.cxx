// SPDX-License-Identifier: BSD-3-Clause
// Extrapolation beyond the source (Extrapolation.h): the target's graphs
// (rows for the functions to extend), the layers away from the valid
// functions, the creep fill and the nearest values.
#include "Transfer/Extrapolation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace mp
{
namespace
{
/// Compressed rows: per item, the entries listed by `visit(item, add)`.
template <class Visit>
void Incidence(Index items, Index targets, Visit visit, std::vector<Index>& start, std::vector<Index>& entries)
{
  start.assign(static_cast<size_t>(targets) + 1, 0);
  for (Index c = 0; c < items; ++c)
  {
    visit(c, [&](Index t) { ++start[static_cast<size_t>(t) + 1]; });
  }
  for (Index t = 0; t < targets; ++t)
  {
    start[t + 1] += start[t];
  }
  entries.resize(static_cast<size_t>(start.back()));
  std::vector<Index> next(start.begin(), start.end() - 1);
  for (Index c = 0; c < items; ++c)
  {
    visit(c, [&](Index t) { entries[static_cast<size_t>(next[static_cast<size_t>(t)]++)] = c; });
  }
}

/// The rows of `want`: neighbours(i, add) adds (neighbour, weight) terms, summed per neighbour.
template <class Neighbours>
void Rows(const std::vector<char>& want, Neighbours neighbours, FunctionGraph& graph)
{
  const Index n = static_cast<Index>(want.size());
  graph.Row.assign(static_cast<size_t>(n), -1);
  std::vector<double> sum(static_cast<size_t>(n), 0.0);
  std::vector<Index> used;
  for (Index i = 0; i < n; ++i)
  {
    if (!want[i])
    {
      continue;
    }
    graph.Row[i] = static_cast<Index>(graph.Start.size()) - 1;
    used.clear();
    neighbours(i, [&](Index k, double w) {
      if (k == i)
      {
        return;
      }
      if (sum[k] == 0.0)
      {
        used.push_back(k);
      }
      sum[k] += w;
    });
    for (Index k : used)
    {
      graph.Neighbors.push_back(k);
      graph.Weights.push_back(sum[k]);
      sum[k] = 0.0;
    }
    graph.Start.push_back(static_cast<Index>(graph.Neighbors.size()));
  }
}

/**
 * Per function, its layer: 0 valid, L the graph distance from the valid
 * ones, -1 not reached. On a distributed graph, rounds of local searches
 * with the smallest layers completed across parts until none changes.
 */
std::vector<Index> Layers(const FunctionGraph& graph, const std::vector<char>& valid, const SolverHooks& hooks)
{
  const Index n = graph.Size();
  const double none = std::numeric_limits<double>::infinity();
  std::vector<double> layer(static_cast<size_t>(n), none);
  for (Index i = 0; i < n; ++i)
  {
    layer[i] = valid[i] ? 0.0 : none;
  }
  for (;;)
  {
    // A search from the rows next to a known layer (unit steps, smallest first).
    using Entry = std::pair<double, Index>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> front;
    for (Index i = 0; i < n; ++i)
    {
      const Index r = graph.Row[i];
      for (Index q = r < 0 ? 0 : graph.Start[r]; r >= 0 && q < graph.Start[r + 1]; ++q)
      {
        layer[i] = std::min(layer[i], layer[graph.Neighbors[q]] + 1.0);
      }
      if (r >= 0 && layer[i] < none)
      {
        front.emplace(layer[i], i);
      }
    }
    while (!front.empty())
    {
      const Entry top = front.top();
      front.pop();
      const Index i = top.second;
      if (top.first > layer[i])
      {
        continue;
      }
      const Index r = graph.Row[i];
      for (Index q = graph.Start[r]; q < graph.Start[r + 1]; ++q)
      {
        const Index k = graph.Neighbors[q];
        if (graph.Row[k] >= 0 && layer[i] + 1.0 < layer[k])
        {
          layer[k] = layer[i] + 1.0;
          front.emplace(layer[k], k);
        }
      }
    }
    if (!hooks.ExchangeMinimum)
    {
      break;
    }
    std::vector<double> before(layer);
    hooks.ExchangeMinimum(layer.data(), 1);
    double more = 0.0;
    for (Index i = 0; i < n; ++i)
    {
      more += layer[i] < before[i] ? 1.0 : 0.0;
    }
    hooks.Reduce(&more, 1);
    if (more == 0.0)
    {
      break;
    }
  }
  std::vector<Index> out(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    out[i] = layer[i] == none ? -1 : static_cast<Index>(layer[i]);
  }
  return out;
}

/// Row i's weighted sums of its neighbours' values where use(k) (numerators, then the weight).
template <class Use>
void NeighbourSums(const FunctionGraph& graph, Index i, const double* values, int width, int offset, int nc,
  Use use, double* sums)
{
  std::fill(sums, sums + nc + 1, 0.0);
  const Index r = graph.Row[i];
  for (Index q = graph.Start[r]; q < graph.Start[r + 1]; ++q)
  {
    const Index k = graph.Neighbors[q];
    if (use(k))
    {
      const double w = graph.Weights[q];
      for (int m = 0; m < nc; ++m)
      {
        sums[m] += w * values[k * width + offset + m];
      }
      sums[nc] += w;
    }
  }
}

/**
 * The functions `which` take their neighbours' mean over those where
 * use(k). Alone, in place, in the order given; on a distributed graph the
 * sums go through full-length vectors, completed across parts first.
 */
template <class Use>
void MeanStep(const FunctionGraph& graph, const std::vector<Index>& which, Use use, double* values, int width,
  int offset, int nc, const SolverHooks& hooks)
{
  std::vector<double> sums(static_cast<size_t>(nc) + 1);
  if (!hooks.Exchange)
  {
    for (Index i : which)
    {
      NeighbourSums(graph, i, values, width, offset, nc, use, sums.data());
      for (int m = 0; sums[nc] > 0.0 && m < nc; ++m)
      {
        values[i * width + offset + m] = sums[m] / sums[nc];
      }
    }
    return;
  }
  const Index n = graph.Size();
  std::vector<double> all(static_cast<size_t>(n) * (nc + 1), 0.0);
  for (Index i : which)
  {
    NeighbourSums(graph, i, values, width, offset, nc, use, &all[static_cast<size_t>(i) * (nc + 1)]);
  }
  hooks.Exchange(all.data(), nc + 1);
  for (Index i : which)
  {
    const double* s = &all[static_cast<size_t>(i) * (nc + 1)];
    for (int m = 0; s[nc] > 0.0 && m < nc; ++m)
    {
      values[i * width + offset + m] = s[m] / s[nc];
    }
  }
}

/// The creep fill: layer by layer, then sweeps of neighbour means.
void CreepFill(const FunctionGraph& graph, const std::vector<Index>& layer, const std::vector<char>& todo,
  double* values, int width, int offset, int nc, const SolverHooks& hooks)
{
  // The functions of each layer (1, 2, ...); the number of layers is the
  // largest over the parts (a count of the functions beyond each, summed).
  std::vector<std::vector<Index>> layers;
  for (Index i = 0; i < graph.Size(); ++i)
  {
    if (todo[i])
    {
      layers.resize(std::max(layers.size(), static_cast<size_t>(layer[i])));
      layers[static_cast<size_t>(layer[i]) - 1].push_back(i);
    }
  }
  double count = static_cast<double>(layers.size());
  for (size_t L = 1; hooks.Reduce; ++L)
  {
    // (Sum of "this part has layer L" over the parts: 0 once no part has.)
    double has = L <= layers.size() ? 1.0 : 0.0;
    hooks.Reduce(&has, 1);
    if (has == 0.0)
    {
      count = static_cast<double>(L - 1);
      break;
    }
  }
  layers.resize(static_cast<size_t>(count));
  for (size_t L = 0; L < layers.size(); ++L)
  {
    const Index before = static_cast<Index>(L) + 1;
    MeanStep(graph, layers[L], [&](Index k) { return layer[k] >= 0 && layer[k] < before; }, values, width,
      offset, nc, hooks);
  }
  // Sweeps of neighbour means over all neighbours reached (the valid ones
  // held): towards the harmonic extension, each value still a mean of valid ones.
  std::vector<Index> all;
  for (const auto& ones : layers)
  {
    all.insert(all.end(), ones.begin(), ones.end());
  }
  for (int sweep = 0; sweep < 20; ++sweep)
  {
    MeanStep(graph, all, [&](Index k) { return layer[k] >= 0; }, values, width, offset, nc, hooks);
  }
}

/// The value of the nearest valid function along the graph (Dijkstra from all valid ones).
void Nearest(const FunctionGraph& graph, const std::vector<char>& valid, const std::vector<char>& todo,
  double* values, int width, int offset, int nc)
{
  const Index n = graph.Size();
  std::vector<double> distance(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  std::vector<Index> from(static_cast<size_t>(n), -1);
  using Entry = std::pair<double, Index>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> front;
  const double* x = graph.Positions.data();
  auto length = [x](Index a, Index b) {
    return std::sqrt((x[3 * a] - x[3 * b]) * (x[3 * a] - x[3 * b]) +
      (x[3 * a + 1] - x[3 * b + 1]) * (x[3 * a + 1] - x[3 * b + 1]) +
      (x[3 * a + 2] - x[3 * b + 2]) * (x[3 * a + 2] - x[3 * b + 2]));
  };
  // Seeds: the functions to fill next to valid ones (rows exist for those to fill only).
  for (Index i = 0; i < n; ++i)
  {
    const Index r = graph.Row[i];
    for (Index q = todo[i] ? graph.Start[r] : 0; todo[i] && q < graph.Start[r + 1]; ++q)
    {
      const Index k = graph.Neighbors[q];
      if (valid[k] && length(i, k) < distance[i])
      {
        distance[i] = length(i, k);
        from[i] = k;
      }
    }
    if (from[i] >= 0)
    {
      front.emplace(distance[i], i);
    }
  }
  while (!front.empty())
  {
    const Entry top = front.top();
    front.pop();
    const Index i = top.second;
    if (top.first > distance[i])
    {
      continue;
    }
    const Index r = graph.Row[i];
    for (Index q = graph.Start[r]; q < graph.Start[r + 1]; ++q)
    {
      const Index k = graph.Neighbors[q];
      if (todo[k] && distance[i] + length(i, k) < distance[k])
      {
        distance[k] = distance[i] + length(i, k);
        from[k] = from[i];
        front.emplace(distance[k], k);
      }
    }
  }
  for (Index i = 0; i < n; ++i)
  {
    for (int m = 0; todo[i] && from[i] >= 0 && m < nc; ++m)
    {
      values[i * width + offset + m] = values[from[i] * width + offset + m];
    }
  }
}
} // namespace

FunctionGraph PointGraph(const MeshView& mesh, const std::vector<char>& want)
{
  FunctionGraph graph;
  const int corners = mesh.CornersPerCell();
  std::vector<Index> start, cells;
  Incidence(mesh.NumberOfCells, mesh.NumberOfPoints, [&](Index c, auto add) {
    const CellCorners cell = mesh.Cell(c);
    for (int a = 0; a < corners; ++a)
    {
      add(cell[a]);
    }
  }, start, cells);
  Rows(want, [&](Index i, auto add) {
    for (Index q = start[i]; q < start[i + 1]; ++q)
    {
      const CellCorners cell = mesh.Cell(cells[static_cast<size_t>(q)]);
      for (int a = 0; a < corners; ++a)
      {
        add(cell[a], 1.0); // one more cell holds the edge
      }
    }
  }, graph);
  graph.Positions.assign(mesh.Points, mesh.Points + 3 * mesh.NumberOfPoints);
  return graph;
}

FunctionGraph CellGraph(const MeshView& mesh, const std::vector<char>& want)
{
  FunctionGraph graph;
  const Index parents = mesh.Parents();
  const int corners = mesh.CornersPerCell();
  std::vector<Index> pointStart, aroundPoint, parentStart, children;
  Incidence(mesh.NumberOfCells, mesh.NumberOfPoints, [&](Index c, auto add) {
    const CellCorners cell = mesh.Cell(c);
    for (int a = 0; a < corners; ++a)
    {
      add(cell[a]);
    }
  }, pointStart, aroundPoint);
  Incidence(mesh.NumberOfCells, parents, [&](Index c, auto add) { add(mesh.ParentOf(c)); }, parentStart, children);
  Rows(want, [&](Index p, auto add) {
    for (Index q = parentStart[p]; q < parentStart[p + 1]; ++q)
    {
      const CellCorners cell = mesh.Cell(children[static_cast<size_t>(q)]);
      for (int a = 0; a < corners; ++a)
      {
        for (Index r = pointStart[cell[a]]; r < pointStart[cell[a] + 1]; ++r)
        {
          add(mesh.ParentOf(aroundPoint[static_cast<size_t>(r)]), 1.0);
        }
      }
    }
  }, graph);
  graph.Positions.assign(3 * static_cast<size_t>(parents), 0.0);
  std::vector<double> count(static_cast<size_t>(parents), 0.0);
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const CellCorners cell = mesh.Cell(c);
    const Index parent = mesh.ParentOf(c);
    for (int a = 0; a < corners; ++a)
    {
      for (int d = 0; d < 3; ++d)
      {
        graph.Positions[3 * parent + d] += mesh.Point(cell[a])[d];
      }
      count[parent] += 1.0;
    }
  }
  for (Index p = 0; p < parents; ++p)
  {
    for (int d = 0; count[p] > 0.0 && d < 3; ++d)
    {
      graph.Positions[3 * p + d] /= count[p];
    }
  }
  return graph;
}

Index Extrapolate(const FunctionGraph& graph, const std::vector<char>& valid, double* values,
  int width, int offset, int nc, ExtrapolationMode mode, const SolverHooks& hooks,
  std::vector<char>& extrapolated)
{
  const Index n = graph.Size();
  extrapolated.assign(static_cast<size_t>(n), 0);
  if (mode == ExtrapolationMode::None)
  {
    return 0;
  }
  const std::vector<Index> layer = Layers(graph, valid, hooks);
  double left = 0.0;
  for (Index i = 0; i < n; ++i)
  {
    extrapolated[i] = layer[i] > 0;
    left += layer[i] < 0 && (!hooks.Counted || hooks.Counted[i]) ? 1.0 : 0.0;
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&left, 1);
  }
  if (mode == ExtrapolationMode::Smooth)
  {
    CreepFill(graph, layer, extrapolated, values, width, offset, nc, hooks);
  }
  else
  {
    Nearest(graph, valid, extrapolated, values, width, offset, nc);
  }
  return static_cast<Index>(left);
}
} // namespace mp
