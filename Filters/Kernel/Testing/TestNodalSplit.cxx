// SPDX-License-Identifier: BSD-3-Clause
// Second-order cells split on their own nodes (Geometry/NodalSplit.h): on
// straight reference and random affine cells the simplices fill the cell
// exactly, use every node, keep the cell's orientation, and two cells
// sharing a face split it alike whatever the keys; folded curved cells are
// refused.
#include "Geometry/NodalSplit.h"
#include "Geometry/Predicates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <vector>

using mp::Index;
using mp::NodalType;
using mp::SplitStatus;

namespace
{
/// The nodes' parametric coordinates, as VTK gives them
/// (vtkQuadraticTetra::GetParametricCoords() etc., VTK 9.2).
std::vector<std::array<double, 3>> Reference(NodalType type)
{
  switch (type)
  {
    case NodalType::Edge3:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { .5, 0, 0 } };
    case NodalType::Triangle6:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { .5, 0, 0 }, { .5, .5, 0 }, { 0, .5, 0 } };
    case NodalType::Quad8:
    case NodalType::Quad9:
    {
      std::vector<std::array<double, 3>> x = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
        { .5, 0, 0 }, { 1, .5, 0 }, { .5, 1, 0 }, { 0, .5, 0 } };
      if (type == NodalType::Quad9)
      {
        x.push_back({ .5, .5, 0 });
      }
      return x;
    }
    case NodalType::Tetra10:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { .5, 0, 0 }, { .5, .5, 0 },
        { 0, .5, 0 }, { 0, 0, .5 }, { .5, 0, .5 }, { 0, .5, .5 } };
    case NodalType::Hexa20:
    case NodalType::Hexa27:
    {
      std::vector<std::array<double, 3>> x = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
        { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 }, { .5, 0, 0 }, { 1, .5, 0 },
        { .5, 1, 0 }, { 0, .5, 0 }, { .5, 0, 1 }, { 1, .5, 1 }, { .5, 1, 1 }, { 0, .5, 1 },
        { 0, 0, .5 }, { 1, 0, .5 }, { 1, 1, .5 }, { 0, 1, .5 } };
      if (type == NodalType::Hexa27)
      {
        x.insert(x.end(),
          { { 0, .5, .5 }, { 1, .5, .5 }, { .5, 0, .5 }, { .5, 1, .5 }, { .5, .5, 0 },
            { .5, .5, 1 }, { .5, .5, .5 } });
      }
      return x;
    }
    case NodalType::Wedge15:
    case NodalType::Wedge18:
    {
      std::vector<std::array<double, 3>> x = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 },
        { 1, 0, 1 }, { 0, 1, 1 }, { .5, 0, 0 }, { .5, .5, 0 }, { 0, .5, 0 }, { .5, 0, 1 },
        { .5, .5, 1 }, { 0, .5, 1 }, { 0, 0, .5 }, { 1, 0, .5 }, { 0, 1, .5 } };
      if (type == NodalType::Wedge18)
      {
        x.insert(x.end(), { { .5, 0, .5 }, { .5, .5, .5 }, { 0, .5, .5 } });
      }
      return x;
    }
    case NodalType::Pyramid13:
      // VTK's parametric coordinates collapse the top face to the apex
      // (its mid nodes 9-12 at (x, y, 0.5) of their base corners): the
      // geometric pyramid with the same apex and its edges' midpoints.
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { .5, 0, 0 },
        { 1, .5, 0 }, { .5, 1, 0 }, { 0, .5, 0 }, { 0, 0, .5 }, { .5, 0, .5 }, { .5, .5, .5 },
        { 0, .5, .5 } };
    default:
      return {};
  }
}

/// The reference cell's length, area or volume.
double ReferenceMeasure(NodalType type)
{
  switch (type)
  {
    case NodalType::Triangle6:
    case NodalType::Wedge15:
    case NodalType::Wedge18:
      return 0.5;
    case NodalType::Tetra10:
      return 1.0 / 6.0;
    case NodalType::Pyramid13:
      return 1.0 / 3.0;
    default:
      return 1.0;
  }
}

const NodalType AllTypes[] = { NodalType::Edge3, NodalType::Triangle6, NodalType::Quad8,
  NodalType::Quad9, NodalType::Tetra10, NodalType::Hexa20, NodalType::Hexa27, NodalType::Wedge15,
  NodalType::Wedge18, NodalType::Pyramid13 };

/// x -> A x + b, with det A > 0 (in the plane for 2D cells, on the line for curves).
struct Affine
{
  double A[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  double b[3] = { 0, 0, 0 };
  double Det = 1.0;
  std::array<double, 3> operator()(const std::array<double, 3>& x) const
  {
    std::array<double, 3> y;
    for (int i = 0; i < 3; ++i)
    {
      y[i] = A[i][0] * x[0] + A[i][1] * x[1] + A[i][2] * x[2] + b[i];
    }
    return y;
  }
};

Affine RandomAffine(std::mt19937& rng, int dimension)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Affine f;
  for (;;)
  {
    for (int i = 0; i < dimension; ++i)
    {
      for (int j = 0; j < dimension; ++j)
      {
        f.A[i][j] = (i == j ? 1.0 : 0.0) + 0.6 * u(rng);
      }
      f.b[i] = 10 * u(rng);
    }
    const double(&A)[3][3] = f.A;
    f.Det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
      A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
      A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    if (f.Det > 0.2)
    {
      return f;
    }
  }
}

/// Signed measures of the simplices (in the xy plane for triangles).
std::vector<double> Measures(const std::vector<double>& x, const std::vector<Index>& s, int d)
{
  std::vector<double> m;
  for (size_t t = 0; t < s.size(); t += d + 1)
  {
    const double* a = &x[3 * s[t]];
    const double* b = &x[3 * s[t + 1]];
    if (d == 1)
    {
      m.push_back(std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
        (b[2] - a[2]) * (b[2] - a[2])));
    }
    else if (d == 2)
    {
      m.push_back(mp::Orient2D(a, b, &x[3 * s[t + 2]]) / 2.0);
    }
    else
    {
      m.push_back(mp::Orient3D(a, b, &x[3 * s[t + 2]], &x[3 * s[t + 3]]) / 6.0);
    }
  }
  return m;
}

std::vector<Index> RandomKeys(std::mt19937& rng, size_t n)
{
  std::vector<Index> keys(n);
  std::iota(keys.begin(), keys.end(), Index(0));
  std::shuffle(keys.begin(), keys.end(), rng);
  return keys;
}

TEST(NodalSplit, FillsAffineCellsWithEveryNode)
{
  std::mt19937 rng(54);
  for (NodalType type : AllTypes)
  {
    const int d = mp::NodalCellDimension(type);
    const std::vector<std::array<double, 3>> ref = Reference(type);
    ASSERT_EQ(static_cast<int>(ref.size()), mp::NodalNodeCount(type));
    for (int trial = 0; trial < 50; ++trial)
    {
      const Affine f = trial == 0 ? Affine() : RandomAffine(rng, d == 1 ? 3 : d);
      std::vector<double> x;
      for (const auto& p : ref)
      {
        const std::array<double, 3> y = f(p);
        x.insert(x.end(), y.begin(), y.end());
      }
      std::vector<Index> nodes(ref.size());
      std::iota(nodes.begin(), nodes.end(), Index(0));
      const std::vector<Index> keys = RandomKeys(rng, nodes.size());
      std::vector<Index> simplices = { 99 }; // appended after what is there
      ASSERT_EQ(SplitStatus::Split,
        mp::SplitNodalCell(
          type, x.data(), nodes.data(), simplices, trial % 2 ? keys.data() : nullptr))
        << static_cast<int>(type);
      ASSERT_EQ(99, simplices[0]);
      simplices.erase(simplices.begin());
      ASSERT_EQ(0u, simplices.size() % (d + 1));
      const std::vector<double> m = Measures(x, simplices, d);
      double sum = 0.0;
      for (double v : m)
      {
        EXPECT_GT(v, 0.0) << "type " << static_cast<int>(type) << " trial " << trial;
        sum += v;
      }
      const double expected = d == 1
        ? std::sqrt(f.A[0][0] * f.A[0][0] + f.A[1][0] * f.A[1][0] + f.A[2][0] * f.A[2][0])
        : ReferenceMeasure(type) * f.Det;
      EXPECT_NEAR(expected, sum, 1e-12 * expected) << static_cast<int>(type);
      const std::set<Index> used(simplices.begin(), simplices.end());
      EXPECT_EQ(nodes.size(), used.size()) << static_cast<int>(type);
    }
  }
}

/// The simplices' faces (sorted ids) that occur once: the split's boundary.
std::set<std::vector<Index>> BoundaryFaces(const std::vector<Index>& s, int d)
{
  std::map<std::vector<Index>, int> count;
  for (size_t t = 0; t < s.size(); t += d + 1)
  {
    for (int k = 0; k <= d; ++k)
    {
      std::vector<Index> f;
      for (int j = 0; j <= d; ++j)
      {
        if (j != k)
        {
          f.push_back(s[t + j]);
        }
      }
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  }
  std::set<std::vector<Index>> once;
  for (const auto& fc : count)
  {
    if (fc.second == 1)
    {
      once.insert(fc.first);
    }
  }
  return once;
}

/// Two cells of one type: the reference cell, and its image by `g`
/// (a translation or a reflection), nodes at the same place merged.
void SharedFacePair(NodalType type,
  const std::function<std::array<double, 3>(std::array<double, 3>)>& g, std::mt19937& rng,
  int trials)
{
  const int d = mp::NodalCellDimension(type);
  const std::vector<std::array<double, 3>> ref = Reference(type);
  std::vector<std::array<double, 3>> points(ref);
  std::vector<Index> a(ref.size()), b(ref.size());
  std::iota(a.begin(), a.end(), Index(0));
  for (size_t k = 0; k < ref.size(); ++k)
  {
    const std::array<double, 3> y = g(ref[k]);
    auto at = std::find_if(points.begin(), points.end(), [&y](const std::array<double, 3>& p) {
      return std::fabs(p[0] - y[0]) + std::fabs(p[1] - y[1]) + std::fabs(p[2] - y[2]) < 1e-12;
    });
    b[k] = at - points.begin();
    if (at == points.end())
    {
      points.push_back(y);
    }
  }
  std::set<Index> shared;
  for (Index k : b)
  {
    if (k < static_cast<Index>(ref.size()))
    {
      shared.insert(k);
    }
  }
  ASSERT_GE(shared.size(), static_cast<size_t>(d == 3 ? 6 : 3));
  const Affine f = RandomAffine(rng, d);
  std::vector<double> x;
  for (const auto& p : points)
  {
    const std::array<double, 3> y = f(p);
    x.insert(x.end(), y.begin(), y.end());
  }
  for (int trial = 0; trial < trials; ++trial)
  {
    const std::vector<Index> keys = RandomKeys(rng, points.size());
    std::vector<Index> sa, sb;
    ASSERT_EQ(SplitStatus::Split, mp::SplitNodalCell(type, x.data(), a.data(), sa, keys.data()));
    ASSERT_EQ(SplitStatus::Split, mp::SplitNodalCell(type, x.data(), b.data(), sb, keys.data()));
    auto onShared = [&shared](const std::set<std::vector<Index>>& faces) {
      std::set<std::vector<Index>> on;
      for (const auto& face : faces)
      {
        if (std::all_of(face.begin(), face.end(), [&](Index k) { return shared.count(k) > 0; }))
        {
          on.insert(face);
        }
      }
      return on;
    };
    const std::set<std::vector<Index>> fa = onShared(BoundaryFaces(sa, d));
    const std::set<std::vector<Index>> fb = onShared(BoundaryFaces(sb, d));
    EXPECT_FALSE(fa.empty());
    EXPECT_EQ(fa, fb) << "type " << static_cast<int>(type) << " trial " << trial;
    // The two splits meet only there: no face is split one way on one side
    // and another way on the other (then the union's interior would hold
    // faces of one cell only).
    std::vector<Index> both(sa);
    both.insert(both.end(), sb.begin(), sb.end());
    const std::set<std::vector<Index>> outer = BoundaryFaces(both, d);
    for (const auto& face : fa)
    {
      EXPECT_EQ(0u, outer.count(face));
    }
  }
}

std::array<double, 3> Shift(std::array<double, 3> p, int axis)
{
  p[axis] += 1.0;
  return p;
}

/// Reflection across the plane n . x = c.
std::array<double, 3> Mirror(std::array<double, 3> p, std::array<double, 3> n, double c)
{
  const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  const double t = 2.0 * (n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - c) / nn;
  return { p[0] - t * n[0], p[1] - t * n[1], p[2] - t * n[2] };
}

TEST(NodalSplit, NeighboursSplitSharedFacesAlike)
{
  std::mt19937 rng(4);
  using P = std::array<double, 3>;
  for (NodalType type : { NodalType::Hexa20, NodalType::Hexa27 })
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      SharedFacePair(
        type, [axis](P p) { return Shift(p, axis); }, rng, 20);
    }
  }
  for (NodalType type : { NodalType::Wedge15, NodalType::Wedge18 })
  {
    SharedFacePair(
      type, [](P p) { return Shift(p, 2); }, rng, 20);
    SharedFacePair(
      type,
      [](P p) {
        return Mirror(p, { 1, 0, 0 }, 0);
      },
      rng, 20);
    SharedFacePair(
      type,
      [](P p) {
        return Mirror(p, { 1, 1, 0 }, 1);
      },
      rng, 20);
  }
  SharedFacePair(
    NodalType::Tetra10,
    [](P p) {
      return Mirror(p, { 1, 1, 1 }, 1);
    },
    rng, 20);
  SharedFacePair(
    NodalType::Tetra10,
    [](P p) {
      return Mirror(p, { 0, 0, 1 }, 0);
    },
    rng, 20);
  SharedFacePair(
    NodalType::Pyramid13,
    [](P p) {
      return Mirror(p, { 0, 0, 1 }, 0);
    },
    rng, 20);
  SharedFacePair(
    NodalType::Pyramid13,
    [](P p) {
      return Mirror(p, { 1, 0, 1 }, 1);
    },
    rng, 20);
  SharedFacePair(
    NodalType::Pyramid13,
    [](P p) {
      return Mirror(p, { 0, 1, 0 }, 0);
    },
    rng, 20);
  for (NodalType type : { NodalType::Quad8, NodalType::Quad9 })
  {
    SharedFacePair(
      type, [](P p) { return Shift(p, 0); }, rng, 5);
  }
  SharedFacePair(
    NodalType::Triangle6,
    [](P p) {
      return Mirror(p, { 1, 1, 0 }, 1);
    },
    rng, 5);
}

TEST(NodalSplit, FoldedCellsAreRefused)
{
  auto split = [](NodalType type, std::vector<std::array<double, 3>> x) {
    std::vector<double> flat;
    for (const auto& p : x)
    {
      flat.insert(flat.end(), p.begin(), p.end());
    }
    std::vector<Index> nodes(x.size());
    std::iota(nodes.begin(), nodes.end(), Index(0));
    std::vector<Index> s = { 7 };
    const SplitStatus status = mp::SplitNodalCell(type, flat.data(), nodes.data(), s);
    if (status != SplitStatus::Split)
    {
      EXPECT_EQ(1u, s.size()); // nothing appended on a refusal
    }
    return status;
  };
  // An edge whose mid node is beyond an end.
  EXPECT_EQ(SplitStatus::NotStarShaped,
    split(NodalType::Edge3, { { 0, 0, 0 }, { 1, 0, 0 }, { 1.5, 0.2, 0 } }));
  // A 6-node triangle whose mid node is pushed across the opposite corner.
  std::vector<std::array<double, 3>> t6 = Reference(NodalType::Triangle6);
  t6[4] = { -0.3, -0.3, 0 };
  EXPECT_EQ(SplitStatus::NotStarShaped, split(NodalType::Triangle6, t6));
  // A 10-node tetrahedron whose mid node of edge 1-3 is pulled through the cell.
  std::vector<std::array<double, 3>> t10 = Reference(NodalType::Tetra10);
  t10[8] = { -0.4, -0.4, -0.4 };
  EXPECT_EQ(SplitStatus::NotStarShaped, split(NodalType::Tetra10, t10));
  // A 20-node hexahedron with a mid-edge node pulled far inwards.
  std::vector<std::array<double, 3>> h20 = Reference(NodalType::Hexa20);
  h20[8] = { 0.5, 1.5, 0.0 };
  EXPECT_EQ(SplitStatus::NotStarShaped, split(NodalType::Hexa20, h20));
  // Mildly curved cells (a mid node off its edge) are split, on every node.
  t10[8] = { 0.55, 0.05, 0.55 };
  EXPECT_EQ(SplitStatus::Split, split(NodalType::Tetra10, t10));
  h20 = Reference(NodalType::Hexa20);
  h20[8] = { 0.5, -0.1, 0.0 };
  EXPECT_EQ(SplitStatus::Split, split(NodalType::Hexa20, h20));
}
} // namespace
