// SPDX-License-Identifier: BSD-3-Clause
// 3D: the sides of a tetrahedron's corners from another's face planes
// (FaceSides.h) on cells of a coarse lattice, whose corners often lie on
// the other cell's planes for a reason the coordinates show (a shared
// coordinate plane, a shared corner, an axis-parallel edge): FaceSide gives
// the same values, bit for bit (signed zeros too), as its filter and
// Orient3D alone, and FaceSides the same table and the SideBits of it.
#include "Geometry/FaceSides.h"
#include "Geometry/Predicates.h"

#include "TetrahedronPairs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using mp::TetrahedronIntersector;
using mptest::PreparedPair;
using mptest::SameBits;

namespace
{
/// FaceSide as it was without the coordinates' shortcut: the filter by
/// the prepared normal, else Orient3D (sign flipped for even faces).
double FilterOrOrient3D(const TetrahedronIntersector::Cell& c, int k, const double* x)
{
  const double* a = c.X[(k + 1) % 4];
  const double w[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
  const double d = c.Normal[k][0] * w[0] + c.Normal[k][1] * w[1] + c.Normal[k][2] * w[2];
  const double size = std::max({ std::fabs(w[0]), std::fabs(w[1]), std::fabs(w[2]) });
  if (std::fabs(d) > c.SideBound[k] * size)
  {
    return d;
  }
  const double o = mp::Orient3D(a, c.X[(k + 2) % 4], c.X[(k + 3) % 4], x);
  return (k % 2) ? o : -o;
}
} // namespace

TEST(FaceSides, LatticeCornersAsTheFilterAndOrient3D)
{
  std::mt19937 rng(5);
  // Coordinates i / 3 (not exact in binary, but equal where they are
  // meant to be), and a few i / 7 between them for planes no axis explains.
  std::uniform_int_distribution<int> pick(0, 4);
  auto coordinate = [&]() {
    const int i = pick(rng);
    return i == 4 ? 2.0 / 7.0 : i / 3.0;
  };
  int pairs = 0;
  int zeros = 0;
  int shown = 0; // of them, on the plane by their coordinates
  for (int n = 0; n < 20000; ++n)
  {
    double t[4][3];
    double s[4][3];
    for (auto& x : t)
      for (double& c : x)
        c = coordinate();
    for (auto& x : s)
      for (double& c : x)
        c = coordinate();
    TetrahedronIntersector::Cell a;
    TetrahedronIntersector::Cell b;
    if (!PreparedPair(t, s, a, b))
      continue;
    ++pairs;
    double sides[4][4];
    mp::clipping::SideBits bits;
    mp::clipping::FaceSides(a, b, mp::clipping::PairExtent(a, b), sides, bits);
    for (int k = 0; k < 4; ++k)
    {
      for (int v = 0; v < 4; ++v)
      {
        const double expected = FilterOrOrient3D(a, k, b.X[v]);
        zeros += expected == 0.0;
        const double* face[3] = { a.X[(k + 1) % 4], a.X[(k + 2) % 4], a.X[(k + 3) % 4] };
        shown += mp::clipping::OnFacePlaneByCoordinates(face[0], face[1], face[2], b.X[v]);
        ASSERT_TRUE(SameBits(mp::clipping::FaceSide(a, k, b.X[v]), expected))
          << "pair " << n << " face " << k << " corner " << v;
        ASSERT_TRUE(SameBits(sides[k][v], expected)) << "pair " << n;
      }
    }
    mp::clipping::SideBits table;
    mp::clipping::GetSideBits(sides, table);
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_EQ(bits.Negative[k], table.Negative[k]);
      EXPECT_EQ(bits.NotPositive[k], table.NotPositive[k]);
      EXPECT_EQ(bits.Zero[k], table.Zero[k]);
    }
  }
  // Enough cells, and corners on the planes among them, most of them
  // shown by their coordinates, some not.
  EXPECT_GT(pairs, 10000);
  EXPECT_GT(shown, 10000);
  EXPECT_GT(zeros, shown);
  std::printf(
    "%d pairs, %d corners on a plane, %d of them by their coordinates\n", pairs, zeros, shown);
}
