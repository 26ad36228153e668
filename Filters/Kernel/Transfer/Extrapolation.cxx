// SPDX-License-Identifier: BSD-3-Clause
// Extrapolation beyond the source (Extrapolation.h): the target's graphs,
// which functions a valid one reaches, the harmonic and the nearest
// extension.
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
/// Edges (both directions, with their weights) into compressed rows, duplicates summed.
void Compress(Index n, std::vector<std::pair<Index, Index>>& edges, FunctionGraph& graph)
{
  std::sort(edges.begin(), edges.end());
  graph.Start.assign(static_cast<size_t>(n) + 1, 0);
  graph.Neighbors.clear();
  graph.Weights.clear();
  for (size_t e = 0; e < edges.size(); ++e)
  {
    if (e > 0 && edges[e] == edges[e - 1])
    {
      graph.Weights.back() += 1.0; // one more cell holds this edge
      continue;
    }
    graph.Neighbors.push_back(edges[e].second);
    graph.Weights.push_back(1.0);
    ++graph.Start[static_cast<size_t>(edges[e].first) + 1];
  }
  for (Index i = 0; i < n; ++i)
  {
    graph.Start[i + 1] += graph.Start[i];
  }
}

/// Which functions the valid ones reach over the graph (valid ones included);
/// on a distributed graph, rounds of local searches until no part reaches more.
std::vector<char> Reached(const FunctionGraph& graph, const std::vector<char>& valid,
  const SolverHooks& hooks)
{
  const Index n = graph.Size();
  std::vector<char> reached(valid.begin(), valid.end());
  std::vector<Index> stack;
  for (Index i = 0; i < n; ++i)
  {
    if (reached[i])
    {
      stack.push_back(i);
    }
  }
  for (;;)
  {
    while (!stack.empty())
    {
      const Index i = stack.back();
      stack.pop_back();
      for (Index q = graph.Start[i]; q < graph.Start[i + 1]; ++q)
      {
        const Index k = graph.Neighbors[static_cast<size_t>(q)];
        if (!reached[k])
        {
          reached[k] = 1;
          stack.push_back(k);
        }
      }
    }
    if (!hooks.Exchange)
    {
      return reached;
    }
    std::vector<double> any(reached.begin(), reached.end());
    hooks.Exchange(any.data(), 1);
    double more = 0.0;
    for (Index i = 0; i < n; ++i)
    {
      if (any[i] > 0.0 && !reached[i])
      {
        reached[i] = 1;
        stack.push_back(i);
        more += 1.0;
      }
    }
    hooks.Reduce(&more, 1);
    if (more == 0.0)
    {
      return reached;
    }
  }
}

/// The harmonic extension of columns [offset, offset + nc) into the `todo` functions.
bool Harmonic(const FunctionGraph& graph, const std::vector<char>& todo, double* values, int width,
  int offset, int nc, const TaskRunner& runner, const SolverHooks& hooks)
{
  const Index n = graph.Size();
  // L_uu on the rows to do (the others decoupled by a 1), -L_ub x_b on the right.
  CsrMatrix L;
  L.Rows = L.Columns = n;
  L.RowStart.assign(static_cast<size_t>(n) + 1, 0);
  std::vector<Column> columns;
  std::vector<double> entries;
  std::vector<double> B(static_cast<size_t>(n) * nc, 0.0);
  for (Index i = 0; i < n; ++i)
  {
    if (!todo[i])
    {
      columns.push_back(static_cast<Column>(i));
      entries.push_back(1.0);
      L.RowStart[i + 1] = static_cast<Index>(columns.size());
      continue;
    }
    std::vector<std::pair<Column, double>> row;
    double degree = 0.0;
    for (Index q = graph.Start[i]; q < graph.Start[i + 1]; ++q)
    {
      const Index k = graph.Neighbors[static_cast<size_t>(q)];
      const double w = graph.Weights[static_cast<size_t>(q)];
      degree += w;
      if (todo[k])
      {
        row.emplace_back(static_cast<Column>(k), -w);
      }
      else
      {
        for (int m = 0; m < nc; ++m)
        {
          B[i * nc + m] += w * values[k * width + offset + m];
        }
      }
    }
    row.emplace_back(static_cast<Column>(i), degree);
    std::sort(row.begin(), row.end());
    for (const auto& entry : row)
    {
      columns.push_back(entry.first);
      entries.push_back(entry.second);
    }
    L.RowStart[i + 1] = static_cast<Index>(columns.size());
  }
  L.ColumnIndex.assign(columns.begin(), columns.end());
  L.Values.assign(entries.begin(), entries.end());
  if (hooks.Exchange)
  {
    hooks.Exchange(B.data(), nc);
  }
  std::vector<double> X(static_cast<size_t>(n) * nc, 0.0);
  BlockCG solver(L, runner);
  SolveOptions options;
  options.Tolerance = 1e-13;
  options.MaxIterations = 2000;
  if (!solver.Solve(B.data(), X.data(), nc, options, hooks))
  {
    return false;
  }
  for (Index i = 0; i < n; ++i)
  {
    for (int m = 0; todo[i] && m < nc; ++m)
    {
      values[i * width + offset + m] = X[i * nc + m];
    }
  }
  return true;
}

/// The value of the nearest valid function along the graph (Dijkstra from all valid ones).
void Nearest(const FunctionGraph& graph, const std::vector<char>& valid,
  const std::vector<char>& todo, double* values, int width, int offset, int nc)
{
  const Index n = graph.Size();
  std::vector<double> distance(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  std::vector<Index> from(static_cast<size_t>(n), -1);
  using Entry = std::pair<double, Index>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> front;
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      distance[i] = 0.0;
      from[i] = i;
      front.emplace(0.0, i);
    }
  }
  const double* x = graph.Positions.data();
  while (!front.empty())
  {
    const Entry top = front.top();
    front.pop();
    const Index i = top.second;
    if (top.first > distance[i])
    {
      continue;
    }
    for (Index q = graph.Start[i]; q < graph.Start[i + 1]; ++q)
    {
      const Index k = graph.Neighbors[static_cast<size_t>(q)];
      const double step = std::sqrt((x[3 * k] - x[3 * i]) * (x[3 * k] - x[3 * i]) +
        (x[3 * k + 1] - x[3 * i + 1]) * (x[3 * k + 1] - x[3 * i + 1]) +
        (x[3 * k + 2] - x[3 * i + 2]) * (x[3 * k + 2] - x[3 * i + 2]));
      if (distance[i] + step < distance[k])
      {
        distance[k] = distance[i] + step;
        from[k] = from[i];
        front.emplace(distance[k], k);
      }
    }
  }
  for (Index i = 0; i < n; ++i)
  {
    for (int m = 0; todo[i] && m < nc; ++m)
    {
      values[i * width + offset + m] = values[from[i] * width + offset + m];
    }
  }
}
} // namespace

FunctionGraph PointGraph(const MeshView& mesh)
{
  FunctionGraph graph;
  const int corners = mesh.CornersPerCell();
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(static_cast<size_t>(mesh.NumberOfCells) * corners * (corners - 1));
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const CellCorners cell = mesh.Cell(c);
    for (int a = 0; a < corners; ++a)
    {
      for (int b = 0; b < corners; ++b)
      {
        if (a != b)
        {
          edges.emplace_back(cell[a], cell[b]);
        }
      }
    }
  }
  Compress(mesh.NumberOfPoints, edges, graph);
  graph.Positions.assign(mesh.Points, mesh.Points + 3 * mesh.NumberOfPoints);
  return graph;
}

FunctionGraph CellGraph(const MeshView& mesh)
{
  FunctionGraph graph;
  const Index parents = mesh.Parents();
  const int corners = mesh.CornersPerCell();
  // Per point, the parents around it; every two of them are joined.
  std::vector<std::pair<Index, Index>> around;
  around.reserve(static_cast<size_t>(mesh.NumberOfCells) * corners);
  graph.Positions.assign(3 * static_cast<size_t>(parents), 0.0);
  std::vector<double> count(static_cast<size_t>(parents), 0.0);
  for (Index c = 0; c < mesh.NumberOfCells; ++c)
  {
    const CellCorners cell = mesh.Cell(c);
    const Index parent = mesh.ParentOf(c);
    for (int a = 0; a < corners; ++a)
    {
      around.emplace_back(cell[a], parent);
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
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  std::vector<std::pair<Index, Index>> edges;
  for (size_t a = 0; a < around.size();)
  {
    size_t b = a;
    while (b < around.size() && around[b].first == around[a].first)
    {
      ++b;
    }
    for (size_t i = a; i < b; ++i)
    {
      for (size_t j = a; j < b; ++j)
      {
        if (i != j)
        {
          edges.emplace_back(around[i].second, around[j].second);
        }
      }
    }
    a = b;
  }
  Compress(parents, edges, graph);
  return graph;
}

Index Extrapolate(const FunctionGraph& graph, const std::vector<char>& valid, double* values,
  int width, int offset, int nc, ExtrapolationMode mode, const TaskRunner& runner,
  const SolverHooks& hooks, std::vector<char>& extrapolated, bool& ok)
{
  ok = true;
  const Index n = graph.Size();
  extrapolated.assign(static_cast<size_t>(n), 0);
  if (mode == ExtrapolationMode::None)
  {
    return 0;
  }
  const std::vector<char> reached = Reached(graph, valid, hooks);
  double left = 0.0;
  for (Index i = 0; i < n; ++i)
  {
    extrapolated[i] = reached[i] && !valid[i];
    left += !reached[i] && (!hooks.Counted || hooks.Counted[i]) ? 1.0 : 0.0;
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&left, 1);
  }
  if (mode == ExtrapolationMode::Smooth)
  {
    ok = Harmonic(graph, extrapolated, values, width, offset, nc, runner, hooks);
  }
  else
  {
    Nearest(graph, valid, extrapolated, values, width, offset, nc);
  }
  return static_cast<Index>(left);
}
} // namespace mp
