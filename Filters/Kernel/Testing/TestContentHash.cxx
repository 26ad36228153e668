// SPDX-License-Identifier: BSD-3-Clause
// ContentHash and Fnv1a64 (Mesh/ContentHash.h): the values the filter has
// always computed (pinned against a plain serial re-computation and a few
// literal values), the same for any number of tasks.
#include "Mesh/ContentHash.h"

#include "Threads.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
/// The word mix, written out again.
std::uint64_t Mix(std::uint64_t h, std::uint64_t word)
{
  h ^= word + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  h *= 0xBF58476D1CE4E5B9ull;
  return h ^ (h >> 31);
}

/// One block's hash, written out again, serially.
std::uint64_t ReferenceBlock(const unsigned char* b, size_t bytes)
{
  std::uint64_t lane[4] = { 0x452821E638D01377ull, 0xBE5466CF34E90C6Cull, 0xC0AC29B7C97C50DDull,
    0x3F84D5B5B5470917ull };
  size_t i = 0;
  while (i + 32 <= bytes)
  {
    for (int l = 0; l < 4; ++l)
    {
      std::uint64_t w;
      std::memcpy(&w, b + i + 8 * l, 8);
      lane[l] = (lane[l] ^ w) * 0x100000001B3ull;
      lane[l] ^= lane[l] >> 29;
    }
    i += 32;
  }
  std::uint64_t h = 0x243F6A8885A308D3ull;
  while (i + 8 <= bytes)
  {
    std::uint64_t w;
    std::memcpy(&w, b + i, 8);
    h = Mix(h, w);
    i += 8;
  }
  std::uint64_t last = 0;
  std::memcpy(&last, b + i, bytes - i);
  h = Mix(h, last);
  for (std::uint64_t l : lane)
  {
    h = Mix(h, l);
  }
  return h;
}

/// A byte range added to a hash h, serially: its length, then its 1 MiB
/// blocks' hashes in order (one hash for a range of at most one block).
std::uint64_t ReferenceRange(std::uint64_t h, const unsigned char* b, size_t bytes)
{
  const size_t block = size_t(1) << 20;
  h = Mix(h, bytes);
  if (bytes <= block)
  {
    return Mix(h, ReferenceBlock(b, bytes));
  }
  for (size_t from = 0; from < bytes; from += block)
  {
    h = Mix(h, ReferenceBlock(b + from, std::min(block, bytes - from)));
  }
  return h;
}

std::vector<unsigned char> RandomBytes(size_t n, unsigned seed)
{
  std::mt19937_64 random(seed);
  std::vector<unsigned char> bytes(n);
  for (unsigned char& b : bytes)
  {
    b = static_cast<unsigned char>(random());
  }
  return bytes;
}

/// Lengths around every boundary of the block hash: its 32-byte runs, its
/// words, its tail, and one, two and more blocks.
const size_t Lengths[] = { 0, 1, 7, 8, 9, 31, 32, 33, 39, 40, 63, 64, 65, 1000, (1u << 20) - 1,
  1u << 20, (1u << 20) + 1, (2u << 20) + 5, (3u << 20) + (1u << 19) + 3 };
} // namespace

TEST(ContentHash, TheSameAsASerialReComputation)
{
  const std::vector<unsigned char> data =
    RandomBytes(Lengths[sizeof Lengths / sizeof *Lengths - 1], 7);
  for (size_t bytes : Lengths)
  {
    mp::ContentHash hash;
    hash.Add(data.data(), bytes);
    EXPECT_EQ(hash.Hash, ReferenceRange(0x243F6A8885A308D3ull, data.data(), bytes)) << bytes;
    EXPECT_EQ(mp::ContentHash::HashBlock(data.data(), std::min(bytes, mp::ContentHash::BlockBytes)),
      ReferenceBlock(data.data(), std::min(bytes, mp::ContentHash::BlockBytes)))
      << bytes;
  }
  // Words and ranges in one chain, in the order added.
  mp::ContentHash hash;
  hash.Add(std::uint64_t(11));
  hash.Add(data.data(), 100);
  hash.Add(std::uint64_t(0));
  hash.Add(data.data() + 5, (2u << 20) + 1);
  std::uint64_t h = Mix(0x243F6A8885A308D3ull, 11);
  h = ReferenceRange(h, data.data(), 100);
  h = Mix(h, 0);
  h = ReferenceRange(h, data.data() + 5, (2u << 20) + 1);
  EXPECT_EQ(hash.Hash, h);
}

TEST(ContentHash, TheSameForAnyNumberOfTasks)
{
  const std::vector<unsigned char> data = RandomBytes((5u << 20) + 12345, 3);
  const size_t sizes[] = { 100, 1u << 20, (1u << 20) + 1, (3u << 20) + 77, data.size() };
  for (size_t bytes : sizes)
  {
    mp::ContentHash serial;
    serial.Add(data.data(), bytes); // default runner: serial
    for (int tasks : { 1, 2, 3 })
    {
      mp::ContentHash threaded;
      threaded.Add(data.data(), bytes, mptest::ThreadRunner(tasks));
      EXPECT_EQ(threaded.Hash, serial.Hash) << bytes << " bytes, " << tasks << " tasks";
      mp::TaskRunner inTurn; // the tasks one after the other
      inTurn.Tasks = tasks;
      mp::ContentHash ordered;
      ordered.Add(data.data(), bytes, inTurn);
      EXPECT_EQ(ordered.Hash, serial.Hash) << bytes << " bytes, " << tasks << " tasks";
    }
  }
}

TEST(ContentHash, PinnedValues)
{
  // What the filter's Fingerprint (vtkMeshProjectionFilter.cxx at b1b1633,
  // its code run as it was) gives for these bytes: a change here would
  // change the key of every operator the filter keeps.
  mp::ContentHash empty;
  EXPECT_EQ(empty.Hash, 0x243F6A8885A308D3ull);
  std::vector<unsigned char> ramp((2u << 20) + 3);
  for (size_t i = 0; i < ramp.size(); ++i)
  {
    ramp[i] = static_cast<unsigned char>(i * 131u + (i >> 8));
  }
  const size_t lengths[] = { 0, 5, 40, 1000, ramp.size() };
  const std::uint64_t expected[] = { 0xBA1021FC229AD651ull, 0x9E8CAD5C1651582Aull,
    0xABB570BA1F6CEF65ull, 0x25D0D85A76EC0342ull, 0x61BEA391A1E1915Aull };
  for (int k = 0; k < 5; ++k)
  {
    mp::ContentHash hash;
    hash.Add(ramp.data(), lengths[k], mptest::ThreadRunner(2));
    EXPECT_EQ(hash.Hash, expected[k]) << lengths[k];
  }
}

TEST(ContentHash, Fnv1a64)
{
  // The adapter's Fnv1a (vtkPMeshProjectionFilter.cxx), its offset basis
  // 1469598103934665603 included (not FNV's published 14695981039346656037:
  // see ContentHash.h), byte by byte.
  auto adapter = [](const void* data, size_t bytes) {
    std::uint64_t h = 1469598103934665603ull;
    const unsigned char* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i)
    {
      h = (h ^ b[i]) * 1099511628211ull;
    }
    return h;
  };
  EXPECT_EQ(mp::Fnv1a64("", 0), 1469598103934665603ull);
  EXPECT_EQ(mp::Fnv1a64("a", 1), 4953267810257967366ull);
  EXPECT_EQ(mp::Fnv1a64("foobar", 6), 9870438755804841970ull);
  const std::string text = "MeshProjection";
  EXPECT_EQ(mp::Fnv1a64(text.data(), text.size()), adapter(text.data(), text.size()));
  const long long key[3] = { 12, -7, 1LL << 40 };
  EXPECT_EQ(mp::Fnv1a64(key, sizeof key), adapter(key, sizeof key));
  const double x[3] = { 0.1, -2.5, 1e300 };
  EXPECT_EQ(mp::Fnv1a64(x, sizeof x), adapter(x, sizeof x));
}
