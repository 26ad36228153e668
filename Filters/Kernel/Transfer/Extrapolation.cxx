// SPDX-License-Identifier: BSD-3-Clause
// Extrapolation beyond the source (Extrapolation.h): the target's graphs
// (rows for the functions to extend), the layers away from the valid
// functions, the creep fill and the nearest values.
#include "Transfer/Extrapolation.h"

#include "Geometry/CellGeometry.h"
#include "Mesh/CellNeighbors.h"
#include "Mesh/NodalCells.h"
#include "Transfer/CsrBuilder.h"

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
/// The rows of `want`: neighbours(i, add) adds (neighbour, weight) terms,
/// summed per neighbour (the neighbours in the order first met).
template <class Neighbours>
void Rows(const std::vector<char>& want, Neighbours neighbours, FunctionGraph& graph)
{
  const Index n = static_cast<Index>(want.size());
  graph.Row.assign(static_cast<size_t>(n), -1);
  RowAccumulator sum(n);
  for (Index i = 0; i < n; ++i)
  {
    if (!want[i])
    {
      continue;
    }
    graph.Row[i] = static_cast<Index>(graph.Start.size()) - 1;
    neighbours(i, [&](Index k, double w) {
      if (k != i)
      {
        sum.Add(k, w);
      }
    });
    sum.Take(false, [&graph](Column k, double w) {
      graph.Neighbors.push_back(k);
      graph.Weights.push_back(w);
    });
    graph.Start.push_back(static_cast<Index>(graph.Neighbors.size()));
  }
}

/**
 * One part's search: each row's layer lowered from the rows next to a
 * known layer (0 valid, infinity unknown).
 */
void SearchLayers(const FunctionGraph& graph, std::vector<double>& layer)
{
  const Index n = graph.Size();
  const double none = std::numeric_limits<double>::infinity();
  // A search from the rows next to a known layer: unit steps, so the
  // rows wait in buckets by layer, smallest first (an entry whose layer
  // has dropped since is stale).
  std::vector<std::vector<Index>> buckets;
  auto push = [&buckets, &layer](Index i) {
    const size_t b = static_cast<size_t>(layer[i]);
    if (buckets.size() <= b)
    {
      buckets.resize(b + 1);
    }
    buckets[b].push_back(i);
  };
  for (Index i = 0; i < n; ++i)
  {
    const Index r = graph.Row[i];
    for (Index q = r < 0 ? 0 : graph.Start[r]; r >= 0 && q < graph.Start[r + 1]; ++q)
    {
      layer[i] = std::min(layer[i], layer[graph.Neighbors[q]] + 1.0);
    }
    if (r >= 0 && layer[i] < none)
    {
      push(i);
    }
  }
  for (size_t b = 0; b < buckets.size(); ++b)
  {
    for (size_t t = 0; t < buckets[b].size(); ++t)
    {
      const Index i = buckets[b][t];
      if (static_cast<size_t>(layer[i]) != b)
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
          push(k); // (into bucket b + 1: the loops read by index)
        }
      }
    }
  }
}

/**
 * Per function, its layer: 0 valid, L the graph distance from the valid
 * ones, -1 not reached. On a distributed graph, rounds of local searches
 * with the smallest layers completed across parts until none changes.
 */
std::vector<Index> Layers(
  const FunctionGraph& graph, const std::vector<char>& valid, const SolverHooks& hooks)
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
    SearchLayers(graph, layer);
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

/**
 * The creep fill's steps: one per layer (as many on every part: the
 * largest over the parts), each the functions of its layer.
 */
std::vector<std::vector<Index>> CreepSteps(
  const std::vector<Index>& layer, const SolverHooks& hooks)
{
  std::vector<std::vector<Index>> steps;
  for (Index i = 0; i < static_cast<Index>(layer.size()); ++i)
  {
    if (layer[i] > 0)
    {
      steps.resize(std::max(steps.size(), static_cast<size_t>(layer[i])));
      steps[static_cast<size_t>(layer[i]) - 1].push_back(i);
    }
  }
  for (size_t L = 1; hooks.Reduce; ++L)
  {
    // (Sum of "this part has layer L" over the parts: 0 once no part has.)
    double has = L <= steps.size() ? 1.0 : 0.0;
    hooks.Reduce(&has, 1);
    if (has == 0.0)
    {
      steps.resize(L - 1);
      break;
    }
  }
  return steps;
}

/// The creep fill's reads: each function of layer L > 0 its neighbours of lower layers, with the graph's weights.
CsrMatrix CreepReads(const FunctionGraph& graph, const std::vector<Index>& layer)
{
  // Calls read(k, weight) for i's neighbours of lower layers, in the graph's order.
  auto lower = [&](Index i, auto read) {
    const Index r = graph.Row[i];
    for (Index q = layer[i] > 0 ? graph.Start[r] : 0; layer[i] > 0 && q < graph.Start[r + 1]; ++q)
    {
      const Index k = graph.Neighbors[q];
      if (layer[k] >= 0 && layer[k] < layer[i])
      {
        read(k, graph.Weights[q]);
      }
    }
  };
  const Index n = graph.Size();
  return BuildCsr(
    n, n,
    [&](Index i) {
      Index count = 0;
      lower(i, [&count](Index, double) { ++count; });
      return count;
    },
    [&](Index i, Column* column, double* value) {
      lower(i, [&](Index k, double w) {
        *column++ = static_cast<Column>(k);
        *value++ = w;
      });
    });
}

/**
 * Per function to fill, the nearest valid function along the graph (edge
 * lengths between the functions' positions; Dijkstra from all valid ones),
 * or -1 where none is connected.
 */
std::vector<Index> NearestValid(
  const FunctionGraph& graph, const std::vector<char>& valid, const std::vector<char>& todo)
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
  return from;
}

/// Nearest's step: each reached function reads its nearest valid one (NearestValid), with weight 1.
void NearestStep(const FunctionGraph& graph, const std::vector<char>& valid, Extension& ext)
{
  const std::vector<char>& todo = ext.Extended;
  const std::vector<Index> from = NearestValid(graph, valid, todo);
  const Index n = graph.Size();
  auto reached = [&](Index i) { return todo[i] && from[i] >= 0; };
  ext.Reads = BuildCsr(
    n, n, [&](Index i) -> Index { return reached(i) ? 1 : 0; },
    [&](Index i, Column* column, double* value) {
      if (reached(i))
      {
        *column = static_cast<Column>(from[i]);
        *value = 1.0;
      }
    });
  ext.Steps.assign(1, {});
  for (Index i = 0; i < n; ++i)
  {
    if (reached(i))
    {
      ext.Steps[0].push_back(i);
    }
  }
}

/// Row i's weighted sums of what it reads (numerators, then the weight).
void ReadSums(const CsrMatrix& reads, Index i, const double* values, int width, int offset, int nc,
  double* sums)
{
  std::fill(sums, sums + nc + 1, 0.0);
  for (Index q = reads.RowStart[i]; q < reads.RowStart[i + 1]; ++q)
  {
    const Index k = reads.ColumnIndex[q];
    const double w = reads.Values[q];
    for (int m = 0; m < nc; ++m)
    {
      sums[m] += w * values[k * width + offset + m];
    }
    sums[nc] += w;
  }
}
} // namespace

FunctionGraph PointGraph(const MeshView& mesh, const std::vector<char>& want)
{
  FunctionGraph graph;
  std::vector<Index> start, cells;
  BuildPointCells(mesh, start, cells);
  Rows(
    want,
    [&](Index i, auto add) {
      for (Index q = start[i]; q < start[i + 1]; ++q)
      {
        // One more cell holds the edge.
        ForEachFunctionPoint(mesh, cells[static_cast<size_t>(q)], [&](Index k) { add(k, 1.0); });
      }
    },
    graph);
  graph.Positions.assign(mesh.Points, mesh.Points + 3 * mesh.NumberOfPoints);
  return graph;
}

FunctionGraph CellGraph(const MeshView& mesh, const std::vector<char>& want)
{
  FunctionGraph graph;
  const Index parents = mesh.Parents();
  const int corners = mesh.CornersPerCell();
  std::vector<Index> pointStart, aroundPoint, parentStart, children;
  BuildPointCells(mesh, pointStart, aroundPoint);
  // Each parent's cells, in increasing ids.
  GroupInRows(
    parents,
    [&](auto put) {
      for (Index c = 0; c < mesh.NumberOfCells; ++c)
      {
        put(mesh.ParentOf(c), c);
      }
    },
    parentStart, children);
  Rows(
    want,
    [&](Index p, auto add) {
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
    },
    graph);
  graph.Positions.resize(3 * static_cast<size_t>(parents));
  for (Index p = 0; p < parents; ++p)
  {
    CornerMean(mesh, children.data() + parentStart[p], parentStart[p + 1] - parentStart[p],
      &graph.Positions[3 * p]);
  }
  return graph;
}

Extension ExtendOver(const FunctionGraph& graph, const std::vector<char>& valid,
  ExtrapolationMode mode, const SolverHooks& hooks)
{
  Extension ext;
  ext.Mode = mode;
  ext.Valid = valid;
  const Index n = graph.Size();
  ext.Extended.assign(static_cast<size_t>(n), 0);
  if (mode == ExtrapolationMode::None)
  {
    return ext;
  }
  const std::vector<Index> layer = Layers(graph, valid, hooks);
  double left = 0.0;
  for (Index i = 0; i < n; ++i)
  {
    ext.Extended[i] = layer[i] > 0;
    left += layer[i] < 0 && graph.Row[i] >= 0 && (!hooks.Counted || hooks.Counted[i]) ? 1.0 : 0.0;
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&left, 1);
  }
  ext.Unreached = static_cast<Index>(left);
  if (mode == ExtrapolationMode::Smooth)
  {
    ext.Steps = CreepSteps(layer, hooks);
    ext.Reads = CreepReads(graph, layer);
  }
  else
  {
    NearestStep(graph, valid, ext);
  }
  return ext;
}

void ApplyExtension(
  const Extension& ext, double* values, int width, int offset, int nc, const SolverHooks& hooks)
{
  std::vector<double> sums(static_cast<size_t>(nc) + 1);
  std::vector<double> all;
  for (const std::vector<Index>& step : ext.Steps)
  {
    if (!hooks.Exchange)
    {
      // (In place: a step reads only valid functions and earlier steps.)
      for (Index i : step)
      {
        ReadSums(ext.Reads, i, values, width, offset, nc, sums.data());
        for (int m = 0; sums[nc] > 0.0 && m < nc; ++m)
        {
          values[i * width + offset + m] = sums[m] / sums[nc];
        }
      }
      continue;
    }
    all.assign(static_cast<size_t>(ext.Reads.Rows) * (nc + 1), 0.0);
    for (Index i : step)
    {
      ReadSums(ext.Reads, i, values, width, offset, nc, &all[static_cast<size_t>(i) * (nc + 1)]);
    }
    hooks.Exchange(all.data(), nc + 1);
    for (Index i = 0; i < ext.Reads.Rows; ++i)
    {
      const double* s = &all[static_cast<size_t>(i) * (nc + 1)];
      for (int m = 0; s[nc] > 0.0 && m < nc; ++m)
      {
        values[i * width + offset + m] = s[m] / s[nc];
      }
    }
  }
}

CsrMatrix ComposedExtension(const Extension& ext, const std::vector<char>& valid)
{
  const Index n = static_cast<Index>(valid.size());
  std::vector<RowList> rows(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      rows[i].emplace_back(static_cast<Column>(i), 1.0);
    }
  }
  // Each extended row the weighted mean of the (composed) rows it reads.
  RowAccumulator sum(n);
  for (const std::vector<Index>& step : ext.Steps)
  {
    for (Index i : step)
    {
      double total = 0.0;
      for (Index q = ext.Reads.RowStart[i]; q < ext.Reads.RowStart[i + 1]; ++q)
      {
        total += ext.Reads.Values[q];
        for (const auto& entry : rows[ext.Reads.ColumnIndex[q]])
        {
          sum.Add(entry.first, ext.Reads.Values[q] * entry.second);
        }
      }
      sum.Take(true, [&](Column k, double s) { rows[i].emplace_back(k, s / total); });
    }
  }
  return CsrFromRowLists(n, rows);
}
} // namespace mp
