// SPDX-License-Identifier: BSD-3-Clause
// SumInBlocks (Mesh/BlockSums.h): per component, blocks of 2^14 terms each
// summed on its own, then the blocks' sums in order; the same bits for any
// number of tasks.
#include "Mesh/BlockSums.h"

#include "Threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace
{
/// Terms of very different sizes and both signs: their sum depends on the
/// order of the additions.
std::vector<double> Terms(mp::Index n, int nc, unsigned seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::vector<double> terms(static_cast<size_t>(n * nc));
  for (double& t : terms)
  {
    t = std::ldexp(mantissa(random), exponent(random));
  }
  return terms;
}

/// The sums written out again, serially: block after block, each from 0.0.
std::vector<double> Reference(const std::vector<double>& terms, mp::Index n, int nc)
{
  std::vector<double> total(static_cast<size_t>(nc), 0.0);
  for (mp::Index begin = 0; begin < n; begin += 16384)
  {
    for (int k = 0; k < nc; ++k)
    {
      double block = 0.0;
      for (mp::Index i = begin; i < std::min(n, begin + 16384); ++i)
      {
        block += terms[static_cast<size_t>(i * nc + k)];
      }
      total[static_cast<size_t>(k)] += block;
    }
  }
  return total;
}

/// Bit for bit (EXPECT_EQ on doubles would take -0.0 for 0.0).
void ExpectSameBits(const std::vector<double>& a, const std::vector<double>& b, const char* what)
{
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_EQ(std::memcmp(&a[k], &b[k], sizeof(double)), 0)
      << what << " component " << k << ": " << a[k] << " and " << b[k];
  }
}
} // namespace

TEST(BlockSums, TheSerialBlockSumsForAnyNumberOfTasks)
{
  const mp::Index sizes[] = { 0, 1, 16383, 16384, 16385, 5 * 16384 + 123, 11 * 16384 };
  for (int nc : { 1, 3 })
  {
    for (mp::Index n : sizes)
    {
      const std::vector<double> terms = Terms(n, nc, static_cast<unsigned>(n + nc));
      auto term = [&](mp::Index i, int k) { return terms[static_cast<size_t>(i * nc + k)]; };
      const std::vector<double> expected = Reference(terms, n, nc);
      ExpectSameBits(mp::SumInBlocks(n, nc, mp::TaskRunner(), term), expected, "serial");
      for (int tasks : { 1, 2, 3, 7 })
      {
        ExpectSameBits(
          mp::SumInBlocks(n, nc, mptest::ThreadRunner(tasks), term), expected, "threads");
        mp::TaskRunner inTurn; // the tasks' ranges one after the other
        inTurn.Tasks = tasks;
        ExpectSameBits(mp::SumInBlocks(n, nc, inTurn, term), expected, "in turn");
      }
    }
  }
}

TEST(BlockSums, OneBlockIsThePlainSum)
{
  const mp::Index n = 16384;
  const std::vector<double> terms = Terms(n, 1, 5);
  double plain = 0.0;
  for (double t : terms)
  {
    plain += t;
  }
  const std::vector<double> sum =
    mp::SumInBlocks(n, 1, mptest::ThreadRunner(4), [&](mp::Index i, int) { return terms[i]; });
  ASSERT_EQ(sum.size(), 1u);
  EXPECT_EQ(sum[0], plain);
}

TEST(BlockSums, NoTermsNoComponents)
{
  EXPECT_EQ(mp::SumInBlocks(0, 2, mp::TaskRunner(), [](mp::Index, int) { return 1.0; }),
    std::vector<double>(2, 0.0));
  EXPECT_TRUE(
    mp::SumInBlocks(100, 0, mp::TaskRunner(), [](mp::Index, int) { return 1.0; }).empty());
}
