// SPDX-License-Identifier: BSD-3-Clause
// Renumbering along space (Mesh/SpatialOrder.h): the Morton key interleaves
// the coordinates' bits, the orders are permutations, the renumbered mesh
// has the same cells, its numbering follows space whatever the input's, and
// the projection between renumbered meshes is the same projection; the
// numbering's quality (Mesh/NumberingQuality.h) tells which meshes need it.
#include "Mesh/NumberingQuality.h"
#include "Mesh/SpatialOrder.h"
#include "Search/CandidateLocator.h"
#include "Transfer/MortarOperator.h"
#include "GeneratedMeshes.h"
#include "Threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <functional>
#include <random>
#include <vector>

using mp::Index;
using mptest::TestMesh;

namespace
{
/// `m` with its cells and points in a random order.
TestMesh Shuffled(const TestMesh& m, unsigned seed)
{
  const int corners = m.Dimension + 1;
  std::vector<Index> cells(static_cast<size_t>(m.NumberOfCells()));
  std::vector<Index> points(static_cast<size_t>(m.NumberOfPoints()));
  std::iota(cells.begin(), cells.end(), Index(0));
  std::iota(points.begin(), points.end(), Index(0));
  std::mt19937 random(seed);
  std::shuffle(cells.begin(), cells.end(), random);
  std::shuffle(points.begin(), points.end(), random); // new -> old
  std::vector<Index> newId(points.size());
  TestMesh s;
  s.Dimension = m.Dimension;
  s.Points.resize(m.Points.size());
  for (size_t p = 0; p < points.size(); ++p)
  {
    newId[points[p]] = static_cast<Index>(p);
    std::copy_n(&m.Points[3 * points[p]], 3, &s.Points[3 * p]);
  }
  for (Index c : cells)
  {
    for (int k = 0; k < corners; ++k)
    {
      s.Cells.push_back(newId[m.Cells[corners * c + k]]);
    }
  }
  s.Finish();
  return s;
}

mp::NumberingQuality Quality(const TestMesh& m)
{
  return mp::MeasureNumbering(m.View(false));
}
constexpr double PointSpreadLimit = mp::NumberingQuality::PointSpreadLimit;
constexpr double FarNeighboursLimit = mp::NumberingQuality::FarNeighboursLimit;

bool IsPermutation(const mp::UninitializedLargeVector<Index>& order)
{
  std::vector<Index> v(order.begin(), order.end());
  std::sort(v.begin(), v.end());
  for (size_t i = 0; i < v.size(); ++i)
  {
    if (v[i] != static_cast<Index>(i))
    {
      return false;
    }
  }
  return true;
}

/// The renumbered copy of a mesh, as a TestMesh with neighbours.
struct Renumbered
{
  mp::SpatialOrder Order;
  TestMesh Mesh;
  std::vector<Index> Parent;
  explicit Renumbered(const TestMesh& m)
  {
    mp::OrderAlongCurve(m.View(false), this->Order);
    this->Mesh.Dimension = m.Dimension;
    this->Mesh.Points.resize(m.Points.size());
    this->Mesh.Cells.resize(m.Cells.size());
    this->Parent.resize(static_cast<size_t>(m.NumberOfCells()));
    mp::RenumberMesh(m.View(false), this->Order, this->Mesh.Points.data(), this->Mesh.Cells.data(),
      this->Parent.data());
    this->Mesh.Finish();
  }
};

/// How a runner runs its tasks: one after the other without a Run (the
/// kernel then knows they cannot overlap), on threads of their own, or
/// through a Run that calls them one after the other in reverse or shuffled
/// order (the kernel must assume they overlap: later ranges then claim
/// first, so earlier ones take over nearly every point they share,
/// deterministically, as threads do only when they happen to overlap).
enum class RunMode
{
  Sequential,
  Threads,
  Reversed,
  Shuffled
};

mp::TaskRunner Tasks(int tasks, RunMode mode)
{
  mp::TaskRunner runner;
  runner.Tasks = tasks;
  if (mode == RunMode::Threads)
  {
    runner.Run = mptest::RunInThreads;
  }
  else if (mode != RunMode::Sequential)
  {
    runner.Run = [mode](int count, const std::function<void(int)>& task) {
      std::vector<int> order(static_cast<size_t>(count));
      std::iota(order.begin(), order.end(), 0);
      std::reverse(order.begin(), order.end());
      if (mode == RunMode::Shuffled)
      {
        std::shuffle(order.begin(), order.end(), std::mt19937(count));
      }
      for (int k : order)
      {
        task(k);
      }
    };
  }
  return runner;
}

/// Everything RenumberMesh gives, for comparisons.
struct Copy
{
  mp::SpatialOrder Order;
  std::vector<double> Points;
  std::vector<Index> Cells;
  std::vector<Index> Parent;
};

/// `narrow`: the cells renumbered into 32-bit ids (then widened into c.Cells).
Copy RenumberWith(const TestMesh& m, const mp::UninitializedLargeVector<Index>& cells,
  const mp::TaskRunner& runner, const std::vector<Index>* parents = nullptr, bool inPlace = false,
  bool narrow = false)
{
  Copy c;
  c.Order.Cells = cells;
  c.Points.resize(m.Points.size());
  c.Cells.resize(m.Cells.size());
  mp::MeshView view = m.View(false);
  if (parents)
  {
    view.Parent = parents->data();
    view.NumberOfParents = *std::max_element(parents->begin(), parents->end()) + 1;
  }
  if (inPlace)
  {
    // The parents overwrite the order, as the filter asks.
    mp::RenumberMesh(view, c.Order, c.Points.data(), c.Cells.data(), c.Order.Cells.data(), runner);
    c.Parent.assign(c.Order.Cells.begin(), c.Order.Cells.end());
    c.Order.Cells = cells;
    return c;
  }
  c.Parent.resize(cells.size());
  if (narrow)
  {
    std::vector<std::int32_t> ids(m.Cells.size(), -1);
    mp::RenumberMesh(view, c.Order, c.Points.data(), ids.data(), c.Parent.data(), runner);
    c.Cells.assign(ids.begin(), ids.end());
    return c;
  }
  mp::RenumberMesh(view, c.Order, c.Points.data(), c.Cells.data(), c.Parent.data(), runner);
  return c;
}

double Smooth(double x, double y, double z)
{
  return std::sin(3 * x) * std::cos(2 * y) + z * x;
}
} // namespace

TEST(SpatialOrder, MortonKeysInterleaveTheCoordinatesBits)
{
  const std::uint32_t x10[3] = { 1, 0, 0 };
  const std::uint32_t x01[3] = { 0, 1, 0 };
  const std::uint32_t x001[3] = { 0, 0, 1 };
  const std::uint32_t x33[3] = { 3, 3, 0 };
  const std::uint32_t x52[3] = { 5, 2, 0 };
  EXPECT_EQ(mp::MortonIndex(x10, 2), 1u);
  EXPECT_EQ(mp::MortonIndex(x01, 2), 2u);
  EXPECT_EQ(mp::MortonIndex(x33, 2), 15u);
  EXPECT_EQ(mp::MortonIndex(x52, 2), 0b011001u); // x = 101, y = 010 -> y2x2 y1x1 y0x0
  EXPECT_EQ(mp::MortonIndex(x10, 3), 1u);
  EXPECT_EQ(mp::MortonIndex(x01, 3), 2u);
  EXPECT_EQ(mp::MortonIndex(x001, 3), 4u);
  const std::uint32_t top2[2] = { 0xffffffffu, 0xffffffffu };
  EXPECT_EQ(mp::MortonIndex(top2, 2), ~std::uint64_t(0));
  const std::uint32_t top3[3] = { 0x1fffff, 0x1fffff, 0x1fffff };
  EXPECT_EQ(mp::MortonIndex(top3, 3), (std::uint64_t(1) << 63) - 1);
}

TEST(SpatialOrder, ShuffledMeshesComeOutNumberedAlongSpaceWithTheSameCells)
{
  for (int dimension : { 2, 3 })
  {
    const TestMesh grid =
      dimension == 2 ? mptest::GridMesh(60, 50, 0.25, 3) : mptest::CubeMesh(12, 11, 10, 0.15, 3);
    const TestMesh shuffled = Shuffled(grid, 11);
    EXPECT_TRUE(Quality(grid).Tidy()) << dimension << "D grid";
    EXPECT_GT(Quality(shuffled).PointSpread, PointSpreadLimit) << dimension << "D shuffled";
    EXPECT_GT(Quality(shuffled).FarNeighbours, 5 * FarNeighboursLimit) << dimension << "D shuffled";

    const Renumbered r(shuffled);
    ASSERT_TRUE(IsPermutation(r.Order.Cells));
    ASSERT_TRUE(IsPermutation(r.Order.Points));
    EXPECT_TRUE(Quality(r.Mesh).Tidy()) << dimension << "D renumbered";
    const int corners = dimension + 1;
    Index next = 0;
    for (Index c = 0; c < r.Mesh.NumberOfCells(); ++c)
    {
      const Index old = r.Order.Cells[c];
      EXPECT_EQ(r.Parent[c], old);
      for (int k = 0; k < corners; ++k)
      {
        const Index p = r.Mesh.Cells[corners * c + k];
        const Index q = shuffled.Cells[corners * old + k];
        ASSERT_EQ(r.Order.Points[p], q);
        ASSERT_EQ(r.Order.NewPoint[q], p);
        for (int a = 0; a < 3; ++a)
        {
          ASSERT_EQ(r.Mesh.Points[3 * p + a], shuffled.Points[3 * q + a]);
        }
        // Points are numbered in the order the cells first use them.
        ASSERT_LE(p, next);
        next = std::max(next, p + 1);
      }
    }
  }
}

TEST(SpatialOrder, TasksGiveTheSerialOrderAndCopy)
{
  // Meshes large enough for 3 tasks (16384 cells each at least), shuffled,
  // with an unused point first and one last. The renumbering's tasks list
  // the points their ranges of cells use concurrently; whatever the order
  // the tasks run in, the result must be the serial first-use numbering.
  // Besides the curve's order (ranges of cells that are regions of space:
  // only their borders are shared), cells in a random order make nearly
  // every point used by several tasks.
  for (int dimension : { 2, 3 })
  {
    TestMesh m = Shuffled(
      dimension == 2 ? mptest::GridMesh(170, 160, 0.25, 3) : mptest::CubeMesh(20, 20, 25, 0.15, 3),
      5);
    m.Points.insert(m.Points.begin(), { 0.5, 0.5, 0.5 });
    for (Index& id : m.Cells)
    {
      ++id;
    }
    m.Points.insert(m.Points.end(), { 0.25, 0.25, 0.25 });
    m.Finish();
    ASSERT_GE(m.NumberOfCells(), 3 * 16384);
    mp::SpatialOrder serial;
    mp::OrderAlongCurve(m.View(false), serial);
    mp::UninitializedLargeVector<Index> random = serial.Cells;
    std::shuffle(random.begin(), random.end(), std::mt19937(8));
    for (const mp::UninitializedLargeVector<Index>* cells : { &serial.Cells, &random })
    {
      const Copy expected = RenumberWith(m, *cells, mp::TaskRunner());
      EXPECT_EQ(
        RenumberWith(m, *cells, mp::TaskRunner(), nullptr, false, true).Cells, expected.Cells);
      // The serial copy: points in first-use order, unused ones last.
      Index next = 0;
      for (Index id : expected.Cells)
      {
        ASSERT_LE(id, next);
        next = std::max(next, id + 1);
      }
      EXPECT_EQ(next, m.NumberOfPoints() - 2);
      EXPECT_EQ(expected.Order.Points[next], 0);
      EXPECT_EQ(expected.Order.Points[next + 1], m.NumberOfPoints() - 1);
      // A parent map (two simplices per original cell, as a split gives)
      // and the parents written over the order, as the filter does.
      std::vector<Index> parents(static_cast<size_t>(m.NumberOfCells()));
      for (size_t c = 0; c < parents.size(); ++c)
      {
        parents[c] = static_cast<Index>(c / 2);
      }
      const Copy expectedWithParents = RenumberWith(m, *cells, mp::TaskRunner(), &parents);
      for (size_t c = 0; c < parents.size(); ++c)
      {
        ASSERT_EQ(expectedWithParents.Parent[c], (*cells)[c] / 2);
      }
      for (int tasks : { 2, 3, 7 })
      {
        for (RunMode mode :
          { RunMode::Sequential, RunMode::Threads, RunMode::Reversed, RunMode::Shuffled })
        {
          const mp::TaskRunner runner = Tasks(tasks, mode);
          const std::string what = std::to_string(dimension) + "D, " +
            (cells == &random ? "random" : "curve") + " order, " + std::to_string(tasks) +
            " tasks, run mode " + std::to_string(static_cast<int>(mode));
          if (cells == &serial.Cells)
          {
            mp::SpatialOrder order;
            mp::OrderAlongCurve(m.View(false), order, runner);
            EXPECT_EQ(order.Cells, serial.Cells) << what;
          }
          // Threads several times: their races differ from run to run.
          for (int run = 0; run < (mode == RunMode::Threads ? 3 : 1); ++run)
          {
            const Copy c = RenumberWith(m, *cells, runner);
            EXPECT_EQ(c.Order.Points, expected.Order.Points) << what;
            EXPECT_EQ(c.Order.NewPoint, expected.Order.NewPoint) << what;
            EXPECT_EQ(c.Cells, expected.Cells) << what;
            EXPECT_EQ(c.Points, expected.Points) << what;
            EXPECT_EQ(c.Parent, expected.Parent) << what;
          }
          // 32-bit ids (what the filter's copies hold): the same numbering.
          const Copy narrow = RenumberWith(m, *cells, runner, nullptr, false, true);
          EXPECT_EQ(narrow.Order.Points, expected.Order.Points) << what << ", 32 bits";
          EXPECT_EQ(narrow.Cells, expected.Cells) << what << ", 32 bits";
          EXPECT_EQ(narrow.Points, expected.Points) << what << ", 32 bits";
          EXPECT_EQ(narrow.Parent, expected.Parent) << what << ", 32 bits";
          const Copy inPlace = RenumberWith(m, *cells, runner, &parents, true);
          EXPECT_EQ(inPlace.Order.Points, expected.Order.Points) << what << ", in place";
          EXPECT_EQ(inPlace.Cells, expected.Cells) << what << ", in place";
          EXPECT_EQ(inPlace.Parent, expectedWithParents.Parent) << what << ", in place";
        }
      }
    }
  }
}

TEST(SpatialOrder, InterleavedSweepsAreNotTidyUntilRenumbered)
{
  // 2D: all lower triangles of a grid, then all upper ones (ids and points
  // tidy, but no cell has a face neighbour among the cells numbered next to
  // it). 3D: the six tetrahedra of each cube grouped by kind.
  TestMesh two;
  two.Dimension = 2;
  const int n = 80;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      const double wobble =
        (i > 0 && i < n && j > 0 && j < n) ? 0.2 * std::sin(7.0 * i + 3.0 * j) : 0.0;
      two.Points.insert(two.Points.end(), { (i + wobble) / n, (j - wobble) / n, 0.0 });
    }
  }
  for (int half = 0; half < 2; ++half)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const Index a = j * (n + 1) + i;
        const Index b = a + 1;
        const Index c = a + n + 2;
        const Index d = a + n + 1;
        two.Cells.insert(two.Cells.end(), { a, half ? c : b, half ? d : c });
      }
    }
  }
  two.Finish();
  const TestMesh cubes = mptest::CubeMesh(12, 11, 10, 0.15, 3);
  TestMesh kinds;
  kinds.Dimension = 3;
  kinds.Points = cubes.Points;
  for (Index kind = 0; kind < 6; ++kind)
  {
    for (Index c = kind; c < cubes.NumberOfCells(); c += 6)
    {
      kinds.Cells.insert(kinds.Cells.end(), &cubes.Cells[4 * c], &cubes.Cells[4 * c] + 4);
    }
  }
  kinds.Finish();
  for (const TestMesh* m : { &two, &kinds })
  {
    // Tidy ids and points: only the cells across faces tell.
    EXPECT_LE(Quality(*m).PointSpread, PointSpreadLimit) << m->Dimension << "D interleaved";
    EXPECT_GT(Quality(*m).FarNeighbours, 5 * FarNeighboursLimit) << m->Dimension << "D interleaved";
    const Renumbered r(*m);
    EXPECT_TRUE(Quality(r.Mesh).Tidy()) << m->Dimension << "D renumbered";
  }
}

/// `m` with its points as they are and its cells in runs of `run` (as
/// numbered), the runs in a random order: how Qhull lists a Delaunay mesh
/// (points as given, a point's new cells together when it is inserted, the
/// points inserted in no spatial order).
TestMesh CellsInRandomRuns(const TestMesh& m, Index run, unsigned seed)
{
  const int corners = m.Dimension + 1;
  const Index n = m.NumberOfCells();
  std::vector<Index> runs(static_cast<size_t>((n + run - 1) / run));
  std::iota(runs.begin(), runs.end(), Index(0));
  std::shuffle(runs.begin(), runs.end(), std::mt19937(seed));
  TestMesh s = m;
  s.Cells.clear();
  for (Index r : runs)
  {
    s.Cells.insert(s.Cells.end(), &m.Cells[0] + corners * r * run,
      &m.Cells[0] + corners * std::min(n, r * run + run));
  }
  s.Finish();
  return s;
}

TEST(SpatialOrder, CellsListedOutOfOrderAreNotTidyUntilRenumbered)
{
  for (int dimension : { 2, 3 })
  {
    const TestMesh grid =
      dimension == 2 ? mptest::GridMesh(150, 140, 0.25, 7) : mptest::CubeMesh(26, 25, 24, 0.15, 7);
    const TestMesh qhullLike = CellsInRandomRuns(grid, 8, 13);
    // The grid's points and cells: only the cells across faces tell.
    EXPECT_LE(Quality(qhullLike).PointSpread, PointSpreadLimit) << dimension << "D";
    EXPECT_GT(Quality(qhullLike).FarNeighbours, 5 * FarNeighboursLimit) << dimension << "D";
    EXPECT_FALSE(Quality(qhullLike).Tidy()) << dimension << "D";
    // The generated grid (a sweep) and the Morton-renumbered copy are tidy.
    const mp::NumberingQuality sweep = Quality(grid);
    EXPECT_LT(sweep.PointSpread, 1.5) << dimension << "D grid";
    EXPECT_EQ(sweep.FarNeighbours, 0.0) << dimension << "D grid";
    const Renumbered r(qhullLike);
    EXPECT_LT(Quality(r.Mesh).PointSpread, 1.0) << dimension << "D renumbered";
    EXPECT_LT(Quality(r.Mesh).FarNeighbours, FarNeighboursLimit) << dimension << "D renumbered";
    for (int tasks : { 2, 3 }) // threads find the same neighbours
    {
      const auto threaded =
        mp::MeasureNumbering(qhullLike.View(false), Tasks(tasks, RunMode::Threads));
      EXPECT_EQ(threaded.PointSpread, Quality(qhullLike).PointSpread) << tasks << " tasks";
      EXPECT_EQ(threaded.FarNeighbours, Quality(qhullLike).FarNeighbours) << tasks << " tasks";
    }
  }
}

TEST(SpatialOrder, UnusedAndNonFinitePointsComeLastAndDoNotSpoilTheOrder)
{
  TestMesh m = Shuffled(mptest::GridMesh(30, 30, 0.2, 5), 2);
  const Index used = m.NumberOfPoints();
  m.Points.insert(m.Points.begin(), { std::nan(""), 1e300, 0.0 }); // unused point 0
  for (Index& id : m.Cells)
  {
    ++id;
  }
  m.Points.insert(m.Points.end(), { 0.5, 0.5, 0.0 }); // unused, last
  const Renumbered r(m);
  ASSERT_TRUE(IsPermutation(r.Order.Points));
  EXPECT_EQ(r.Order.Points[used], 0);
  EXPECT_EQ(r.Order.Points[used + 1], used + 1);
  EXPECT_TRUE(Quality(r.Mesh).Tidy());
}

TEST(SpatialOrder, TheProjectionBetweenRenumberedMeshesIsTheSame)
{
  for (int dimension : { 2, 3 })
  {
    const TestMesh target = Shuffled(
      dimension == 2 ? mptest::GridMesh(40, 40, 0.25, 1) : mptest::CubeMesh(8, 8, 8, 0.15, 1), 4);
    const TestMesh source = Shuffled(
      dimension == 2 ? mptest::GridMesh(43, 37, 0.25, 2) : mptest::CubeMesh(9, 8, 7, 0.15, 2), 5);
    const Renumbered t(target);
    const Renumbered s(source);
    auto project = [](const TestMesh& a, const TestMesh& b, const std::vector<double>& u) {
      mp::BoxGridLocator locator(b.View());
      mp::MortarOperator op;
      EXPECT_TRUE(op.Build(a.View(), b.View(), &locator, mp::OperatorOptions()));
      std::vector<double> v(static_cast<size_t>(a.NumberOfPoints()));
      op.Apply(u.data(), 1, v.data(), std::nan(""));
      return v;
    };
    const std::vector<double> u = mptest::Sample3D(source, Smooth);
    std::vector<double> ur(u.size());
    for (size_t p = 0; p < u.size(); ++p)
    {
      ur[p] = u[static_cast<size_t>(s.Order.Points[p])];
    }
    const std::vector<double> plain = project(target, source, u);
    const std::vector<double> renumbered = project(t.Mesh, s.Mesh, ur);
    double largest = 0;
    for (size_t p = 0; p < plain.size(); ++p)
    {
      largest =
        std::max(largest, std::fabs(plain[static_cast<size_t>(t.Order.Points[p])] - renumbered[p]));
    }
    EXPECT_LT(largest, 1e-12) << dimension << "D";
  }
}

namespace
{
/// A target and a source: a shuffled grid (2D) or cube (3D) stretched in x
/// over [0.3, 1.2], a third of it beyond the unit box the source covers;
/// and the target renumbered.
struct PartlyCovered
{
  TestMesh Target;
  TestMesh Source;
  Renumbered Ordered;
  explicit PartlyCovered(int dimension)
    : Target(Stretched(Shuffled(
        dimension == 2 ? mptest::GridMesh(30, 30, 0.25, 1) : mptest::CubeMesh(7, 7, 7, 0.15, 1),
        4)))
    , Source(
        dimension == 2 ? mptest::GridMesh(23, 29, 0.25, 2) : mptest::CubeMesh(6, 8, 7, 0.15, 2))
    , Ordered(Target)
  {}
  static TestMesh Stretched(TestMesh m)
  {
    for (size_t p = 0; p < m.Points.size(); p += 3)
    {
      m.Points[p] = 0.3 + 0.9 * m.Points[p];
    }
    m.Finish();
    return m;
  }
};
} // namespace

TEST(SpatialOrder, CoveredFractionsThroughTheRenumberingAreTheCellsOwn)
{
  // A target partly outside the source (fractions strictly between 0 and
  // 1 along the edge), renumbered; the covered fraction per original cell
  // through Parent, with OneCellPerParent (the values moved) and without
  // it (the measure-weighted sums), equals the plain mesh's.
  for (int dimension : { 2, 3 })
  {
    const PartlyCovered pair(dimension);
    const TestMesh& target = pair.Target;
    const TestMesh& source = pair.Source;
    const Renumbered& t = pair.Ordered;
    auto fractions = [&source](const mp::MeshView& view) {
      mp::BoxGridLocator locator(source.View());
      mp::MortarOperator op;
      EXPECT_TRUE(op.Build(view, source.View(), &locator, mp::OperatorOptions()));
      const mp::LargeVector<double>& f = op.GetCoveredFraction();
      return std::vector<double>(f.begin(), f.end());
    };
    const std::vector<double> plain = fractions(target.View());
    mp::MeshView view = t.Mesh.View();
    view.Parent = t.Parent.data();
    view.NumberOfParents = target.NumberOfCells();
    for (bool moved : { true, false })
    {
      view.OneCellPerParent = moved;
      const std::vector<double> through = fractions(view);
      ASSERT_EQ(through.size(), plain.size());
      double largest = 0;
      int partial = 0;
      for (size_t c = 0; c < plain.size(); ++c)
      {
        largest = std::max(largest, std::fabs(plain[c] - through[c]));
        partial += plain[c] > 0.01 && plain[c] < 0.99;
      }
      EXPECT_LT(largest, 1e-12) << dimension << "D, OneCellPerParent " << moved;
      EXPECT_GT(partial, 10) << dimension << "D";
    }
  }
}

namespace
{
/**
 * M_tt and the point cover of `view` (parents set) assembled in each
 * number of `tasks` (the first 1) are the one-task ones bit for bit, from
 * cells covered whole, in part (blocks of their own) and not at all, with
 * the cover's values per cell and per parent.
 */
void ExpectTargetMassInTasksIsTheSerialOne(
  const mp::MeshView& view, const std::vector<int>& taskCounts)
{
  const Index cells = view.NumberOfCells;
  mp::CellMasses masses;
  masses.Dofs = 3;
  masses.State.resize(static_cast<size_t>(cells));
  std::vector<double> perCell(static_cast<size_t>(cells));
  std::vector<double> perParent(static_cast<size_t>(cells));
  std::vector<mp::PartialMasses> partial(1);
  for (Index c = 0; c < cells; ++c)
  {
    const unsigned h = static_cast<unsigned>(c) * 2654435761u;
    const int kind = static_cast<int>(h >> 28) % 4; // whole (2 in 4), in part, none
    masses.State[static_cast<size_t>(c)] = kind == 3
      ? mp::CellMasses::None
      : (kind == 2 ? mp::CellMasses::Part : 1e-13f * (kind - 0.5f));
    if (kind == 2)
    {
      const mp::CellCorners ids = view.Cell(c);
      const Index dofs[3] = { ids[0], ids[1], ids[2] };
      const double m = 1e-6 * (1 + (h & 1023));
      const double block[3][3] = { { 2 * m, m, 0.5 * m }, { m, 3 * m, m }, { 0.5 * m, m, 2 * m } };
      partial[0].Add(view, c, dofs, block);
    }
    perCell[static_cast<size_t>(c)] = ((h >> 8) & 1023) / 1023.0;
    perParent[static_cast<size_t>(view.Parent[c])] = ((h >> 12) & 1023) / 1023.0;
  }
  masses.Gather(partial);
  for (bool byParent : { false, true })
  {
    mp::CellValues values;
    values.Values = byParent ? perParent.data() : perCell.data();
    values.ByParent = byParent;
    mp::CsrMatrix serial;
    mp::LargeVector<double> serialCover;
    for (int tasks : taskCounts)
    {
      mp::CsrMatrix mass;
      mp::LargeVector<double> cover;
      mp::AssembleTargetMass(
        mp::SpaceType::P1, view, &masses, mptest::ThreadRunner(tasks), mass, values, &cover);
      ASSERT_EQ(cover.size(), static_cast<size_t>(view.NumberOfPoints));
      if (tasks == 1)
      {
        serial = mass;
        serialCover = cover;
        // The cover is the largest value around each point.
        std::vector<double> expected(cover.size(), 0.0);
        for (Index c = 0; c < cells; ++c)
        {
          const mp::CellCorners ids = view.Cell(c);
          for (int k = 0; k < 3; ++k)
          {
            double& most = expected[static_cast<size_t>(ids[k])];
            most = std::max(most,
              byParent ? perParent[static_cast<size_t>(view.Parent[c])]
                       : perCell[static_cast<size_t>(c)]);
          }
        }
        EXPECT_TRUE(std::equal(expected.begin(), expected.end(), cover.begin())) << byParent;
        continue;
      }
      EXPECT_TRUE(mass.RowStart == serial.RowStart) << tasks;
      EXPECT_TRUE(mass.ColumnIndex == serial.ColumnIndex) << tasks;
      EXPECT_TRUE(mass.Values == serial.Values) << tasks << " tasks, by parent " << byParent;
      EXPECT_TRUE(cover == serialCover) << tasks << " tasks, by parent " << byParent;
    }
  }
}
} // namespace

TEST(SpatialOrder, TargetMassInTasksIsTheSerialOne)
{
  // M_tt's values come from tasks owning ranges of points (from 2 x 4096
  // points on: two tasks and more), each adding its rows of the blocks of
  // the cells around its points in cell order: on a renumbered mesh of
  // 203,401 points, from cells covered whole, in part (blocks of their
  // own) and not at all, 2, 3 and 7 tasks give the one-task matrix and point
  // cover bit for bit, with the cover's values per cell and per parent. So
  // do 64 tasks on the shuffled mesh itself (each task's cells too spread
  // for a set of bits: it reads its span).
  const TestMesh mesh = Shuffled(mptest::GridMesh(450, 450, 0.25, 5), 6);
  ASSERT_GE(mesh.NumberOfPoints(), Index(3) << 16);
  const Renumbered t(mesh);
  mp::MeshView view = t.Mesh.View();
  view.Parent = t.Parent.data();
  view.NumberOfParents = mesh.NumberOfCells();
  view.OneCellPerParent = true;
  ExpectTargetMassInTasksIsTheSerialOne(view, { 1, 2, 3, 7 });
  mp::MeshView shuffled = mesh.View(false);
  std::vector<Index> identity(static_cast<size_t>(mesh.NumberOfCells()));
  std::iota(identity.begin(), identity.end(), Index(0));
  shuffled.Parent = identity.data();
  shuffled.NumberOfParents = mesh.NumberOfCells();
  shuffled.OneCellPerParent = true;
  ExpectTargetMassInTasksIsTheSerialOne(shuffled, { 1, 2, 64 });
}

TEST(SpatialOrder, PointCoverIsTheLargestFractionAroundEachPoint)
{
  // The point cover made with M_tt (P1 targets), on the plain and the
  // renumbered target (its parents' fractions moved or summed), in one task
  // and in threads: bit for bit the largest covered fraction of the cells
  // around each point, as a plain loop over the cells finds it; none for
  // P0 targets.
  for (int dimension : { 2, 3 })
  {
    const PartlyCovered meshes(dimension);
    const Renumbered& ordered = meshes.Ordered;
    mp::MeshView views[3] = { meshes.Target.View(), ordered.Mesh.View(), ordered.Mesh.View() };
    for (int v : { 1, 2 })
    {
      views[v].Parent = ordered.Parent.data();
      views[v].NumberOfParents = meshes.Target.NumberOfCells();
      views[v].OneCellPerParent = v == 1;
    }
    for (const mp::MeshView& view : views)
    {
      for (int tasks : { 1, 3 })
      {
        mp::BoxGridLocator locator(meshes.Source.View());
        mp::OperatorOptions options;
        options.Runner = mptest::ThreadRunner(tasks);
        mp::MortarOperator op;
        ASSERT_TRUE(op.Build(view, meshes.Source.View(), &locator, options));
        const mp::LargeVector<double>& f = op.GetCoveredFraction();
        std::vector<double> expected(static_cast<size_t>(view.NumberOfPoints), 0.0);
        for (mp::Index c = 0; c < view.NumberOfCells; ++c)
        {
          const mp::CellCorners ids = view.Cell(c);
          for (int k = 0; k < view.CornersPerCell(); ++k)
          {
            double& most = expected[static_cast<size_t>(ids[k])];
            most = std::max(most, f[static_cast<size_t>(view.ParentOf(c))]);
          }
        }
        mp::LargeVector<double> cover;
        op.TakePointCover(cover);
        ASSERT_EQ(cover.size(), expected.size());
        int partial = 0;
        for (size_t p = 0; p < expected.size(); ++p)
        {
          ASSERT_EQ(cover[p], expected[p])
            << dimension << "D, view " << &view - views << ", point " << p;
          partial += expected[p] > 0.01 && expected[p] < 0.99;
        }
        EXPECT_GT(partial, 5) << dimension << "D";
        mp::LargeVector<double> again;
        op.TakePointCover(again);
        EXPECT_TRUE(again.empty()); // handed over once
        options.TargetSpace = mp::SpaceType::P0;
        mp::MortarOperator cells;
        ASSERT_TRUE(cells.Build(view, meshes.Source.View(), &locator, options));
        cells.TakePointCover(again);
        EXPECT_TRUE(again.empty());
      }
    }
  }
}
