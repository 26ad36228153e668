// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TetrahedronPairs.h
 * @brief Pairs of tetrahedra for the 3D clip's tests: two cells as a
 *        two-cell mesh, random pairs, prepared pairs, and a bitwise
 *        comparison of doubles.
 */
#ifndef MeshProjection_Kernel_Testing_TetrahedronPairs_h
#define MeshProjection_Kernel_Testing_TetrahedronPairs_h

#include "Geometry/TetrahedronIntersector.h"

#include "GeneratedMeshes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace mptest
{
/// Target t (cell 0) and source s (cell 1) as one mesh on their 8 corners.
inline TestMesh TwoTetrahedra(const double t[4][3], const double s[4][3])
{
  TestMesh m;
  m.Dimension = 3;
  for (int k = 0; k < 4; ++k)
    m.Points.insert(m.Points.end(), { t[k][0], t[k][1], t[k][2] });
  for (int k = 0; k < 4; ++k)
    m.Points.insert(m.Points.end(), { s[k][0], s[k][1], s[k][2] });
  m.Cells = { 0, 1, 2, 3, 4, 5, 6, 7 };
  return m;
}

/// A random pair: t's corners in [-1, 1]^3, s's in [-scale, scale]^3 (t's drawn first).
inline void RandomPair(std::mt19937& rng, double scale, double (&t)[4][3], double (&s)[4][3])
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& x : t)
    for (double& c : x)
      c = u(rng);
  for (auto& x : s)
    for (double& c : x)
      c = scale * u(rng);
}

/// The cells of TwoTetrahedra(t, s), prepared; false (skip the pair) when
/// either has a volume below 1e-4.
inline bool PreparedPair(const double t[4][3], const double s[4][3],
  mp::TetrahedronIntersector::Cell& a, mp::TetrahedronIntersector::Cell& b)
{
  const TestMesh m = TwoTetrahedra(t, s);
  if (m.CellVolume(0) < 1e-4 || m.CellVolume(1) < 1e-4)
    return false;
  EXPECT_TRUE(mp::TetrahedronIntersector::Prepare(m.View(false), 0, a));
  EXPECT_TRUE(mp::TetrahedronIntersector::Prepare(m.View(false), 1, b));
  return true;
}

/// Whether two doubles are the same bits (signed zeros and NaN payloads apart).
inline bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}
} // namespace mptest

#endif
