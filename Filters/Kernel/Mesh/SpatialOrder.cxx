// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/SpatialOrder.h"

#include <algorithm>
#include <type_traits>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace mp
{
namespace
{
/// The bits of x (below 2^32) moved to the even positions of the result.
std::uint64_t SpreadBy1(std::uint64_t x)
{
  x &= 0xffffffffULL;
  x = (x | (x << 16)) & 0x0000ffff0000ffffULL;
  x = (x | (x << 8)) & 0x00ff00ff00ff00ffULL;
  x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0fULL;
  x = (x | (x << 2)) & 0x3333333333333333ULL;
  x = (x | (x << 1)) & 0x5555555555555555ULL;
  return x;
}
/// The bits of x (below 2^21) moved to every third position of the result.
std::uint64_t SpreadBy2(std::uint64_t x)
{
  x &= 0x1fffffULL;
  x = (x | (x << 32)) & 0x001f00000000ffffULL;
  x = (x | (x << 16)) & 0x001f0000ff0000ffULL;
  x = (x | (x << 8)) & 0x100f00f00f00f00fULL;
  x = (x | (x << 4)) & 0x10c30c30c30c30c3ULL;
  x = (x | (x << 2)) & 0x1249249249249249ULL;
  return x;
}
} // namespace

std::uint64_t MortonIndex(const std::uint32_t* x, int dimension)
{
  if (dimension == 3)
  {
    return SpreadBy2(x[0]) | (SpreadBy2(x[1]) << 1) | (SpreadBy2(x[2]) << 2);
  }
  if (dimension == 2)
  {
    return SpreadBy1(x[0]) | (SpreadBy1(x[1]) << 1);
  }
  return dimension == 1 ? x[0] : 0;
}

namespace
{
struct Box
{
  double Lo[3] = { std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double Hi[3] = { -std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  Box& operator+=(const Box& o)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Lo[a] = std::min(this->Lo[a], o.Lo[a]);
      this->Hi[a] = std::max(this->Hi[a], o.Hi[a]);
    }
    return *this;
  }
};

/// Asks for a cache line ahead of its use: the renumbering's reads follow
/// the old numbering, so in a shuffled mesh nearly every one misses.
inline void Prefetch(const void* address)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address);
#else
  (void)address;
#endif
}
/// How many cells ahead the prefetches run.
constexpr Index Ahead = 16;
/// A cell's key (CellKeys): the unsigned type of Index, so that the keys
/// can be moved in order.Cells' own room.
using CellKey = std::make_unsigned_t<Index>;
static_assert(sizeof(CellKey) == 8, "a cell's key takes 64 bits");

} // namespace

namespace
{
/// The box of the points (in storage order: no random access), leaving out
/// those no valid mesh has (NaN, infinite, beyond 1e100).
Box PointBox(const MeshView& mesh, const TaskRunner& runner)
{
  return runner.ForRanges(mesh.NumberOfPoints, [&](Index begin, Index end) {
    Box b;
    for (Index p = begin; p < end; ++p)
    {
      const double* x = mesh.Point(p);
      if (std::fabs(x[0]) <= 1e100 && std::fabs(x[1]) <= 1e100 && std::fabs(x[2]) <= 1e100)
      {
        for (int a = 0; a < 3; ++a)
        {
          b.Lo[a] = std::min(b.Lo[a], x[a]);
          b.Hi[a] = std::max(b.Hi[a], x[a]);
        }
      }
    }
    return b;
  });
}

/// The grid a point's position on the curve is read in: the box's axes of
/// positive extent, each cut into just below 2^bits steps.
struct CurveGrid
{
  int Axes[3];
  int Dimension = 0;
  double Scale[3] = {};
  double Top = 0; ///< the largest step
  const double* Lo;

  explicit CurveGrid(const Box& box)
    : Lo(box.Lo)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (box.Hi[a] > box.Lo[a])
      {
        this->Axes[this->Dimension++] = a;
      }
    }
    // A 32-bit position: 16 bits per axis in 2D, 10 in 3D (finer than any
    // mesh's cells along an axis; ties keep the old order).
    const int dimension = this->Dimension;
    const int bits = dimension == 3 ? 10 : (dimension == 2 ? 16 : 32);
    for (int k = 0; k < dimension; ++k)
    {
      const int a = this->Axes[k];
      // Just below 2^bits steps, so that the largest point stays inside.
      this->Scale[k] = (std::ldexp(1.0, bits) - 1.0) / (box.Hi[a] - box.Lo[a]);
    }
    this->Top = std::ldexp(1.0, bits) - 1.0;
  }

  /// Point x's position on the curve.
  std::uint32_t Position(const double* x) const
  {
    std::uint32_t q[3] = {};
    for (int k = 0; k < this->Dimension; ++k)
    {
      const double s = (x[this->Axes[k]] - this->Lo[this->Axes[k]]) * this->Scale[k];
      // NaN and beyond the box (non-finite points) clamped: any key will do.
      q[k] = s > 0 ? static_cast<std::uint32_t>(std::min(s, this->Top)) : 0u;
    }
    return static_cast<std::uint32_t>(MortonIndex(q, this->Dimension));
  }
};

/**
 * Each point's position on the curve (in storage order: no random
 * access), then each cell's key: the lowest of its corners' positions in
 * the high 32 bits, the cell id in the low ones. (A key from the cell's
 * centre read every corner's three coordinates in the old numbering,
 * mostly cache misses, for each cell; the corners'
 * positions are a sixth of the points' bytes, and the order they give
 * keeps the front's search as fast.)
 */
void CellKeys(const MeshView& mesh, const CurveGrid& grid, const TaskRunner& runner,
  UninitializedLargeVector<CellKey>& keys)
{
  // (pointKeys and keys are written whole by tasks: not zeroed first.)
  UninitializedLargeVector<std::uint32_t> pointKeys(static_cast<size_t>(mesh.NumberOfPoints));
  runner.ForRanges(mesh.NumberOfPoints, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
    {
      pointKeys[p] = grid.Position(mesh.Point(p));
    }
    return 0;
  });
  keys.resize(static_cast<size_t>(mesh.NumberOfCells));
  runner.ForRanges(mesh.NumberOfCells, [&](Index begin, Index end) {
    const int corners = mesh.CornersPerCell();
    for (Index c = begin; c < end; ++c)
    {
      if (c + Ahead < end)
      {
        const CellCorners ahead = mesh.Cell(c + Ahead);
        for (int k = 0; k < corners; ++k)
        {
          Prefetch(pointKeys.data() + ahead[k]);
        }
      }
      const CellCorners ids = mesh.Cell(c);
      std::uint32_t lowest = pointKeys[ids[0]];
      for (int k = 1; k < corners; ++k)
      {
        lowest = std::min(lowest, pointKeys[ids[k]]);
      }
      keys[c] = (static_cast<CellKey>(lowest) << 32) | static_cast<CellKey>(c);
    }
    return 0;
  });
}

/**
 * Least-significant-digit radix sort of the n keys at `keys` on their high
 * 32 bits in three digits of 11, 11 and 10 bits: stable, so equal keys
 * stay in id order. Each task counts and then moves its own range of keys;
 * the buckets' starts are laid out bucket by bucket and, within a bucket,
 * task by task, so that the result is the same for any number of tasks.
 * The moves go back and forth between `keys` and `other` (n keys' room);
 * returns the one holding the sorted keys.
 */
CellKey* SortKeys(CellKey* keys, CellKey* other, Index n, const TaskRunner& runner)
{
  constexpr int Shifts[3] = { 32, 43, 54 };
  constexpr size_t Buckets = 2048;
  const int tasks = runner.TasksFor(n, 16384);
  std::vector<size_t> count(static_cast<size_t>(tasks) * Buckets);
  for (int d = 0; d < 3; ++d)
  {
    const int shift = Shifts[d];
    runner.RunAll(tasks, [&](int t) {
      size_t* mine = count.data() + static_cast<size_t>(t) * Buckets;
      std::fill(mine, mine + Buckets, size_t(0));
      const Index end = RangeBegin(n, t + 1, tasks);
      for (Index i = RangeBegin(n, t, tasks); i < end; ++i)
      {
        ++mine[(keys[i] >> shift) & (Buckets - 1)];
      }
    });
    size_t at = 0;
    bool moves = true;
    for (size_t b = 0; b < Buckets; ++b)
    {
      size_t inBucket = 0;
      for (int t = 0; t < tasks; ++t)
      {
        size_t& c = count[static_cast<size_t>(t) * Buckets + b];
        const size_t here = c;
        c = at;
        at += here;
        inBucket += here;
      }
      moves &= inBucket != static_cast<size_t>(n);
    }
    if (!moves)
    {
      continue; // one value of this digit: nothing moves
    }
    runner.RunAll(tasks, [&](int t) {
      size_t* start = count.data() + static_cast<size_t>(t) * Buckets;
      const Index end = RangeBegin(n, t + 1, tasks);
      for (Index i = RangeBegin(n, t, tasks); i < end; ++i)
      {
        const CellKey k = keys[i];
        other[start[(k >> shift) & (Buckets - 1)]++] = k;
      }
    });
    std::swap(keys, other);
  }
  return keys;
}
} // namespace

void OrderAlongCurve(const MeshView& mesh, SpatialOrder& order, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  order.Cells.resize(static_cast<size_t>(n));
  if (n < 2 || n > Index(0xffffffff))
  {
    std::iota(order.Cells.begin(), order.Cells.end(), Index(0));
    return; // keys carry the cell id in 32 bits
  }
  const Box box = PointBox(mesh, runner);
  const CurveGrid grid(box);
  UninitializedLargeVector<CellKey> keys;
  CellKeys(mesh, grid, runner, keys);
  // The moves' second buffer is order.Cells (keys of the corresponding
  // unsigned type): no array of their own, whose fresh pages would cost
  // their faults. The cell ids are then the sorted keys' low bits, taken
  // where the keys ended.
  CellKey* cells = reinterpret_cast<CellKey*>(order.Cells.data());
  const CellKey* sorted = SortKeys(keys.data(), cells, n, runner);
  runner.ForRanges(n, [&](Index begin, Index end) {
    for (Index c = begin; c < end; ++c)
    {
      cells[c] = sorted[c] & 0xffffffffULL;
    }
    return 0;
  });
}

namespace
{
/**
 * `mesh` renumbered by order.Cells into `out` (connectivity) and `parent`
 * (RenumberMesh). Points are numbered in the order the ordered cells first
 * use them. With one task, in one pass: a point's slot in NewPoint is its
 * new id from its first use on. With several, the ordered cells are split
 * into ranges, one per task, and each task lists the points its cells use
 * in their first use there, a point seen once set in a bit array of the
 * task's own (an eighth of a byte a point, mostly in the core's cache:
 * the tasks share no memory in this pass; slots in one array claimed by
 * atomic exchanges, as first written here, made that pass on a Gmsh mesh
 * of 10^6 cells as long on two threads as on one). A point then belongs to
 * the first range using it: the bits of the ranges before a task's are
 * cleared from its own, its list keeps the points whose bits remain, and
 * the lists, one range after the other, are exactly the serial first-use
 * order; meanwhile `out` holds the old ids (32 bits are enough).
 */
template <class Id>
class Renumbering
{
public:
  static constexpr Index Unclaimed = std::numeric_limits<Index>::max();

  Renumbering(
    const MeshView& mesh, SpatialOrder& order, Id* out, Index* parent, const TaskRunner& runner)
    : Mesh(mesh)
    , Order(order)
    , Out(out)
    , Parent(parent)
    , Runner(runner)
    , N(mesh.NumberOfCells)
    , NP(mesh.NumberOfPoints)
    , Corners(mesh.CornersPerCell())
  {}

  /// Numbers the points and writes the cells; then the points no cell
  /// uses, last in their old order.
  void Run()
  {
    // (At most 64 tasks: their bits take no more room than NewPoint.)
    const int tasks = static_cast<int>(std::min<Index>(this->Runner.TasksFor(this->N, 16384), 64));
    this->Order.NewPoint.resize(static_cast<size_t>(this->NP));
    this->NewId = this->Order.NewPoint.data();
    this->Order.Points.resize(static_cast<size_t>(this->NP));
    Index next = tasks == 1 ? this->NumberInOneTask() : this->NumberInTasks(tasks);
    // Points no cell uses: last, in their old order.
    for (Index p = 0; p < this->NP && next < this->NP; ++p)
    {
      Index& id = this->Order.NewPoint[p];
      if (id == Unclaimed)
      {
        id = next;
        this->Order.Points[next++] = p;
      }
    }
  }

private:
  using Word = std::uint64_t;

  /// The serial pass: returns the number of points used.
  Index NumberInOneTask()
  {
    const MeshView& mesh = this->Mesh;
    SpatialOrder& order = this->Order;
    const Index n = this->N;
    const int corners = this->Corners;
    Index* newId = this->NewId;
    Id* out = this->Out;
    Index* parent = this->Parent;
    Index next = 0;
    this->Runner.Fill(newId, this->NP, Unclaimed);
    for (Index c = 0; c < n; ++c)
    {
      // Two stages of prefetching: the connectivity of the cell 2 * Ahead
      // on, the slots of the one Ahead on (its ids asked for before).
      if (c + 2 * Ahead < n)
      {
        Prefetch(mesh.Cell(order.Cells[c + 2 * Ahead]).Address());
      }
      if (c + Ahead < n)
      {
        const CellCorners ahead = mesh.Cell(order.Cells[c + Ahead]);
        for (int k = 0; k < corners; ++k)
        {
          Prefetch(newId + ahead[k]);
        }
        if (mesh.Parent)
        {
          Prefetch(mesh.Parent + order.Cells[c + Ahead]);
        }
      }
      const Index old = order.Cells[c];
      const CellCorners ids = mesh.Cell(old);
      for (int k = 0; k < corners; ++k)
      {
        Index& slot = newId[ids[k]];
        if (slot == Unclaimed)
        {
          slot = next;
          order.Points[next++] = ids[k];
        }
        out[corners * c + k] = static_cast<Id>(slot);
      }
      parent[c] = mesh.ParentOf(old);
    }
    return next;
  }

  /// The passes by ranges of cells (see the class comment): returns the
  /// number of points used.
  Index NumberInTasks(int tasks)
  {
    this->Tasks = tasks;
    this->Words = static_cast<size_t>(this->NP / 64 + 1);
    this->Seen.resize(static_cast<size_t>(tasks));
    this->Used.resize(static_cast<size_t>(tasks));
    this->ListFirstUses();
    this->ClearEarlierRanges();
    const Index next = this->KeepFirstUses();
    this->PlaceFirstUses();
    return next;
  }

  /// Each task's list of the points its range of cells uses, in their
  /// first use there, and the cells with old point ids.
  void ListFirstUses()
  {
    const MeshView& mesh = this->Mesh;
    const SpatialOrder& order = this->Order;
    const int tasks = this->Tasks;
    const int corners = this->Corners;
    Id* out = this->Out;
    Index* parent = this->Parent;
    this->Runner.RunAll(tasks, [&](int t) {
      UninitializedLargeVector<Word>& bits = this->Seen[t];
      bits.resize(this->Words);
      std::fill(bits.begin(), bits.end(), Word(0));
      Word* mine = bits.data();
      LargeVector<Index>& list = this->Used[t];
      list.reserve(static_cast<size_t>((this->NP / tasks) + (this->NP / tasks) / 8 + 16));
      const Index first = RangeBegin(this->N, t, tasks);
      const Index last = RangeBegin(this->N, t + 1, tasks);
      for (Index c = first; c < last; ++c)
      {
        if (c + Ahead < last)
        {
          Prefetch(mesh.Cell(order.Cells[c + Ahead]).Address());
          if (mesh.Parent)
          {
            Prefetch(mesh.Parent + order.Cells[c + Ahead]);
          }
        }
        const Index old = order.Cells[c];
        const CellCorners ids = mesh.Cell(old);
        for (int k = 0; k < corners; ++k)
        {
          const Index p = ids[k];
          Word& w = mine[p >> 6];
          const Word bit = Word(1) << (p & 63);
          if (!(w & bit))
          {
            w |= bit;
            list.push_back(p);
          }
          out[corners * c + k] = static_cast<Id>(p);
        }
        parent[c] = mesh.ParentOf(old);
      }
    });
  }

  /// Each word of the bits, across the tasks in order: the bits of the
  /// ranges before each task's cleared from its own (in ranges of words);
  /// points in no task's set (no cell uses them) marked unclaimed.
  void ClearEarlierRanges()
  {
    const int tasks = this->Tasks;
    const Index np = this->NP;
    Index* newId = this->NewId;
    this->Runner.ForRanges(
      static_cast<Index>(this->Words),
      [&](Index begin, Index end) {
        for (Index w = begin; w < end; ++w)
        {
          Word before = 0;
          for (int t = 0; t < tasks; ++t)
          {
            Word& bits = this->Seen[t][w];
            const Word own = bits;
            bits = own & ~before;
            before |= own;
          }
          for (Index p = 64 * w; p < std::min(np, 64 * w + 64) && before != ~Word(0); ++p)
          {
            if (!((before >> (p & 63)) & 1))
            {
              newId[p] = Unclaimed;
            }
          }
        }
        return 0;
      },
      4096);
  }

  /// Each task keeps the points whose bits remain, in order; they get
  /// consecutive new ids after those of the tasks before it (Offset).
  /// Returns the number of points used.
  Index KeepFirstUses()
  {
    const int tasks = this->Tasks;
    this->Offset.assign(static_cast<size_t>(tasks) + 1, 0);
    this->Runner.RunAll(tasks, [&](int t) {
      const Word* bits = this->Seen[t].data();
      LargeVector<Index>& list = this->Used[t];
      Index kept = 0;
      for (const Index p : list)
      {
        list[kept] = p;
        kept += (bits[p >> 6] >> (p & 63)) & 1;
      }
      list.resize(static_cast<size_t>(kept));
      UninitializedLargeVector<Word>().swap(this->Seen[t]);
      this->Offset[t + 1] = kept;
    });
    for (int t = 0; t < tasks; ++t)
    {
      this->Offset[t + 1] += this->Offset[t];
    }
    return this->Offset[tasks];
  }

  /// Each task copies its list into place and writes its points' new ids;
  /// then the cells' old ids are replaced by their points' new ids.
  void PlaceFirstUses()
  {
    const int tasks = this->Tasks;
    Index* newId = this->NewId;
    this->Runner.RunAll(tasks, [&](int t) {
      const LargeVector<Index>& list = this->Used[t];
      std::copy(list.begin(), list.end(), this->Order.Points.begin() + this->Offset[t]);
      for (size_t i = 0; i < list.size(); ++i)
      {
        newId[list[i]] = this->Offset[t] + static_cast<Index>(i);
      }
    });
    std::vector<LargeVector<Index>>().swap(this->Used);
    const int corners = this->Corners;
    Id* out = this->Out;
    this->Runner.RunAll(tasks, [&](int t) {
      const Index end = corners * RangeBegin(this->N, t + 1, tasks);
      for (Index i = corners * RangeBegin(this->N, t, tasks); i < end; ++i)
      {
        out[i] = static_cast<Id>(newId[static_cast<Index>(out[i])]);
      }
    });
  }

  const MeshView& Mesh;
  SpatialOrder& Order;
  Id* Out;
  Index* Parent;
  const TaskRunner& Runner;
  const Index N;
  const Index NP;
  const int Corners;
  Index* NewId = nullptr;
  // The passes by ranges: per task its bits of the points seen and its list.
  int Tasks = 1;
  size_t Words = 0;
  std::vector<UninitializedLargeVector<Word>> Seen;
  std::vector<LargeVector<Index>> Used;
  std::vector<Index> Offset;
};

/// The renumbered mesh: its cells and points (Renumbering), then the
/// points' coordinates copied in their new order.
template <class Id>
void Renumber(const MeshView& mesh, SpatialOrder& order, double* points, Id* out, Index* parent,
  const TaskRunner& runner)
{
  Renumbering<Id>(mesh, order, out, parent, runner).Run();
  runner.ForRanges(mesh.NumberOfPoints, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
    {
      if (p + Ahead < end)
      {
        Prefetch(mesh.Point(order.Points[p + Ahead]));
      }
      std::copy_n(mesh.Point(order.Points[p]), 3, points + 3 * p);
    }
    return 0;
  });
}
} // namespace

void RenumberMesh(const MeshView& mesh, SpatialOrder& order, double* points, Index* connectivity,
  Index* parent, const TaskRunner& runner)
{
  Renumber(mesh, order, points, connectivity, parent, runner);
}

void RenumberMesh(const MeshView& mesh, SpatialOrder& order, double* points,
  std::int32_t* connectivity, Index* parent, const TaskRunner& runner)
{
  Renumber(mesh, order, points, connectivity, parent, runner);
}
} // namespace mp
