// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Marshal.h
 * @brief What the processes send each other, as bytes: values appended to
 *        and read back from buffers, and a point's identity across
 *        processes (not public, not wrapped).
 *
 * Buffers are plain bytes (std::vector<char>) so that one exchange
 * (MPIParts::AllToAll) carries any trivially copyable values; the reader
 * knows the type, as the writer did. A point is known across processes by
 * its global id or, without ids, by the bits of its coordinates (-0 read
 * as 0): two processes' copies of one point are the same double values,
 * since they come from one mesh split into parts.
 */
#ifndef MeshProjection_Parallel_Marshal_h
#define MeshProjection_Parallel_Marshal_h

#include "Mesh/ContentHash.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace mpvtk
{
/// A point's identity across processes: its global id, or its coordinates' bits.
struct PointKey
{
  double X[3];
  bool operator==(const PointKey& o) const { return std::memcmp(this->X, o.X, sizeof X) == 0; }
};

/// Hashes a point key (for unordered maps of points): FNV-1a over its bytes. (for unordered maps of points).
struct PointKeyHash
{
  size_t operator()(const PointKey& k) const
  {
    return static_cast<size_t>(mp::Fnv1a64(k.X, sizeof k.X));
  }
};

/// The key of a point known by its coordinates.
inline PointKey KeyOf(const double* x)
{
  PointKey k;
  for (int d = 0; d < 3; ++d)
  {
    k.X[d] = x[d] == 0.0 ? 0.0 : x[d]; // -0 is 0
  }
  return k;
}

/// Appends `count` values to `buffer`, as their bytes.
template <class T>
void Append(std::vector<char>& buffer, const T* values, size_t count)
{
  const size_t at = buffer.size();
  buffer.resize(at + count * sizeof(T));
  if (count)
  {
    std::memcpy(buffer.data() + at, values, count * sizeof(T));
  }
}

/// The values of type T that `buffer` holds (a trailing part of one is dropped).
template <class T>
std::vector<T> Read(const std::vector<char>& buffer)
{
  std::vector<T> values(buffer.size() / sizeof(T));
  if (!values.empty())
  {
    std::memcpy(values.data(), buffer.data(), values.size() * sizeof(T));
  }
  return values;
}
} // namespace mpvtk

#endif
