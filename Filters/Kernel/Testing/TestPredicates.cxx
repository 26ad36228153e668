// SPDX-License-Identifier: BSD-3-Clause
#include "Geometry/Predicates.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace
{
int Sign(double v)
{
  return (v > 0) - (v < 0);
}
} // namespace

TEST(Predicates, SimpleOrientations)
{
  const double a[2] = { 0, 0 };
  const double b[2] = { 1, 0 };
  const double c[2] = { 0, 1 };
  EXPECT_DOUBLE_EQ(mp::Orient2D(a, b, c), 1.0);
  EXPECT_DOUBLE_EQ(mp::Orient2D(a, c, b), -1.0);
  const double onLine[2] = { 0.5, 0 };
  EXPECT_EQ(mp::Orient2D(a, b, onLine), 0.0);
}

// Points on the line y = x, perturbed by one ulp: floating-point evaluation
// gets many of these wrong; the exact result is known by construction.
TEST(Predicates, NearlyCollinearIsExact)
{
  const double b[2] = { 12.0, 12.0 };
  const double c[2] = { 24.0, 24.0 };
  int wrongNaive = 0;
  for (int i = 0; i < 64; ++i)
  {
    for (int j = 0; j < 64; ++j)
    {
      double p[2] = { 0.5, 0.5 };
      for (int k = 0; k < i; ++k)
        p[0] = std::nextafter(p[0], 1.0);
      for (int k = 0; k < j; ++k)
        p[1] = std::nextafter(p[1], 1.0);
      // p lies on y = x iff i == j; above it (left of b -> c) iff j > i.
      const int expected = (j > i) - (j < i);
      EXPECT_EQ(Sign(mp::Orient2D(b, c, p)), expected) << i << " " << j;
      EXPECT_EQ(Sign(mp::Orient2DExact(b, c, p)), expected);
      const double naive = (b[0] - p[0]) * (c[1] - p[1]) - (b[1] - p[1]) * (c[0] - p[0]);
      wrongNaive += Sign(naive) != expected;
    }
  }
  // The test is only meaningful if plain floating point fails here.
  EXPECT_GT(wrongNaive, 0);
}

TEST(Predicates, AntisymmetryAndCyclicInvariance)
{
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> grid(-4, 4);
  for (int n = 0; n < 20000; ++n)
  {
    // Points on a coarse lattice scaled by an awkward factor: many exact
    // collinearities, where only exact arithmetic is consistent.
    const double s = 0.1;
    const double a[2] = { s * grid(rng), s * grid(rng) };
    const double b[2] = { s * grid(rng), s * grid(rng) };
    const double p[2] = { s * grid(rng), s * grid(rng) };
    const int o = Sign(mp::Orient2D(a, b, p));
    EXPECT_EQ(o, Sign(mp::Orient2D(b, p, a)));
    EXPECT_EQ(o, Sign(mp::Orient2D(p, a, b)));
    EXPECT_EQ(-o, Sign(mp::Orient2D(b, a, p)));
    EXPECT_EQ(Sign(mp::Orient2D(a, b, p)), Sign(mp::Orient2DExact(a, b, p)));
  }
}
