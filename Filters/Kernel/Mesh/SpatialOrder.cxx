// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh/SpatialOrder.h"

#include <algorithm>
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

void Centre(const MeshView& mesh, Index c, double x[3])
{
  const int corners = mesh.CornersPerCell();
  const Index* ids = mesh.Cell(c);
  x[0] = x[1] = x[2] = 0.0;
  for (int k = 0; k < corners; ++k)
  {
    const double* p = mesh.Point(ids[k]);
    x[0] += p[0];
    x[1] += p[1];
    x[2] += p[2];
  }
  x[0] /= corners;
  x[1] /= corners;
  x[2] /= corners;
}
} // namespace

void OrderAlongCurve(const MeshView& mesh, SpatialOrder& order, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  const Index np = mesh.NumberOfPoints;
  order.Cells.resize(static_cast<size_t>(n));
  std::iota(order.Cells.begin(), order.Cells.end(), Index(0));
  if (n < 2 || n > Index(0xffffffff))
  {
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
  // Key in the high 32 bits, cell id in the low ones.
  std::vector<std::uint64_t> keys(static_cast<size_t>(n));
  runner.ForRanges(n, [&](Index begin, Index end) {
    const int corners = mesh.CornersPerCell();
    for (Index c = begin; c < end; ++c)
    {
      if (c + Ahead < end)
      {
        const Index* ahead = mesh.Cell(c + Ahead);
        for (int k = 0; k < corners; ++k)
        {
          Prefetch(mesh.Point(ahead[k]));
        }
      }
      double x[3];
      Centre(mesh, c, x);
      std::uint32_t q[3] = {};
      for (int k = 0; k < dimension; ++k)
      {
        const double s = (x[axes[k]] - box.Lo[axes[k]]) * scale[k];
        // NaN and beyond the box (non-finite points) clamped: any key will do.
        q[k] = s > 0 ? static_cast<std::uint32_t>(std::min(s, top)) : 0u;
      }
      keys[c] = (MortonIndex(q, dimension) << 32) | static_cast<std::uint64_t>(c);
    }
    return 0;
  });
  // Least-significant-digit radix sort on the key's 32 bits in three digits
  // of 11, 11 and 10 bits, the three histograms counted in one pass: stable,
  // so equal keys stay in id order.
  constexpr int Shifts[3] = { 32, 43, 54 };
  constexpr size_t Buckets = 2048;
  std::vector<size_t> count(3 * (Buckets + 1), 0);
  for (std::uint64_t k : keys)
  {
    for (int d = 0; d < 3; ++d)
    {
      ++count[d * (Buckets + 1) + ((k >> Shifts[d]) & (Buckets - 1)) + 1];
    }
  }
  std::vector<std::uint64_t> other(keys.size());
  for (int d = 0; d < 3; ++d)
  {
    size_t* start = count.data() + d * (Buckets + 1);
    if (start[1 + ((keys[0] >> Shifts[d]) & (Buckets - 1))] == keys.size())
    {
      continue; // one value of this digit: nothing moves
    }
    for (size_t b = 0; b < Buckets; ++b)
    {
      start[b + 1] += start[b];
    }
    for (std::uint64_t k : keys)
    {
      other[start[(k >> Shifts[d]) & (Buckets - 1)]++] = k;
    }
    keys.swap(other);
  }
  for (Index c = 0; c < n; ++c)
  {
    order.Cells[c] = static_cast<Index>(keys[c] & 0xffffffffULL);
  }
}

double NumberingSpread(const MeshView& mesh)
{
  const Index n = mesh.NumberOfCells;
  if (n < 2 || mesh.NumberOfPoints < 2)
  {
    return 0.0;
  }
  const int corners = mesh.CornersPerCell();
  const Index samples = std::min<Index>(n - 1, 4096);
  std::vector<Index> spread(static_cast<size_t>(samples));
  std::vector<Index> jump(static_cast<size_t>(samples));
  auto lowest = [&](Index c) { return *std::min_element(mesh.Cell(c), mesh.Cell(c) + corners); };
  for (Index s = 0; s < samples; ++s)
  {
    const Index c = (n - 1) * s / samples;
    const Index* ids = mesh.Cell(c);
    spread[s] = *std::max_element(ids, ids + corners) - lowest(c);
    jump[s] = std::abs(lowest(c + 1) - lowest(c));
  }
  const auto middle = static_cast<std::ptrdiff_t>(samples / 2);
  std::nth_element(spread.begin(), spread.begin() + middle, spread.end());
  std::nth_element(jump.begin(), jump.begin() + middle, jump.end());
  return static_cast<double>(std::max(spread[middle], jump[middle])) /
    static_cast<double>(mesh.NumberOfPoints);
}

double ChainedFraction(const MeshView& mesh)
{
  const Index n = mesh.NumberOfCells;
  if (n < 2)
  {
    return 1.0;
  }
  const int corners = mesh.CornersPerCell();
  const Index samples = std::min<Index>(n, 4096);
  const Index reach = 4;
  Index chained = 0;
  for (Index s = 0; s < samples; ++s)
  {
    const Index c = (n - 1) * s / std::max<Index>(1, samples - 1);
    const Index* ids = mesh.Cell(c);
    bool found = false;
    for (Index o = std::max<Index>(0, c - reach); o <= std::min(n - 1, c + reach) && !found; ++o)
    {
      if (o == c)
      {
        continue;
      }
      const Index* other = mesh.Cell(o);
      int common = 0;
      for (int a = 0; a < corners; ++a)
      {
        common += std::count(other, other + corners, ids[a]) > 0;
      }
      found = common >= corners - 1;
    }
    chained += found;
  }
  return static_cast<double>(chained) / static_cast<double>(samples);
}

void RenumberMesh(const MeshView& mesh, SpatialOrder& order, double* points,
  Index* connectivity, Index* parent, const TaskRunner& runner)
{
  const Index n = mesh.NumberOfCells;
  const Index np = mesh.NumberOfPoints;
  const int corners = mesh.CornersPerCell();
  // Points in the order the ordered cells first use them, numbered while
  // the cells are copied (one pass over the old cells).
  order.NewPoint.assign(static_cast<size_t>(np), -1);
  order.Points.resize(static_cast<size_t>(np));
  Index next = 0;
  for (Index c = 0; c < n; ++c)
  {
    // Two stages of prefetching: the connectivity of the cell 2 * Ahead
    // on, the point slots of the one Ahead on (its ids asked for before).
    if (c + 2 * Ahead < n)
    {
      Prefetch(mesh.Cell(order.Cells[c + 2 * Ahead]));
    }
    if (c + Ahead < n)
    {
      const Index* ahead = mesh.Cell(order.Cells[c + Ahead]);
      for (int k = 0; k < corners; ++k)
      {
        Prefetch(&order.NewPoint[ahead[k]]);
      }
      if (mesh.Parent)
      {
        Prefetch(mesh.Parent + order.Cells[c + Ahead]);
      }
    }
    const Index old = order.Cells[c];
    const Index* ids = mesh.Cell(old);
    for (int k = 0; k < corners; ++k)
    {
      Index& p = order.NewPoint[ids[k]];
      if (p < 0)
      {
        p = next;
        order.Points[next++] = ids[k];
      }
      connectivity[corners * c + k] = p;
    }
    parent[c] = mesh.ParentOf(old);
  }
  for (Index p = 0; p < np; ++p)
  {
    if (order.NewPoint[p] < 0)
    {
      order.NewPoint[p] = next;
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
} // namespace mp
