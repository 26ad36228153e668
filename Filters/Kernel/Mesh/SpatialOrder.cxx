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

} // namespace

void OrderAlongCurve(const MeshView& mesh, SpatialOrder& order, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  const Index np = mesh.NumberOfPoints;
  order.Cells.resize(static_cast<size_t>(n));
  if (n < 2 || n > Index(0xffffffff))
  {
    std::iota(order.Cells.begin(), order.Cells.end(), Index(0));
    return; // keys carry the cell id in 32 bits
  }
  // The box of the points (in storage order: no random access), leaving out
  // those no valid mesh has (NaN, infinite, beyond 1e100), and its axes of
  // positive extent.
  const Box box = runner.ForRanges(np, [&](Index begin, Index end) {
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
  int axes[3];
  int dimension = 0;
  double scale[3] = {};
  for (int a = 0; a < 3; ++a)
  {
    if (box.Hi[a] > box.Lo[a])
    {
      axes[dimension++] = a;
    }
  }
  // A 32-bit position: 16 bits per axis in 2D, 10 in 3D (finer than any
  // mesh's cells along an axis; ties keep the old order).
  const int bits = dimension == 3 ? 10 : (dimension == 2 ? 16 : 32);
  for (int k = 0; k < dimension; ++k)
  {
    const int a = axes[k];
    // Just below 2^bits steps, so that the largest point stays inside.
    scale[k] = (std::ldexp(1.0, bits) - 1.0) / (box.Hi[a] - box.Lo[a]);
  }
  const double top = std::ldexp(1.0, bits) - 1.0;
  // Each point's position on the curve (in storage order: no random
  // access), then each cell's key: the lowest of its corners' positions in
  // the high 32 bits, the cell id in the low ones. (A key from the cell's
  // centre read every corner's three coordinates in the old numbering,
  // mostly cache misses, for each cell; the corners'
  // positions are a sixth of the points' bytes, and the order they give
  // keeps the front's search as fast.)
  // (pointKeys, keys and other are written whole by tasks: not zeroed first.)
  UninitializedLargeVector<std::uint32_t> pointKeys(static_cast<size_t>(np));
  runner.ForRanges(np, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
    {
      const double* x = mesh.Point(p);
      std::uint32_t q[3] = {};
      for (int k = 0; k < dimension; ++k)
      {
        const double s = (x[axes[k]] - box.Lo[axes[k]]) * scale[k];
        // NaN and beyond the box (non-finite points) clamped: any key will do.
        q[k] = s > 0 ? static_cast<std::uint32_t>(std::min(s, top)) : 0u;
      }
      pointKeys[p] = static_cast<std::uint32_t>(MortonIndex(q, dimension));
    }
    return 0;
  });
  UninitializedLargeVector<std::uint64_t> keys(static_cast<size_t>(n));
  runner.ForRanges(n, [&](Index begin, Index end) {
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
      keys[c] = (static_cast<std::uint64_t>(lowest) << 32) | static_cast<std::uint64_t>(c);
    }
    return 0;
  });
  UninitializedLargeVector<std::uint32_t>().swap(pointKeys);
  // Least-significant-digit radix sort on the key's 32 bits in three digits
  // of 11, 11 and 10 bits: stable, so equal keys stay in id order. Each
  // task counts and then moves its own range of keys; the buckets' starts
  // are laid out bucket by bucket and, within a bucket, task by task, so
  // that the result is the same for any number of tasks.
  constexpr int Shifts[3] = { 32, 43, 54 };
  constexpr size_t Buckets = 2048;
  const int tasks = runner.TasksFor(n, 16384);
  std::vector<size_t> count(static_cast<size_t>(tasks) * Buckets);
  UninitializedLargeVector<std::uint64_t> other(keys.size());
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
      moves &= inBucket != keys.size();
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
        const std::uint64_t k = keys[i];
        other[start[(k >> shift) & (Buckets - 1)]++] = k;
      }
    });
    keys.swap(other);
  }
  runner.ForRanges(n, [&](Index begin, Index end) {
    for (Index c = begin; c < end; ++c)
    {
      order.Cells[c] = static_cast<Index>(keys[c] & 0xffffffffULL);
    }
    return 0;
  });
}

namespace
{
template <class Id>
void Renumber(const MeshView& mesh, SpatialOrder& order, double* points, Id* out,
  Index* parent, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  const Index np = mesh.NumberOfPoints;
  const int corners = mesh.CornersPerCell();
  // Points are numbered in the order the ordered cells first use them.
  // With one task, in one pass: a point's slot in NewPoint is its new id
  // from its first use on. With several, the ordered cells are split into
  // ranges, one per task, and each task lists the points its cells use in
  // their first use there, a point seen once set in a bit array of the
  // task's own (an eighth of a byte a point, mostly in the core's cache:
  // the tasks share no memory in this pass; slots in one array claimed by
  // atomic exchanges, as first written here, made that pass on a Gmsh mesh
  // of 10^6 cells as long on two threads as on one). A point then belongs to
  // the first range using it: the bits of the ranges before a task's are
  // cleared from its own, its list keeps the points whose bits remain, and
  // the lists, one range after the other, are exactly the serial first-use
  // order; meanwhile `out` holds the old ids (32 bits are enough).
  constexpr Index Unclaimed = std::numeric_limits<Index>::max();
  // (At most 64 tasks: their bits take no more room than NewPoint.)
  const int tasks = static_cast<int>(std::min<Index>(runner.TasksFor(n, 16384), 64));
  order.NewPoint.resize(static_cast<size_t>(np));
  Index* newId = order.NewPoint.data();
  order.Points.resize(static_cast<size_t>(np));
  Index next = 0;
  if (tasks == 1)
  {
    runner.Fill(newId, np, Unclaimed);
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
  }
  else
  {
    using Word = std::uint64_t;
    const size_t words = static_cast<size_t>(np / 64 + 1);
    std::vector<UninitializedLargeVector<Word>> seen(static_cast<size_t>(tasks));
    std::vector<LargeVector<Index>> used(static_cast<size_t>(tasks));
    runner.RunAll(tasks, [&](int t) {
      UninitializedLargeVector<Word>& bits = seen[t];
      bits.resize(words);
      std::fill(bits.begin(), bits.end(), Word(0));
      Word* mine = bits.data();
      LargeVector<Index>& list = used[t];
      list.reserve(static_cast<size_t>((np / tasks) + (np / tasks) / 8 + 16));
      const Index first = RangeBegin(n, t, tasks);
      const Index last = RangeBegin(n, t + 1, tasks);
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
    // Each word of the bits, across the tasks in order: the bits of the
    // ranges before each task's cleared from its own (in ranges of words);
    // points in no task's set (no cell uses them) marked unclaimed.
    runner.ForRanges(static_cast<Index>(words), [&](Index begin, Index end) {
      for (Index w = begin; w < end; ++w)
      {
        Word before = 0;
        for (int t = 0; t < tasks; ++t)
        {
          Word& bits = seen[t][w];
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
    }, 4096);
    // Each task keeps the points whose bits remain, in order; they get
    // consecutive new ids after those of the tasks before it.
    std::vector<Index> offset(static_cast<size_t>(tasks) + 1, 0);
    runner.RunAll(tasks, [&](int t) {
      const Word* bits = seen[t].data();
      LargeVector<Index>& list = used[t];
      Index kept = 0;
      for (const Index p : list)
      {
        list[kept] = p;
        kept += (bits[p >> 6] >> (p & 63)) & 1;
      }
      list.resize(static_cast<size_t>(kept));
      UninitializedLargeVector<Word>().swap(seen[t]);
      offset[t + 1] = kept;
    });
    for (int t = 0; t < tasks; ++t)
    {
      offset[t + 1] += offset[t];
    }
    next = offset[tasks];
    // Each task copies its list into place and writes its points' new ids;
    // then the cells' old ids are replaced by their points' new ids.
    runner.RunAll(tasks, [&](int t) {
      const LargeVector<Index>& list = used[t];
      std::copy(list.begin(), list.end(), order.Points.begin() + offset[t]);
      for (size_t i = 0; i < list.size(); ++i)
      {
        newId[list[i]] = offset[t] + static_cast<Index>(i);
      }
    });
    std::vector<LargeVector<Index>>().swap(used);
    runner.RunAll(tasks, [&](int t) {
      const Index end = corners * RangeBegin(n, t + 1, tasks);
      for (Index i = corners * RangeBegin(n, t, tasks); i < end; ++i)
      {
        out[i] = static_cast<Id>(newId[static_cast<Index>(out[i])]);
      }
    });
  }
  // Points no cell uses: last, in their old order.
  for (Index p = 0; p < np && next < np; ++p)
  {
    Index& id = order.NewPoint[p];
    if (id == Unclaimed)
    {
      id = next;
      order.Points[next++] = p;
    }
  }
  runner.ForRanges(np, [&](Index begin, Index end) {
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

void RenumberMesh(const MeshView& mesh, SpatialOrder& order, double* points,
  Index* connectivity, Index* parent, const TaskRunner& runner)
{
  Renumber(mesh, order, points, connectivity, parent, runner);
}

void RenumberMesh(const MeshView& mesh, SpatialOrder& order, double* points,
  std::int32_t* connectivity, Index* parent, const TaskRunner& runner)
{
  Renumber(mesh, order, points, connectivity, parent, runner);
}
} // namespace mp
