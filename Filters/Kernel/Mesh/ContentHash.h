// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ContentHash.h
 * @brief 64-bit hashes of the contents of arrays: ContentHash, a chained
 *        word mix with block-wise hashing of byte ranges in tasks, and
 *        Fnv1a64 for short keys.
 *
 * The filter keeps an operator from one time step to the next while the
 * meshes stay the same; readers build new arrays at every step, so the
 * test is on the arrays' values, not their addresses: a ContentHash of the
 * points, cells and the like. A mesh's arrays are tens of MiB, and one
 * chain of multiplies through all of them is a serial dependency as long
 * as the data; so a byte range is cut into blocks of BlockBytes, each
 * hashed on its own (four interleaved chains, whose multiplies do not wait
 * for each other) in the runner's tasks, and the blocks' hashes are added
 * to the chain in block order: the same value for any number of tasks.
 *
 * Not a cryptographic hash: equal contents give equal values, and a change
 * is missed only by a 64-bit collision.
 *
 * Fnv1a64 is the plain FNV-1a loop (64 bits) over a few bytes: keys of
 * hash tables and of the MPI filter's routing (a point's coordinates, a
 * cell's ids), where a block's setup would cost more than the key.
 *
 * In Mesh, the lowest room: it needs only the runner (Tasks.h), and the
 * VTK adapter hashes its arrays with it.
 */
#ifndef MeshProjection_Kernel_ContentHash_h
#define MeshProjection_Kernel_ContentHash_h

#include "Mesh/MeshView.h"
#include "Mesh/Tasks.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace mp
{
/**
 * FNV-1a, 64 bits, over data[0..bytes): from h = 1469598103934665603,
 * h = (h ^ byte) * 1099511628211 byte by byte.
 *
 * Note the offset basis: the adapter's Fnv1a (vtkPMeshProjectionFilter.cxx)
 * has always started from 1469598103934665603, one digit short of FNV's
 * published 14695981039346656037, so the published test vectors do not
 * hold. It is kept: this function gives the adapter's values (the MPI
 * filter routes keys to processes by them), and any odd start is as good
 * for a hash table. (Named with its width so that it does not meet a
 * file's own Fnv1a.)
 */
inline std::uint64_t Fnv1a64(const void* data, size_t bytes)
{
  std::uint64_t h = 1469598103934665603ull;
  const unsigned char* b = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i)
  {
    h = (h ^ b[i]) * 1099511628211ull;
  }
  return h;
}

/**
 * A 64-bit hash of a sequence of words and byte ranges, in the order they
 * are added. Start from a default ContentHash (Hash = Seed), Add what
 * identifies the contents, read Hash. The values are fixed: the same input
 * gives the same Hash on every run, build and number of tasks of one byte
 * order (callers may compare it with one kept from an earlier step).
 *
 * A wrapper that adds its own kinds of input (the adapter's VTK arrays)
 * can hold one, or derive from it with `using ContentHash::Add;` so that
 * its own Add overloads do not hide these.
 */
struct ContentHash
{
  /// The value of an empty hash.
  static constexpr std::uint64_t Seed = 0x243F6A8885A308D3ull;
  /// Bytes per block of Add(data, bytes, runner): 1 MiB.
  static constexpr size_t BlockBytes = size_t(1) << 20;

  std::uint64_t Hash = Seed;

  /// Mixes one word into the chain:
  ///   h ^= word + 0x9E3779B97F4A7C15 + (h << 6) + (h >> 2);
  ///   h *= 0xBF58476D1CE4E5B9; h ^= h >> 31.
  void Add(std::uint64_t word)
  {
    this->Hash ^= word + 0x9E3779B97F4A7C15ull + (this->Hash << 6) + (this->Hash >> 2);
    this->Hash *= 0xBF58476D1CE4E5B9ull;
    this->Hash ^= this->Hash >> 31;
  }

  /**
   * Adds data[0..bytes): first the length (Add(bytes)), then the hash of
   * each block of BlockBytes (HashBlock; the last one shorter), in block
   * order. The blocks are hashed in `runner`'s tasks, a range of whole
   * blocks each (one block, or none: no tasks). `data` may be null when
   * bytes is 0.
   */
  void Add(const void* data, size_t bytes, const TaskRunner& runner = TaskRunner())
  {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    this->Add(static_cast<std::uint64_t>(bytes));
    const size_t blocks = (bytes + BlockBytes - 1) / BlockBytes;
    if (blocks <= 1)
    {
      this->Add(HashBlock(b, bytes));
      return;
    }
    std::vector<std::uint64_t> hashes(blocks);
    const Index n = static_cast<Index>(blocks);
    const int tasks = runner.TasksFor(n, 1);
    runner.RunAll(tasks, [&](int task) {
      for (Index k = RangeBegin(n, task, tasks); k < RangeBegin(n, task + 1, tasks); ++k)
      {
        const size_t from = static_cast<size_t>(k) * BlockBytes;
        hashes[static_cast<size_t>(k)] = HashBlock(b + from, std::min(BlockBytes, bytes - from));
      }
    });
    for (std::uint64_t h : hashes)
    {
      this->Add(h);
    }
  }

  /**
   * The hash of one block on its own: four chains over its 32-byte runs
   * (interleaved: their multiplies do not wait for each other), then a
   * fresh ContentHash takes the remaining 8-byte words, the last 0-7 bytes
   * as one word (zero-padded), and the four chains; its Hash is the
   * block's. Words are read with memcpy, in the host's byte order.
   */
  static std::uint64_t HashBlock(const void* data, size_t bytes)
  {
    const unsigned char* b = static_cast<const unsigned char*>(data);
    std::uint64_t h[4] = { 0x452821E638D01377ull, 0xBE5466CF34E90C6Cull, 0xC0AC29B7C97C50DDull,
      0x3F84D5B5B5470917ull };
    size_t i = 0;
    for (; i + 32 <= bytes; i += 32)
    {
      for (int l = 0; l < 4; ++l)
      {
        std::uint64_t w;
        std::memcpy(&w, b + i + 8 * l, 8);
        h[l] = (h[l] ^ w) * 0x100000001B3ull;
        h[l] ^= h[l] >> 29;
      }
    }
    ContentHash block;
    for (; i + 8 <= bytes; i += 8)
    {
      std::uint64_t w;
      std::memcpy(&w, b + i, 8);
      block.Add(w);
    }
    std::uint64_t last = 0;
    if (bytes > i)
    {
      std::memcpy(&last, b + i, bytes - i);
    }
    block.Add(last);
    for (std::uint64_t lane : h)
    {
      block.Add(lane);
    }
    return block.Hash;
  }
};
} // namespace mp

#endif
