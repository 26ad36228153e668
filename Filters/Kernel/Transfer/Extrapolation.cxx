// SPDX-License-Identifier: BSD-3-Clause
// Extrapolation beyond the source (Extrapolation.h): the target's graphs
// (rows for the functions to extend), the layers away from the valid
// functions, the creep fill and the nearest values.
#include "Transfer/Extrapolation.h"

#include "Mesh/CellNeighbors.h"

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
/// Compressed rows: per item, the entries listed by `visit(item, add)` (the
/// cells around points: BuildPointCells).
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

/// Compressed rows over `n` functions from per-function lists of (column, weight).
CsrMatrix Compressed(Index n, const std::vector<std::vector<std::pair<Column, double>>>& rows)
{
  CsrMatrix m;
  m.Rows = m.Columns = n;
  m.RowStart.assign(static_cast<size_t>(n) + 1, 0);
  for (Index i = 0; i < n; ++i)
  {
    m.RowStart[i + 1] = m.RowStart[i] + static_cast<Index>(rows[i].size());
  }
  m.ColumnIndex.resize(static_cast<size_t>(m.NonZeros()));
  m.Values.resize(static_cast<size_t>(m.NonZeros()));
  for (Index i = 0; i < n; ++i)
  {
    Index at = m.RowStart[i];
    for (const auto& entry : rows[i])
    {
      m.ColumnIndex[at] = entry.first;
      m.Values[at++] = entry.second;
    }
  }
  return m;
}

/**
 * The creep fill's steps: one per layer (as many on every part: the
 * largest over the parts), each function reading its neighbours of lower
 * layers with the graph's weights.
 */
void CreepSteps(const FunctionGraph& graph, const std::vector<Index>& layer, const SolverHooks& hooks,
  Extension& ext)
{
  const Index n = graph.Size();
  for (Index i = 0; i < n; ++i)
  {
    if (layer[i] > 0)
    {
      ext.Steps.resize(std::max(ext.Steps.size(), static_cast<size_t>(layer[i])));
      ext.Steps[static_cast<size_t>(layer[i]) - 1].push_back(i);
    }
  }
  for (size_t L = 1; hooks.Reduce; ++L)
  {
    // (Sum of "this part has layer L" over the parts: 0 once no part has.)
    double has = L <= ext.Steps.size() ? 1.0 : 0.0;
    hooks.Reduce(&has, 1);
    if (has == 0.0)
    {
      ext.Steps.resize(L - 1);
      break;
    }
  }
  // Each function of layer L reads its neighbours of lower layers: counted,
  // then written.
  CsrMatrix& reads = ext.Reads;
  reads.Rows = reads.Columns = n;
  reads.RowStart.assign(static_cast<size_t>(n) + 1, 0);
  for (int pass = 0; pass < 2; ++pass)
  {
    for (Index i = 0; i < n; ++i)
    {
      const Index r = graph.Row[i];
      Index at = reads.RowStart[i];
      for (Index q = layer[i] > 0 ? graph.Start[r] : 0; layer[i] > 0 && q < graph.Start[r + 1]; ++q)
      {
        const Index k = graph.Neighbors[q];
        if (layer[k] >= 0 && layer[k] < layer[i])
        {
          if (pass == 1)
          {
            reads.ColumnIndex[at] = static_cast<Column>(k);
            reads.Values[at] = graph.Weights[q];
          }
          ++at;
        }
      }
      if (pass == 0)
      {
        reads.RowStart[i + 1] = reads.RowStart[i] + (at - reads.RowStart[i]);
      }
    }
    if (pass == 0)
    {
      reads.ColumnIndex.resize(static_cast<size_t>(reads.NonZeros()));
      reads.Values.resize(static_cast<size_t>(reads.NonZeros()));
    }
  }
}

/// Nearest's step: each reached function reads the nearest valid one along the graph (Dijkstra from all valid ones).
void NearestStep(const FunctionGraph& graph, const std::vector<char>& valid, Extension& ext)
{
  const std::vector<char>& todo = ext.Extended;
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
  // Each reached function reads its nearest valid one, with weight 1.
  CsrMatrix& reads = ext.Reads;
  reads.Rows = reads.Columns = n;
  reads.RowStart.assign(static_cast<size_t>(n) + 1, 0);
  ext.Steps.assign(1, {});
  for (Index i = 0; i < n; ++i)
  {
    const bool reached = todo[i] && from[i] >= 0;
    reads.RowStart[i + 1] = reads.RowStart[i] + (reached ? 1 : 0);
    if (reached)
    {
      reads.ColumnIndex.push_back(static_cast<Column>(from[i]));
      reads.Values.push_back(1.0);
      ext.Steps[0].push_back(i);
    }
  }
}

/// Row i's weighted sums of what it reads (numerators, then the weight).
void ReadSums(const CsrMatrix& reads, Index i, const double* values, int width, int offset, int nc, double* sums)
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
  const int corners = mesh.CornersPerCell();
  std::vector<Index> start, cells;
  BuildPointCells(mesh, start, cells);
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
  BuildPointCells(mesh, pointStart, aroundPoint);
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
    left += layer[i] < 0 && (!hooks.Counted || hooks.Counted[i]) ? 1.0 : 0.0;
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&left, 1);
  }
  ext.Unreached = static_cast<Index>(left);
  if (mode == ExtrapolationMode::Smooth)
  {
    CreepSteps(graph, layer, hooks, ext);
  }
  else
  {
    NearestStep(graph, valid, ext);
  }
  return ext;
}

void ApplyExtension(const Extension& ext, double* values, int width, int offset, int nc,
  const SolverHooks& hooks)
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
  std::vector<std::vector<std::pair<Column, double>>> rows(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      rows[i].emplace_back(static_cast<Column>(i), 1.0);
    }
  }
  // Each extended row the weighted mean of the (composed) rows it reads,
  // summed in a dense accumulator.
  std::vector<double> sum(static_cast<size_t>(n), 0.0);
  std::vector<Column> used;
  for (const std::vector<Index>& step : ext.Steps)
  {
    for (Index i : step)
    {
      double total = 0.0;
      used.clear();
      for (Index q = ext.Reads.RowStart[i]; q < ext.Reads.RowStart[i + 1]; ++q)
      {
        total += ext.Reads.Values[q];
        for (const auto& entry : rows[ext.Reads.ColumnIndex[q]])
        {
          if (sum[entry.first] == 0.0)
          {
            used.push_back(entry.first);
          }
          sum[entry.first] += ext.Reads.Values[q] * entry.second;
        }
      }
      std::sort(used.begin(), used.end());
      for (const Column k : used)
      {
        rows[i].emplace_back(k, sum[k] / total);
        sum[k] = 0.0;
      }
    }
  }
  return Compressed(n, rows);
}
} // namespace mp
