// SPDX-License-Identifier: BSD-3-Clause
// Extrapolation (Transfer/Extrapolation.h): the creep fill keeps every
// extended value within the valid values' range and reads lower layers
// only; Nearest gives each function the value of the valid function
// nearest along the graph (a Dijkstra of the test's own); the composed
// extension E is the steps' product (rows summing to 1); the cell graph's
// positions are the cells' corner means.
#include "Transfer/Extrapolation.h"

#include "GeneratedMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
using mp::Index;
using mptest::TestMesh;

/// Valid: the points left of x = 0.35 (and a few scattered ones beyond, in `scatter` of them).
std::vector<char> ValidLeft(const mp::MeshView& view, int scatter)
{
  std::vector<char> valid(static_cast<size_t>(view.NumberOfPoints), 0);
  for (Index i = 0; i < view.NumberOfPoints; ++i)
  {
    valid[i] = view.Point(i)[0] < 0.35 || (scatter > 0 && i % scatter == 0);
  }
  return valid;
}

std::vector<char> Not(const std::vector<char>& valid)
{
  std::vector<char> out(valid.size());
  for (size_t i = 0; i < valid.size(); ++i)
  {
    out[i] = !valid[i];
  }
  return out;
}

/// Per function, the graph distance (as NearestValid defines it: edge
/// lengths between positions, paths through functions to fill only) to
/// valid function v, by a plain Dijkstra over all nodes (O(n^2)).
std::vector<double> DistancesFrom(
  const mp::FunctionGraph& g, const std::vector<char>& valid, Index v)
{
  const Index n = g.Size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> d(static_cast<size_t>(n), inf);
  std::vector<char> done(static_cast<size_t>(n), 0);
  auto length = [&](Index a, Index b) {
    const double* x = &g.Positions[3 * a];
    const double* y = &g.Positions[3 * b];
    return std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
      (x[2] - y[2]) * (x[2] - y[2]));
  };
  // First steps: the functions to fill whose rows hold v.
  for (Index i = 0; i < n; ++i)
  {
    const Index r = g.Row[i];
    for (Index q = r >= 0 ? g.Start[r] : 0; r >= 0 && q < g.Start[r + 1]; ++q)
    {
      if (g.Neighbors[q] == v)
      {
        d[i] = length(i, v);
      }
    }
  }
  for (;;)
  {
    Index best = -1;
    for (Index i = 0; i < n; ++i)
    {
      if (!done[i] && d[i] < inf && (best < 0 || d[i] < d[best]))
      {
        best = i;
      }
    }
    if (best < 0)
    {
      return d;
    }
    done[best] = 1;
    const Index r = g.Row[best];
    for (Index q = g.Start[r]; q < g.Start[r + 1]; ++q)
    {
      const Index k = g.Neighbors[q];
      if (!valid[k])
      {
        d[k] = std::min(d[k], d[best] + length(best, k));
      }
    }
  }
}

/// Parents that pair cells 2k and 2k + 1 (a grid's triangles into quads).
std::vector<Index> PairsOfCells(Index cells)
{
  std::vector<Index> parent(static_cast<size_t>(cells));
  for (Index c = 0; c < cells; ++c)
  {
    parent[c] = c / 2;
  }
  return parent;
}
} // namespace

TEST(Extrapolation, CreepFillStaysWithinTheValidRange)
{
  const TestMesh m = mptest::GridMesh(16, 13, 0.3, 2);
  const mp::MeshView view = m.View(false);
  const std::vector<char> valid = ValidLeft(view, 0);
  const mp::FunctionGraph graph = mp::PointGraph(view, Not(valid));
  const mp::Extension e =
    mp::ExtendOver(graph, valid, mp::ExtrapolationMode::Smooth, mp::SolverHooks());
  const Index n = view.NumberOfPoints;
  // Two fields of values on the valid points (the second a column beside the first).
  std::mt19937 rng(3);
  std::vector<double> values(2 * static_cast<size_t>(n), 0.0);
  double low[2] = { 1e300, 1e300 };
  double high[2] = { -1e300, -1e300 };
  for (Index i = 0; i < n; ++i)
  {
    for (int c = 0; c < 2; ++c)
    {
      values[2 * i + c] =
        valid[i] ? std::uniform_real_distribution<double>(-3.0 + c, 5.0)(rng) : 1e9;
      if (valid[i])
      {
        low[c] = std::min(low[c], values[2 * i + c]);
        high[c] = std::max(high[c], values[2 * i + c]);
      }
    }
  }
  mp::ApplyExtension(e, values.data(), 2, 0, 2, mp::SolverHooks());
  Index extended = 0;
  for (Index i = 0; i < n; ++i)
  {
    ASSERT_TRUE(valid[i] || e.Extended[i]) << "point " << i << " not reached";
    extended += e.Extended[i];
    for (int c = 0; c < 2; ++c)
    {
      EXPECT_GE(values[2 * i + c], low[c]) << "point " << i;
      EXPECT_LE(values[2 * i + c], high[c]) << "point " << i;
    }
    // A function reads functions of earlier layers (valid, or in an earlier step).
    for (Index q = e.Reads.RowStart[i]; q < e.Reads.RowStart[i + 1]; ++q)
    {
      EXPECT_GT(e.Reads.Values[q], 0.0);
    }
  }
  EXPECT_EQ(extended, n - std::count(valid.begin(), valid.end(), 1));
  EXPECT_GT(e.Steps.size(), 5u); // layers across 2/3 of the grid
  // Each step reads only valid functions and earlier steps.
  std::vector<char> known(valid);
  for (const std::vector<Index>& step : e.Steps)
  {
    for (Index i : step)
    {
      EXPECT_GT(e.Reads.RowStart[i + 1], e.Reads.RowStart[i]) << "point " << i << " reads nothing";
      for (Index q = e.Reads.RowStart[i]; q < e.Reads.RowStart[i + 1]; ++q)
      {
        EXPECT_TRUE(known[e.Reads.ColumnIndex[q]]) << "point " << i;
      }
    }
    for (Index i : step)
    {
      known[i] = 1;
    }
  }
  // The composed extension: rows over valid columns summing to 1, giving the applied values.
  const mp::CsrMatrix E = mp::ComposedExtension(e, valid);
  for (Index i = 0; i < n; ++i)
  {
    double sum = 0.0;
    double value = 0.0;
    for (Index q = E.RowStart[i]; q < E.RowStart[i + 1]; ++q)
    {
      EXPECT_TRUE(valid[E.ColumnIndex[q]]);
      sum += E.Values[q];
      value += E.Values[q] * values[2 * E.ColumnIndex[q]];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << "row " << i;
    EXPECT_NEAR(value, values[2 * i], 1e-9 * (1.0 + std::fabs(values[2 * i]))) << "row " << i;
  }
}

TEST(Extrapolation, FunctionsWithNeitherRowNorValidityAreLeftAlone)
{
  // Rows for the points right of x = 0.35; of the valid ones left of it,
  // the upper half (y > 0.5) holds no value of the field (as a
  // mass-weighted array's guarded functions): not read, not extended.
  const TestMesh m = mptest::GridMesh(16, 13, 0.3, 2);
  const mp::MeshView view = m.View(false);
  const std::vector<char> valid = ValidLeft(view, 0);
  const mp::FunctionGraph graph = mp::PointGraph(view, Not(valid));
  const Index n = view.NumberOfPoints;
  std::vector<char> reads(valid);
  std::vector<double> values(static_cast<size_t>(n), 1e9);
  double low = 1e300;
  double high = -1e300;
  Index band = 0;
  for (Index i = 0; i < n; ++i)
  {
    const double x = view.Point(i)[0];
    reads[i] = valid[i] && view.Point(i)[1] <= 0.5;
    band += valid[i] && !reads[i];
    values[i] = reads[i] ? std::sin(7.0 * x) + view.Point(i)[1] : (valid[i] ? -5.0 : 1e9);
    low = reads[i] ? std::min(low, values[i]) : low;
    high = reads[i] ? std::max(high, values[i]) : high;
  }
  ASSERT_GT(band, 0);
  for (const mp::ExtrapolationMode mode :
    { mp::ExtrapolationMode::Smooth, mp::ExtrapolationMode::Nearest })
  {
    const mp::Extension e = mp::ExtendOver(graph, reads, mode, mp::SolverHooks());
    std::vector<double> out(values);
    mp::ApplyExtension(e, out.data(), 1, 0, 1, mp::SolverHooks());
    // (Those beyond the upper half are reached through the lower one.)
    EXPECT_EQ(e.Unreached, 0);
    for (Index i = 0; i < n; ++i)
    {
      if (valid[i] && !reads[i])
      {
        EXPECT_FALSE(e.Extended[i]) << "point " << i;
        EXPECT_EQ(out[i], -5.0) << "point " << i;
      }
      else if (!valid[i])
      {
        EXPECT_TRUE(e.Extended[i]) << "point " << i;
        EXPECT_GE(out[i], low) << "point " << i;
        EXPECT_LE(out[i], high) << "point " << i;
      }
    }
  }
}

TEST(Extrapolation, NearestTakesTheNearestValidFunctionAlongTheGraph)
{
  const TestMesh m = mptest::GridMesh(11, 9, 0.3, 4);
  mp::MeshView view = m.View(false);
  // Parents: pairs of triangles, so that the cell graph is tried too.
  const std::vector<Index> parent = PairsOfCells(m.NumberOfCells());
  for (bool points : { true, false })
  {
    mp::MeshView v = view;
    if (!points)
    {
      v.Parent = parent.data();
      v.NumberOfParents = parent.back() + 1;
    }
    const Index n = points ? v.NumberOfPoints : v.Parents();
    std::vector<char> valid(static_cast<size_t>(n), 0);
    for (Index i = 0; i < n; i += 7)
    {
      valid[i] = 1;
    }
    const mp::FunctionGraph graph =
      points ? mp::PointGraph(v, Not(valid)) : mp::CellGraph(v, Not(valid));
    const mp::Extension e =
      mp::ExtendOver(graph, valid, mp::ExtrapolationMode::Nearest, mp::SolverHooks());
    std::vector<std::vector<double>> distance(static_cast<size_t>(n));
    for (Index k = 0; k < n; ++k)
    {
      if (valid[k])
      {
        distance[k] = DistancesFrom(graph, valid, k);
      }
    }
    // The values: each valid function's own id; after the extension, the nearest one's.
    std::vector<double> values(static_cast<size_t>(n), -1.0);
    for (Index i = 0; i < n; ++i)
    {
      values[i] = valid[i] ? static_cast<double>(i) : -1.0;
    }
    mp::ApplyExtension(e, values.data(), 1, 0, 1, mp::SolverHooks());
    for (Index i = 0; i < n; ++i)
    {
      if (valid[i])
      {
        continue;
      }
      double nearest = std::numeric_limits<double>::infinity();
      for (Index k = 0; k < n; ++k)
      {
        nearest = valid[k] ? std::min(nearest, distance[k][i]) : nearest;
      }
      ASSERT_TRUE(e.Extended[i]) << (points ? "point " : "cell ") << i;
      const Index chosen = static_cast<Index>(values[i]);
      ASSERT_GE(chosen, 0) << i;
      ASSERT_TRUE(valid[chosen]);
      EXPECT_NEAR(distance[chosen][i], nearest, 1e-12) << (points ? "point " : "cell ") << i;
    }
  }
}

TEST(Extrapolation, CellGraphPositionsAreCornerMeans)
{
  const TestMesh m = mptest::GridMesh(5, 4, 0.3, 6);
  mp::MeshView view = m.View(false);
  const std::vector<Index> parent = PairsOfCells(m.NumberOfCells());
  view.Parent = parent.data();
  view.NumberOfParents = parent.back() + 1;
  const mp::FunctionGraph graph =
    mp::CellGraph(view, std::vector<char>(static_cast<size_t>(view.Parents()), 1));
  for (Index p = 0; p < view.Parents(); ++p)
  {
    for (int d = 0; d < 3; ++d)
    {
      double sum = 0.0;
      for (Index c : { 2 * p, 2 * p + 1 })
      {
        for (int k = 0; k < 3; ++k)
        {
          sum += view.Point(view.Cell(c)[k])[d];
        }
      }
      EXPECT_NEAR(graph.Positions[3 * p + d], sum / 6.0, 1e-15) << "parent " << p;
    }
    // Neighbours: the parents sharing a point, each with the number of cells around the edges between them.
    for (Index q = graph.Start[graph.Row[p]]; q < graph.Start[graph.Row[p] + 1]; ++q)
    {
      EXPECT_NE(graph.Neighbors[q], p);
      EXPECT_GT(graph.Weights[q], 0.0);
    }
  }
}
