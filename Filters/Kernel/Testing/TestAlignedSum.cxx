// SPDX-License-Identifier: BSD-3-Clause
// Directions known up to sign (Mesh/AlignedSum.h): the serial aligned sum,
// and parts of it made apart (processes), aligned on the principal axis of
// their outer products before they are added.
#include "Mesh/AlignedSum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
/// The angle between the lines of a and b (0 when parallel, either sign).
double LineAngle(const double* a, const double* b)
{
  const double c = std::fabs(mp::Dot(a, b)) / std::sqrt(mp::Dot(a, a) * mp::Dot(b, b));
  return std::acos(std::min(1.0, c));
}

/// Chords of a helix's turn at n points, every other one reversed.
std::vector<double> Chords(int n)
{
  std::vector<double> w;
  for (int i = 0; i < n; ++i)
  {
    const double t0 = 0.1 * i, t1 = 0.1 * (i + 1);
    const double sign = i % 2 == 0 ? 1.0 : -1.0;
    w.push_back(sign * (std::cos(t1) - std::cos(t0)));
    w.push_back(sign * (std::sin(t1) - std::sin(t0)));
    w.push_back(sign * 0.05);
  }
  return w;
}
} // namespace

TEST(AlignedSum, FlipsTermsThatPointAgainstTheSum)
{
  double sum[3] = { 0.0, 0.0, 0.0 };
  const double a[3] = { 1.0, 0.1, 0.0 };
  const double b[3] = { -1.0, 0.1, 0.0 };
  mp::AddAligned(sum, a);
  mp::AddAligned(sum, b);
  EXPECT_EQ(sum[0], 2.0);
  EXPECT_EQ(sum[1], 0.0);
  EXPECT_EQ(sum[2], 0.0);
}

TEST(AlignedSum, PrincipalAxisOfOneOuterProductIsItsVector)
{
  const double s[3] = { 0.3, -2.0, 0.7 };
  double m[6] = { 0, 0, 0, 0, 0, 0 };
  mp::AddOuter(m, s);
  double axis[3];
  mp::PrincipalAxis(m, axis);
  EXPECT_NEAR(mp::Dot(axis, axis), 1.0, 1e-15);
  EXPECT_LT(LineAngle(axis, s), 1e-12);
  const double zero[6] = { 0, 0, 0, 0, 0, 0 };
  mp::PrincipalAxis(zero, axis);
  EXPECT_EQ(mp::Dot(axis, axis), 0.0);
}

TEST(AlignedSum, PartsOfOppositeSignsAlignedOnTheAxisGiveTheSerialDirection)
{
  // Serial: every chord into one aligned sum. Parts: the chords split in
  // two, each part's own aligned sum, the second part negated (its sign is
  // its own); summed plainly they cancel, aligned on the axis they do not.
  const std::vector<double> w = Chords(8);
  double serial[3] = { 0, 0, 0 }, parts[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } };
  for (int i = 0; i < 8; ++i)
  {
    mp::AddAligned(serial, &w[3 * i]);
    mp::AddAligned(parts[i < 4 ? 0 : 1], &w[3 * i]);
  }
  for (double& v : parts[1])
  {
    v = -v;
  }
  double m[6] = { 0, 0, 0, 0, 0, 0 };
  mp::AddOuter(m, parts[0]);
  mp::AddOuter(m, parts[1]);
  double axis[3], sum[3];
  mp::PrincipalAxis(m, axis);
  for (double* part : parts)
  {
    mp::AlignWithAxis(part, axis);
  }
  for (int k = 0; k < 3; ++k)
  {
    sum[k] = parts[0][k] + parts[1][k];
  }
  EXPECT_LT(LineAngle(sum, serial), 1e-12);
  double plain[3];
  for (int k = 0; k < 3; ++k)
  {
    plain[k] = parts[0][k] - parts[1][k]; // (the parts as they were: one negated)
  }
  EXPECT_GT(LineAngle(plain, serial), 0.1);
}
