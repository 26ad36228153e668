// SPDX-License-Identifier: BSD-3-Clause
// ForCellCornersInOrder (Mesh/CellCornersInOrder.h): every point gets its
// cells' values in cell order, as the serial loop gives them, for any number
// of tasks and any numbering of the points (following space: few values
// wait; shuffled: the ranges stop and finish in the last loop), and never
// from two tasks at once.
#include "Mesh/CellCornersInOrder.h"

#include "Threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

namespace
{
/// Triangles of a grid of n x n squares, row after row (points numbered
/// as the rows go: a numbering that follows space).
struct Grid
{
  std::vector<double> Points;
  std::vector<mp::Index> Connectivity;
  std::vector<std::int32_t> Connectivity32;
  mp::Index NumberOfPoints = 0;
  mp::Index NumberOfCells = 0;

  explicit Grid(int n)
  {
    const int m = n + 1;
    this->NumberOfPoints = mp::Index(m) * m;
    for (int j = 0; j < m; ++j)
    {
      for (int i = 0; i < m; ++i)
      {
        this->Points.insert(this->Points.end(), { double(i), double(j), 0.0 });
      }
    }
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const mp::Index a = mp::Index(j) * m + i;
        this->Connectivity.insert(
          this->Connectivity.end(), { a, a + 1, a + m + 1, a, a + m + 1, a + m });
      }
    }
    this->NumberOfCells = static_cast<mp::Index>(this->Connectivity.size() / 3);
    this->Connectivity32.assign(this->Connectivity.begin(), this->Connectivity.end());
  }

  /// The points renumbered by a random permutation.
  void Shuffle(unsigned seed)
  {
    std::vector<mp::Index> to(static_cast<size_t>(this->NumberOfPoints));
    std::iota(to.begin(), to.end(), mp::Index(0));
    std::shuffle(to.begin(), to.end(), std::mt19937(seed));
    for (mp::Index& p : this->Connectivity)
    {
      p = to[static_cast<size_t>(p)];
    }
    this->Connectivity32.assign(this->Connectivity.begin(), this->Connectivity.end());
  }

  mp::MeshView View(bool narrow) const
  {
    mp::MeshView view;
    view.CellDimension = 2;
    view.SpaceDimension = 2;
    view.Points = this->Points.data();
    view.NumberOfPoints = this->NumberOfPoints;
    view.NumberOfCells = this->NumberOfCells;
    if (narrow)
    {
      view.Connectivity32 = this->Connectivity32.data();
    }
    else
    {
      view.Connectivity = this->Connectivity.data();
    }
    return view;
  }
};

/// Per cell a value, some not positive (those cells are skipped).
std::vector<double> Values(mp::Index cells, unsigned seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> value(0.0, 1.0);
  std::vector<double> values(static_cast<size_t>(cells));
  for (size_t c = 0; c < values.size(); ++c)
  {
    values[c] = c % 7 == 3
      ? 0.0
      : (c % 11 == 5 ? -value(random) : std::ldexp(value(random), int(c % 40) - 20));
  }
  return values;
}

/// What each point receives, in order, and whether two tasks met at one.
struct Received
{
  std::vector<std::vector<double>> Values;
  std::vector<double> Sums;
  std::vector<std::atomic<int>> Busy;
  std::atomic<int> Met{ 0 };

  explicit Received(mp::Index points)
    : Values(static_cast<size_t>(points))
    , Sums(static_cast<size_t>(points), 0.0)
    , Busy(static_cast<size_t>(points))
  {
    for (std::atomic<int>& b : this->Busy)
    {
      b = 0;
    }
  }
  void Apply(mp::Index p, double v)
  {
    const size_t i = static_cast<size_t>(p);
    if (this->Busy[i].exchange(1) != 0)
    {
      ++this->Met;
    }
    this->Values[i].push_back(v);
    this->Sums[i] += v;
    this->Busy[i] = 0;
  }
};

void ExpectSerialOrder(const Grid& grid, bool narrow, int tasks)
{
  const mp::MeshView view = grid.View(narrow);
  const std::vector<double> values = Values(view.NumberOfCells, 9);
  auto value = [&](mp::Index c) { return values[static_cast<size_t>(c)]; };
  // The serial loop.
  Received serial(view.NumberOfPoints);
  for (mp::Index c = 0; c < view.NumberOfCells; ++c)
  {
    if (values[c] > 0.0)
    {
      for (int k = 0; k < 3; ++k)
      {
        serial.Apply(view.Corner(3 * c + k), values[c]);
      }
    }
  }
  for (bool threads : { true, false })
  {
    mp::TaskRunner runner = mptest::ThreadRunner(tasks);
    if (!threads)
    {
      runner.Run = nullptr; // the tasks one after the other
    }
    Received received(view.NumberOfPoints);
    mp::ForCellCornersInOrder(
      view, runner, value, [&](mp::Index p, double v) { received.Apply(p, v); });
    EXPECT_EQ(received.Met.load(), 0) << tasks << " tasks";
    EXPECT_TRUE(received.Values == serial.Values) << tasks << " tasks, threads " << threads;
    EXPECT_EQ(
      std::memcmp(received.Sums.data(), serial.Sums.data(), serial.Sums.size() * sizeof(double)), 0)
      << tasks << " tasks, threads " << threads;
  }
}
} // namespace

TEST(CellCornersInOrder, SerialOrderWithANumberingThatFollowsSpace)
{
  const Grid grid(200); // 80000 triangles: up to 4 tasks of 16384 cells
  for (int tasks : { 1, 2, 3, 4 })
  {
    ExpectSerialOrder(grid, false, tasks);
  }
  ExpectSerialOrder(grid, true, 3);
}

TEST(CellCornersInOrder, SerialOrderWithShuffledPoints)
{
  Grid grid(200);
  grid.Shuffle(4);
  for (int tasks : { 2, 3, 4 })
  {
    ExpectSerialOrder(grid, false, tasks);
  }
  ExpectSerialOrder(grid, true, 4);
}

TEST(CellCornersInOrder, SmallMeshesTakeThePlainLoop)
{
  const Grid grid(20); // 800 triangles
  ExpectSerialOrder(grid, false, 4);
}
