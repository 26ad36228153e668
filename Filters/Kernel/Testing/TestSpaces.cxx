// SPDX-License-Identifier: BSD-3-Clause
// The operator for every pair of spaces (P1 -> P1, P0 -> P0, P0 -> P1,
// P1 -> P0, source -> target) in 2D and 3D: hand-computed entries,
// constants, conservation, one operator applied many times, the solver's
// hooks, the matrices as read out, and M_tt's pattern. (The plane frames
// of planar meshes: TestPlaneFrame.cxx.)
#include "Mesh/CellNeighbors.h"
#include "GeneratedMeshes.h"
#include "Threads.h"
#include "Transfer/BlockCG.h"
#include "Transfer/CsrMatrix.h"
#include "Transfer/MassMatrix.h"
#include "Transfer/MortarOperator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

using mp::Index;
using mp::SpaceType;
using mptest::TestMesh;

namespace
{
struct SpacePair
{
  SpaceType Source;
  SpaceType Target;
  const char* Name;
};

const SpacePair Pairs[4] = { { SpaceType::P1, SpaceType::P1, "P1->P1" },
  { SpaceType::P0, SpaceType::P0, "P0->P0" }, { SpaceType::P0, SpaceType::P1, "P0->P1" },
  { SpaceType::P1, SpaceType::P0, "P1->P0" } };

/// The operator from `source` (space s) to `target` (space t), built once.
struct Operator
{
  mp::MortarOperator Op;
  bool Ok = false;
  Operator(const TestMesh& target, const TestMesh& source, SpaceType t, SpaceType s)
  {
    mp::BoxGridLocator locator(source.View());
    mp::OperatorOptions options;
    options.TargetSpace = t;
    options.SourceSpace = s;
    this->Ok = this->Op.Build(target.View(), source.View(), &locator, options);
  }
  std::vector<double> Apply(const std::vector<double>& us, int components = 1) const
  {
    std::vector<double> ut(static_cast<size_t>(this->Op.GetNumberOfTargetFunctions()) * components);
    EXPECT_TRUE(this->Op.Apply(us.data(), components, ut.data(), std::nan("")));
    return ut;
  }
};

Index Size(const TestMesh& m, SpaceType type)
{
  return type == SpaceType::P1 ? m.NumberOfPoints() : m.NumberOfCells();
}

/// Exact integral of a field of the space: P1 by the mesh's rule, P0 as
/// the sum of value times cell measure.
double Integral(const TestMesh& m, SpaceType type, const std::vector<double>& u)
{
  if (type == SpaceType::P1)
  {
    return m.Integral(u);
  }
  double sum = 0;
  for (Index c = 0; c < m.NumberOfCells(); ++c)
  {
    sum += u[c] * m.CellArea(c);
  }
  return sum;
}

/// A non-trivial field: at the points sin(x) + y^2 (+ cos(z)), or another
/// smooth one (which = 1); on the cells random values (seeded by `which`).
std::vector<double> Field(const TestMesh& m, SpaceType type, int which)
{
  std::vector<double> u(static_cast<size_t>(Size(m, type)));
  if (type == SpaceType::P1)
  {
    for (Index p = 0; p < m.NumberOfPoints(); ++p)
    {
      const double* x = &m.Points[3 * p];
      u[p] = which == 0 ? std::sin(x[0]) + x[1] * x[1] + (m.Dimension == 3 ? std::cos(x[2]) : 0.0)
                        : std::cos(2 * x[1]) - x[0] * x[2] + 0.25 * x[0];
    }
  }
  else
  {
    std::mt19937 rng(1000 + which);
    std::uniform_real_distribution<double> value(-1.0, 2.0);
    for (double& v : u)
    {
      v = value(rng);
    }
  }
  return u;
}

/// Random non-matching meshes of the same domain (the unit square or cube).
std::pair<TestMesh, TestMesh> SameDomain(int d)
{
  if (d == 2)
  {
    return { mptest::GridMesh(9, 7, 0.25, 101), mptest::GridMesh(13, 11, 0.25, 102) };
  }
  return { mptest::CubeMesh(3, 4, 3, 0.15, 103), mptest::CubeMesh(4, 3, 5, 0.15, 104) };
}

/// Random non-matching meshes of the unit square or cube with enough target
/// cells for 3 concurrent tasks (64 or more each); seeds from `seed` on.
std::pair<TestMesh, TestMesh> TaskSizedDomain(int d, unsigned seed)
{
  if (d == 2)
  {
    return { mptest::GridMesh(20, 16, 0.25, seed), mptest::GridMesh(17, 19, 0.25, seed + 1) };
  }
  return { mptest::CubeMesh(4, 4, 4, 0.15, seed + 2), mptest::CubeMesh(5, 3, 4, 0.15, seed + 3) };
}

/// Builds the operator of every space pair on SameDomain(2) and
/// SameDomain(3), and hands it to check(meshes, pair, operator, what).
template <class Check>
void ForEveryPairOnSameDomains(const Check& check)
{
  for (int d : { 2, 3 })
  {
    const auto meshes = SameDomain(d);
    for (const SpacePair& pair : Pairs)
    {
      const std::string what = std::to_string(d) + "D " + pair.Name;
      Operator p(meshes.first, meshes.second, pair.Target, pair.Source);
      ASSERT_TRUE(p.Ok) << what << ": " << p.Op.GetError();
      check(meshes, pair, p, what);
    }
  }
}

/// The tetrahedron 0,e1,e2,e3 alone; its source split by the plane x = y
/// through m = (1/2,1/2,0): S0 = (0,e1,m,e3), S1 = (0,m,e2,e3), of volume
/// 1/12 each. Source points: 0, e1, e2, e3, 4 m.
std::pair<TestMesh, TestMesh> SplitTetrahedron()
{
  TestMesh target;
  target.Dimension = 3;
  target.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  target.Cells = { 0, 1, 2, 3 };
  target.Finish();
  TestMesh source;
  source.Dimension = 3;
  source.Points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0.5, 0 };
  source.Cells = { 0, 1, 4, 3, 0, 4, 2, 3 };
  source.Finish();
  return { target, source };
}

/// Checks every entry of `m` against the dense `expected` (rows x columns).
void ExpectEntries(const mp::CsrMatrix& m, const std::vector<std::vector<double>>& expected,
  double tolerance, const std::string& what)
{
  ASSERT_EQ(m.Rows, Index(expected.size())) << what;
  for (Index i = 0; i < m.Rows; ++i)
  {
    ASSERT_EQ(m.Columns, Index(expected[i].size())) << what;
    for (Index j = 0; j < m.Columns; ++j)
    {
      EXPECT_NEAR(m.Entry(i, j), expected[i][j], tolerance) << what << " entry " << i << ", " << j;
    }
  }
}

/// Compressed rows as documented: RowStart from 0, monotone, up to the
/// arrays' size; columns sorted, unique and in range in every row.
void ExpectCsr(const mp::CsrMatrix& m, const std::string& what)
{
  ASSERT_EQ(m.RowStart.size(), size_t(m.Rows) + 1) << what;
  EXPECT_EQ(m.RowStart[0], 0) << what;
  for (Index i = 0; i < m.Rows; ++i)
  {
    ASSERT_LE(m.RowStart[i], m.RowStart[i + 1]) << what << " row " << i;
  }
  ASSERT_EQ(m.NonZeros(), Index(m.ColumnIndex.size())) << what;
  ASSERT_EQ(m.NonZeros(), Index(m.Values.size())) << what;
  for (Index i = 0; i < m.Rows; ++i)
  {
    for (Index p = m.RowStart[i]; p < m.RowStart[i + 1]; ++p)
    {
      ASSERT_GE(m.ColumnIndex[p], 0) << what << " row " << i;
      ASSERT_LT(m.ColumnIndex[p], m.Columns) << what << " row " << i;
      if (p > m.RowStart[i])
      {
        ASSERT_LT(m.ColumnIndex[p - 1], m.ColumnIndex[p]) << what << " row " << i;
      }
    }
  }
}

} // namespace

// (a) Entries by hand. On the split triangle (area 1/2, halves 1/4) with
// the integral of two affine functions over a triangle of area A,
// A/12 (sum f_a g_a + sum f_a sum g_a), and of one, A times its mean:
//  - P0 target: M_tt = 1/2 (the cell's area);
//  - P0 -> P0: M_ts = the intersection areas, 1/4 and 1/4;
//  - P1 -> P0: M_ts(0, j) = integral of source hat j over the target cell:
//    corners 0 and m lie in both halves, 1/12 + 1/12; (1,0) and (0,1) in
//    one, 1/12;
//  - P0 -> P1: M_ts(i, s) = integral of target hat i over S_s: on S0, x
//    takes (0, 1, 1/2), 1/4 (3/2)/3 = 1/8, y takes (0, 0, 1/2): 1/24, and
//    1 - x - y takes (1, 0, 0): 1/12; S1 the mirror image;
//  - P1 target: the element mass matrix A/12 (1 + delta);
//  - P1 -> P1: the source hat at 0 is the target's 1 - x - y, its M_ts row
//    the element mass row (1/12, 1/24, 1/24); the others as in
//    MortarProjector.HandComputedEntries, e.g. int x * 2min(x, y) = 1/16.
TEST(Spaces, HandComputedEntries2D)
{
  const auto meshes = mptest::SplitTriangle();
  const double tol = 1e-15;
  const std::vector<std::vector<double>> p1Mass = { { 1.0 / 12, 1.0 / 24, 1.0 / 24 },
    { 1.0 / 24, 1.0 / 12, 1.0 / 24 }, { 1.0 / 24, 1.0 / 24, 1.0 / 12 } };
  const std::vector<std::vector<double>> p0Mass = { { 0.5 } };
  {
    Operator p(meshes.first, meshes.second, SpaceType::P1, SpaceType::P1);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(),
      { { 1.0 / 12, 1.0 / 48, 1.0 / 48, 1.0 / 24 }, { 1.0 / 24, 5.0 / 96, 1.0 / 96, 1.0 / 16 },
        { 1.0 / 24, 1.0 / 96, 5.0 / 96, 1.0 / 16 } },
      tol, "P1->P1 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p1Mass, tol, "P1->P1 M_tt");
  }
  {
    Operator p(meshes.first, meshes.second, SpaceType::P0, SpaceType::P0);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(), { { 0.25, 0.25 } }, tol, "P0->P0 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p0Mass, tol, "P0->P0 M_tt");
  }
  {
    Operator p(meshes.first, meshes.second, SpaceType::P1, SpaceType::P0);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(),
      { { 1.0 / 12, 1.0 / 12 }, { 1.0 / 8, 1.0 / 24 }, { 1.0 / 24, 1.0 / 8 } }, tol, "P0->P1 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p1Mass, tol, "P0->P1 M_tt");
  }
  {
    Operator p(meshes.first, meshes.second, SpaceType::P0, SpaceType::P1);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(
      p.Op.GetMixedMass(), { { 1.0 / 6, 1.0 / 12, 1.0 / 12, 1.0 / 6 } }, tol, "P1->P0 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p0Mass, tol, "P1->P0 M_tt");
  }
}

// The unit square split along (0,0)-(1,1) (target T0 below, T1 above) and
// along (1,0)-(0,1) (source S0 below, S1 above): four pieces of area 1/4.
// P0 -> P0: every M_ts entry 1/4, M_tt = diag(1/2, 1/2). P1 -> P0: the source
// hat at (1,0) (x on S0, 1 - y on S1) over T0: 1/8 + 1/8, over T1: 1/24 +
// 1/24; the hat at (0,0) (1 - x - y, on S0 only) over each: 1/12; the hat at
// (1,1) (x + y - 1, on S1 only): 1/12; the hat at (0,1) mirrors (1,0).
TEST(Spaces, HandComputedEntriesOnASquareSplitTwoWays)
{
  TestMesh target;
  target.Points = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };
  target.Cells = { 0, 1, 2, 0, 2, 3 };
  target.Finish();
  TestMesh source = target;
  source.Cells = { 0, 1, 3, 1, 2, 3 };
  source.Finish();
  const double tol = 1e-15;
  {
    Operator p(target, source, SpaceType::P0, SpaceType::P0);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(), { { 0.25, 0.25 }, { 0.25, 0.25 } }, tol, "P0->P0 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), { { 0.5, 0.0 }, { 0.0, 0.5 } }, tol, "P0->P0 M_tt");
  }
  {
    Operator p(target, source, SpaceType::P0, SpaceType::P1);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(),
      { { 1.0 / 12, 1.0 / 4, 1.0 / 12, 1.0 / 12 }, { 1.0 / 12, 1.0 / 12, 1.0 / 12, 1.0 / 4 } }, tol,
      "P1->P0 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), { { 0.5, 0.0 }, { 0.0, 0.5 } }, tol, "P1->P0 M_tt");
  }
}

// The same in 3D, on the split tetrahedron (volume 1/6, halves 1/12), with
// the integral of two affine functions over a tetrahedron of volume V,
// V/20 (sum f_a g_a + sum f_a sum g_a), and of one, V times its mean:
//  - P0 target: M_tt = 1/6; P0 -> P0: M_ts = 1/12, 1/12;
//  - P1 -> P0: a source hat over a half holding its point: (1/12)/4 = 1/48;
//    0, e3 and m lie in both halves (1/24), e1 and e2 in one (1/48);
//  - P0 -> P1: x takes (0, 1, 1/2, 0) on S0: (1/12)(3/2)/4 = 1/32, on S1
//    (0, 1/2, 0, 0): 1/96; 1 - x - y - z takes (1, 0, 0, 0) on both: 1/48,
//    z likewise 1/48;
//  - P1 target: the element mass matrix V/20 (1 + delta): 1/60, 1/120;
//  - P1 -> P1: e.g. int x psi_m: x takes (0, 1, 1/2, 0) and psi_m (0, 0, 1,
//    0) on S0, (1/240)(1/2 + 3/2) = 1/120; (0, 1/2, 0, 0) and (0, 1, 0, 0)
//    on S1, (1/240)(1/2 + 1/2) = 1/240; together 1/80.
TEST(Spaces, HandComputedEntries3D)
{
  const auto meshes = SplitTetrahedron();
  const double tol = 1e-15;
  std::vector<std::vector<double>> p1Mass(4, std::vector<double>(4, 1.0 / 120));
  for (int i = 0; i < 4; ++i)
  {
    p1Mass[i][i] = 1.0 / 60;
  }
  const std::vector<std::vector<double>> p0Mass = { { 1.0 / 6 } };
  {
    Operator p(meshes.first, meshes.second, SpaceType::P1, SpaceType::P1);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(),
      { { 1.0 / 60, 1.0 / 240, 1.0 / 240, 1.0 / 120, 1.0 / 120 },
        { 1.0 / 120, 1.0 / 96, 1.0 / 480, 1.0 / 120, 1.0 / 80 },
        { 1.0 / 120, 1.0 / 480, 1.0 / 96, 1.0 / 120, 1.0 / 80 },
        { 1.0 / 120, 1.0 / 240, 1.0 / 240, 1.0 / 60, 1.0 / 120 } },
      tol, "P1->P1 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p1Mass, tol, "P1->P1 M_tt");
  }
  {
    Operator p(meshes.first, meshes.second, SpaceType::P0, SpaceType::P0);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(), { { 1.0 / 12, 1.0 / 12 } }, tol, "P0->P0 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p0Mass, tol, "P0->P0 M_tt");
  }
  {
    Operator p(meshes.first, meshes.second, SpaceType::P1, SpaceType::P0);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(),
      { { 1.0 / 48, 1.0 / 48 }, { 1.0 / 32, 1.0 / 96 }, { 1.0 / 96, 1.0 / 32 },
        { 1.0 / 48, 1.0 / 48 } },
      tol, "P0->P1 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p1Mass, tol, "P0->P1 M_tt");
  }
  {
    Operator p(meshes.first, meshes.second, SpaceType::P0, SpaceType::P1);
    ASSERT_TRUE(p.Ok) << p.Op.GetError();
    ExpectEntries(p.Op.GetMixedMass(), { { 1.0 / 24, 1.0 / 48, 1.0 / 48, 1.0 / 24, 1.0 / 24 } },
      tol, "P1->P0 M_ts");
    ExpectEntries(p.Op.GetTargetMass(), p0Mass, tol, "P1->P0 M_tt");
  }
}

// (b) Constants are reproduced by every pair (P0 and P1 hold them).
TEST(Spaces, ConstantsAreReproduced)
{
  ForEveryPairOnSameDomains([](const std::pair<TestMesh, TestMesh>& meshes, const SpacePair& pair,
                              Operator& p, const std::string& what) {
    ASSERT_EQ(p.Op.GetNumberOfSourceFunctions(), Size(meshes.second, pair.Source)) << what;
    ASSERT_EQ(p.Op.GetNumberOfTargetFunctions(), Size(meshes.first, pair.Target)) << what;
    EXPECT_EQ(p.Op.GetNumberOfValid(), Size(meshes.first, pair.Target)) << what;
    const std::vector<double> us(static_cast<size_t>(Size(meshes.second, pair.Source)), 2.5);
    const auto ut = p.Apply(us);
    for (size_t i = 0; i < ut.size(); ++i)
    {
      ASSERT_NEAR(ut[i], 2.5, 1e-13) << what << " function " << i;
    }
  });
}

// (c) The integral of the projection equals the source's, for every pair.
TEST(Spaces, IntegralsAreConserved)
{
  ForEveryPairOnSameDomains([](const std::pair<TestMesh, TestMesh>& meshes, const SpacePair& pair,
                              Operator& p, const std::string& what) {
    const auto us = Field(meshes.second, pair.Source, 0);
    const auto ut = p.Apply(us);
    const double is = Integral(meshes.second, pair.Source, us);
    ASSERT_GT(std::fabs(is), 0.1) << what;
    EXPECT_NEAR(Integral(meshes.first, pair.Target, ut), is, 1e-13 * std::fabs(is)) << what;
  });
}

// (d) Built once, applied many times: two fields one by one and side by
// side give the same values; restarting from the result changes nothing and
// costs no more iterations.
TEST(Spaces, BuiltOnceAppliedManyTimes)
{
  ForEveryPairOnSameDomains([](const std::pair<TestMesh, TestMesh>& meshes, const SpacePair& pair,
                              Operator& p, const std::string& what) {
    const auto f = Field(meshes.second, pair.Source, 0);
    const auto g = Field(meshes.second, pair.Source, 1);
    std::vector<double> fg;
    for (size_t j = 0; j < f.size(); ++j)
    {
      fg.insert(fg.end(), { f[j], g[j] });
    }
    const auto a = p.Apply(f);
    const auto b = p.Apply(g);
    const auto ab = p.Apply(fg, 2);
    const Index n = p.Op.GetNumberOfTargetFunctions();
    ASSERT_EQ(ab.size(), size_t(2 * n)) << what;
    for (Index i = 0; i < n; ++i)
    {
      ASSERT_NEAR(ab[2 * i], a[i], 1e-14) << what << " function " << i;
      ASSERT_NEAR(ab[2 * i + 1], b[i], 1e-14) << what << " function " << i;
    }
    // Again from the previous result.
    mp::SolveOptions warm;
    warm.StartFromX = true;
    std::vector<double> again = a;
    ASSERT_TRUE(p.Op.Apply(f.data(), 1, again.data(), std::nan(""), warm)) << what;
    for (Index i = 0; i < n; ++i)
    {
      ASSERT_NEAR(again[i], a[i], 1e-13) << what << " function " << i;
    }
    // The iterations, counted on the operator's own M_tt.
    const mp::CsrMatrix& mass = p.Op.GetTargetMass();
    const mp::BlockCG cg(mass, mp::TaskRunner());
    std::vector<double> rhs(static_cast<size_t>(n));
    p.Op.GetMixedMass().MultiplyRows(f.data(), rhs.data(), 1, 0, n);
    std::vector<char> converged;
    std::vector<double> cold(static_cast<size_t>(n), 0.0);
    const int coldIterations =
      cg.Iterate(rhs.data(), cold.data(), 1, mp::SolveOptions(), converged);
    ASSERT_TRUE(converged[0]) << what;
    std::vector<double> restarted = a;
    const int warmIterations = cg.Iterate(rhs.data(), restarted.data(), 1, warm, converged);
    ASSERT_TRUE(converged[0]) << what;
    EXPECT_LE(warmIterations, coldIterations) << what;
    if (pair.Target == SpaceType::P1)
    {
      EXPECT_GT(coldIterations, 0) << what; // M_tt is not diagonal
    }
    for (Index i = 0; i < n; ++i)
    {
      ASSERT_NEAR(cold[i], a[i], 1e-13) << what << " function " << i;
      ASSERT_NEAR(restarted[i], a[i], 1e-13) << what << " function " << i;
    }
  });
}

// Restarting from a result that holds the fill value (NaN) at uncovered
// target functions: those are decoupled, so the restart must not see it.
TEST(Spaces, RestartFromAResultWithUncoveredFunctions)
{
  const TestMesh target = mptest::GridMesh(8, 8, 0.2, 111);
  const TestMesh source = mptest::GridMesh(5, 7, 0.2, 112, -0.25, -0.25, 0.5, 1.25);
  for (const SpacePair& pair : Pairs)
  {
    Operator p(target, source, pair.Target, pair.Source);
    ASSERT_TRUE(p.Ok) << pair.Name << ": " << p.Op.GetError();
    ASSERT_GT(p.Op.GetNumberOfValid(), 0) << pair.Name;
    ASSERT_LT(p.Op.GetNumberOfValid(), p.Op.GetNumberOfTargetFunctions()) << pair.Name;
    const auto f = Field(source, pair.Source, 0);
    const auto a = p.Apply(f);
    mp::SolveOptions warm;
    warm.StartFromX = true;
    std::vector<double> again = a;
    // With hooks the solve cannot fall back on the direct solver: the
    // iterations themselves must converge from the restart.
    int reduces = 0;
    mp::SolverHooks hooks;
    hooks.Reduce = [&reduces](double*, int) { ++reduces; };
    ASSERT_TRUE(p.Op.Apply(f.data(), 1, again.data(), std::nan(""), warm, hooks)) << pair.Name;
    EXPECT_GT(reduces, 0) << pair.Name;
    for (size_t i = 0; i < a.size(); ++i)
    {
      if (p.Op.GetValid()[i])
      {
        ASSERT_NEAR(again[i], a[i], 1e-13) << pair.Name << " function " << i;
      }
      else
      {
        ASSERT_TRUE(std::isnan(again[i])) << pair.Name << " function " << i;
      }
    }
  }
}

// (e) Hooks that only count (a single part: sums and rows are complete)
// change nothing and are called in every iteration.
TEST(Spaces, SolverHooksAreCalledAndChangeNothing)
{
  ForEveryPairOnSameDomains([](const std::pair<TestMesh, TestMesh>& meshes, const SpacePair& pair,
                              Operator& p, const std::string& what) {
    int reduces = 0;
    int exchanges = 0;
    mp::SolverHooks hooks;
    hooks.Reduce = [&reduces](double*, int count) {
      EXPECT_GT(count, 0);
      ++reduces;
    };
    hooks.Exchange = [&exchanges](double*, int width) {
      EXPECT_GT(width, 0);
      ++exchanges;
    };
    const Index n = p.Op.GetNumberOfTargetFunctions();
    std::vector<char> counted(static_cast<size_t>(n), 1);
    hooks.Counted = counted.data();
    const auto f = Field(meshes.second, pair.Source, 0);
    const auto plain = p.Apply(f);
    std::vector<double> hooked(static_cast<size_t>(n));
    ASSERT_TRUE(p.Op.Apply(f.data(), 1, hooked.data(), std::nan(""), mp::SolveOptions(), hooks))
      << what;
    EXPECT_GT(reduces, 0) << what;
    EXPECT_GT(exchanges, 0) << what;
    for (Index i = 0; i < n; ++i)
    {
      ASSERT_EQ(hooked[i], plain[i]) << what << " function " << i;
    }
    // Per iteration, on the operator's M_tt.
    const mp::BlockCG cg(p.Op.GetTargetMass(), mp::TaskRunner());
    std::vector<double> rhs(static_cast<size_t>(n));
    p.Op.GetMixedMass().MultiplyRows(f.data(), rhs.data(), 1, 0, n);
    std::vector<char> converged;
    std::vector<double> x(static_cast<size_t>(n), 0.0);
    std::vector<double> y(static_cast<size_t>(n), 0.0);
    const int iterations = cg.Iterate(rhs.data(), x.data(), 1, mp::SolveOptions(), converged);
    reduces = 0;
    exchanges = 0;
    EXPECT_EQ(cg.Iterate(rhs.data(), y.data(), 1, mp::SolveOptions(), converged, hooks), iterations)
      << what;
    EXPECT_GE(reduces, iterations) << what;
    EXPECT_GE(exchanges, iterations) << what;
    EXPECT_GT(reduces, 0) << what;
    EXPECT_GT(exchanges, 0) << what;
    for (Index i = 0; i < n; ++i)
    {
      ASSERT_EQ(y[i], x[i]) << what << " function " << i;
    }
  });
}

// (f) The matrices as read out: compressed rows, and with P1 or P0 on both
// sides (partitions of unity) all entries of M_ts add up to the covered
// measure; so do those of M_tt over the valid rows (an invalid row holds
// just a 1 on the diagonal). Meshes of the same domain, and partial
// overlaps of known measure.
TEST(Spaces, MatricesReadOut)
{
  for (int d : { 2, 3 })
  {
    std::vector<std::pair<std::pair<TestMesh, TestMesh>, double>> cases;
    cases.emplace_back(SameDomain(d), 1.0);
    if (d == 2)
    {
      // [0,1]^2 against [0.3,1.3]x[-0.2,0.8]: 0.7 x 0.8.
      cases.emplace_back(std::make_pair(mptest::GridMesh(10, 9, 0.25, 121),
                           mptest::GridMesh(7, 8, 0.25, 122, 0.3, -0.2, 1.3, 0.8)),
        0.7 * 0.8);
    }
    else
    {
      // [0,1]^3 against itself moved by (0.25, -0.1, 0.2): 0.75 x 0.9 x 0.8.
      TestMesh moved = mptest::CubeMesh(4, 3, 3, 0.15, 124);
      mptest::Move3D(moved, 0, 0, 1, 0.25, -0.1, 0.2);
      moved.Finish();
      cases.emplace_back(
        std::make_pair(mptest::CubeMesh(3, 4, 3, 0.15, 123), moved), 0.75 * 0.9 * 0.8);
    }
    for (size_t c = 0; c < cases.size(); ++c)
    {
      const TestMesh& target = cases[c].first.first;
      const TestMesh& source = cases[c].first.second;
      const double overlap = cases[c].second;
      for (const SpacePair& pair : Pairs)
      {
        const std::string what =
          std::to_string(d) + "D case " + std::to_string(c) + " " + pair.Name;
        Operator p(target, source, pair.Target, pair.Source);
        ASSERT_TRUE(p.Ok) << what << ": " << p.Op.GetError();
        const mp::CsrMatrix& mts = p.Op.GetMixedMass();
        const mp::CsrMatrix& mtt = p.Op.GetTargetMass();
        ExpectCsr(mts, what + " M_ts");
        ExpectCsr(mtt, what + " M_tt");
        EXPECT_EQ(mts.Rows, Size(target, pair.Target)) << what;
        EXPECT_EQ(mts.Columns, Size(source, pair.Source)) << what;
        EXPECT_EQ(mtt.Rows, Size(target, pair.Target)) << what;
        EXPECT_EQ(mtt.Columns, Size(target, pair.Target)) << what;
        EXPECT_NEAR(p.Op.GetCoveredMeasure(), overlap, 1e-13 * overlap) << what;
        double sumTs = 0;
        for (double v : mts.Values)
        {
          sumTs += v;
        }
        EXPECT_NEAR(sumTs, p.Op.GetCoveredMeasure(), 1e-13 * overlap) << what;
        EXPECT_NEAR(sumTs, overlap, 1e-13 * overlap) << what;
        double sumTt = 0;
        double largest = 0;
        for (Index i = 0; i < mtt.Rows; ++i)
        {
          for (Index q = mtt.RowStart[i]; q < mtt.RowStart[i + 1]; ++q)
          {
            if (p.Op.GetValid()[i])
            {
              sumTt += mtt.Values[q];
              largest = std::max(largest, std::fabs(mtt.Values[q]));
            }
            else
            {
              EXPECT_EQ(mtt.Values[q], mtt.ColumnIndex[q] == i ? 1.0 : 0.0) << what << " row " << i;
            }
          }
          // An invalid row has no M_ts entries either (or only zeros).
          for (Index q = mts.RowStart[i]; !p.Op.GetValid()[i] && q < mts.RowStart[i + 1]; ++q)
          {
            EXPECT_EQ(mts.Values[q], 0.0) << what << " row " << i;
          }
        }
        EXPECT_NEAR(sumTt, overlap, 1e-13 * overlap) << what;
        // M_tt is symmetric.
        for (Index i = 0; i < mtt.Rows; ++i)
        {
          for (Index q = mtt.RowStart[i]; q < mtt.RowStart[i + 1]; ++q)
          {
            ASSERT_NEAR(mtt.Entry(mtt.ColumnIndex[q], i), mtt.Values[q], 1e-15 * largest)
              << what << " entry " << i << ", " << mtt.ColumnIndex[q];
          }
        }
      }
    }
  }
}

// The pairs with concurrent tasks (64 target cells or more per task): the
// matrices of the serial build.
TEST(Spaces, ConcurrentTasksGiveTheSerialMatrices)
{
  for (int d : { 2, 3 })
  {
    const auto meshes = TaskSizedDomain(d, 141);
    for (const SpacePair& pair : Pairs)
    {
      const std::string what = std::to_string(d) + "D " + pair.Name;
      Operator serial(meshes.first, meshes.second, pair.Target, pair.Source);
      ASSERT_TRUE(serial.Ok) << what;
      mp::BoxGridLocator locator(meshes.second.View());
      mp::OperatorOptions options;
      options.TargetSpace = pair.Target;
      options.SourceSpace = pair.Source;
      options.Runner.Tasks = 3;
      options.Runner.Run = mptest::RunInThreads;
      mp::MortarOperator concurrent;
      ASSERT_TRUE(concurrent.Build(meshes.first.View(), meshes.second.View(), &locator, options))
        << what;
      for (const auto& m : { std::make_pair(&serial.Op.GetMixedMass(), &concurrent.GetMixedMass()),
             std::make_pair(&serial.Op.GetTargetMass(), &concurrent.GetTargetMass()) })
      {
        ASSERT_EQ(m.first->RowStart.size(), m.second->RowStart.size()) << what;
        ASSERT_EQ(m.first->ColumnIndex.size(), m.second->ColumnIndex.size()) << what;
        for (size_t k = 0; k < m.first->RowStart.size(); ++k)
        {
          ASSERT_EQ(m.first->RowStart[k], m.second->RowStart[k]) << what;
        }
        for (size_t k = 0; k < m.first->ColumnIndex.size(); ++k)
        {
          ASSERT_EQ(m.first->ColumnIndex[k], m.second->ColumnIndex[k]) << what;
          ASSERT_NEAR(m.first->Values[k], m.second->Values[k], 1e-15) << what;
        }
      }
    }
  }
}

// A restart whose new field is zero returns zero, not the previous solution.
TEST(Spaces, RestartOnAZeroFieldGivesZero)
{
  ForEveryPairOnSameDomains([](const std::pair<TestMesh, TestMesh>& meshes, const SpacePair& pair,
                              Operator& p, const std::string& what) {
    std::vector<double> ut = p.Apply(Field(meshes.second, pair.Source, 0));
    const std::vector<double> zero(static_cast<size_t>(Size(meshes.second, pair.Source)), 0.0);
    mp::SolveOptions restart;
    restart.StartFromX = true;
    ASSERT_TRUE(p.Op.Apply(zero.data(), 1, ut.data(), -7.0, restart)) << what;
    for (size_t i = 0; i < ut.size(); ++i)
    {
      ASSERT_EQ(ut[i], p.Op.GetValid()[i] ? 0.0 : -7.0) << what << " function " << i;
    }
  });
}

// Single use (OperatorOptions::Fields): the right-hand sides summed during
// the search, serially and in 3 concurrent tasks (rows shared by tasks
// deferred), give the assembled operator's projection; such an operator
// refuses other fields and holds no M_ts.
TEST(Spaces, SingleUseFieldsGiveTheAssembledProjection)
{
  for (int d : { 2, 3 })
  {
    const auto meshes = TaskSizedDomain(d, 151);
    for (const SpacePair& pair : Pairs)
    {
      const std::string what = std::to_string(d) + "D " + pair.Name;
      const TestMesh& target = meshes.first;
      const TestMesh& source = meshes.second;
      const std::vector<double> a = Field(source, pair.Source, 0);
      const std::vector<double> b = Field(source, pair.Source, 1);
      const Index ns = Size(source, pair.Source);
      const Index nt = Size(target, pair.Target);
      Operator assembled(target, source, pair.Target, pair.Source);
      ASSERT_TRUE(assembled.Ok) << what;
      // Two fields side by side, and 40 (more than the assembler's cache
      // of fields per source cell holds at full size: SourceCellFields.h).
      for (int nc : { 2, 40 })
      {
        std::vector<double> fields(static_cast<size_t>(nc * ns));
        for (Index j = 0; j < ns; ++j)
        {
          for (int c = 0; c < nc; ++c)
          {
            fields[nc * j + c] = (c % 2 ? b[j] : a[j]) * (1.0 + 0.125 * (c / 2));
          }
        }
        std::vector<double> expected(static_cast<size_t>(nc * nt));
        ASSERT_TRUE(assembled.Op.Apply(fields.data(), nc, expected.data(), -7.0)) << what;
        for (int tasks : { 1, 3 })
        {
          mp::BoxGridLocator locator(source.View());
          mp::OperatorOptions options;
          options.TargetSpace = pair.Target;
          options.SourceSpace = pair.Source;
          options.Fields = fields.data();
          options.FieldComponents = nc;
          options.Runner.Tasks = tasks;
          options.Runner.Run = mptest::RunInThreads;
          mp::MortarOperator single;
          ASSERT_TRUE(single.Build(target.View(), source.View(), &locator, options)) << what;
          EXPECT_FALSE(single.HasMixedMass()) << what;
          EXPECT_EQ(single.GetMixedMass().NonZeros(), 0) << what;
          std::vector<double> values(static_cast<size_t>(nc * nt));
          ASSERT_TRUE(single.Apply(fields.data(), nc, values.data(), -7.0)) << what;
          for (size_t k = 0; k < values.size(); ++k)
          {
            ASSERT_NEAR(values[k], expected[k], 1e-12)
              << what << " components " << nc << " tasks " << tasks << " entry " << k;
          }
          // Other fields cannot be projected without M_ts.
          EXPECT_FALSE(single.Apply(a.data(), 1, values.data(), -7.0)) << what;
        }
      }
    }
  }
}

// M_tt's pattern (MassPattern) is the point graph: each point with itself
// and with every point it shares a cell with, columns sorted, no repeats.
// Rows of every length the pattern builder sorts differently (up to 8, up
// to 32, more: a fan of 50 triangles, the cube's tetrahedra), a point used
// by no cell, on one task and on three (the two larger meshes have enough
// points to be split into three ranges).
TEST(MassPattern, IsThePointGraph)
{
  std::vector<TestMesh> meshes = { mptest::GridMesh(9, 7, 0.3, 5),
    mptest::CubeMesh(4, 3, 3, 0.2, 6), mptest::GridMesh(130, 100, 0.3, 7),
    mptest::CubeMesh(25, 25, 25, 0.2, 8) };
  // A fan: the centre point 0 in 50 triangles, its rim points in 2 each,
  // and a last point no cell uses.
  TestMesh fan;
  fan.Points = { 0.0, 0.0, 0.0 };
  const int rim = 50;
  for (int k = 0; k < rim; ++k)
  {
    const double a = 2.0 * M_PI * k / rim;
    fan.Points.insert(fan.Points.end(), { std::cos(a), std::sin(a), 0.0 });
  }
  for (int k = 0; k < rim; ++k)
  {
    fan.Cells.insert(fan.Cells.end(), { 0, 1 + k, 1 + (k + 1) % rim });
  }
  fan.Points.insert(fan.Points.end(), { 5.0, 5.0, 0.0 });
  meshes.push_back(fan);
  int lengths[3] = {}; // rows of up to 8, up to 32, more columns
  int split = 0;       // meshes of at least 3 x 4096 points (PointGraph's grain)
  for (const TestMesh& mesh : meshes)
  {
    split += mesh.NumberOfPoints() >= 3 * 4096;
    const mp::MeshView view = mesh.View(false);
    const Index n = view.NumberOfPoints;
    std::vector<std::vector<int>> expected(static_cast<size_t>(n));
    for (Index p = 0; p < n; ++p)
    {
      expected[p].push_back(static_cast<int>(p));
    }
    for (Index c = 0; c < view.NumberOfCells; ++c)
    {
      for (int a = 0; a < view.CornersPerCell(); ++a)
      {
        for (int b = 0; b < view.CornersPerCell(); ++b)
        {
          expected[view.Cell(c)[a]].push_back(static_cast<int>(view.Cell(c)[b]));
        }
      }
    }
    for (auto& row : expected)
    {
      std::sort(row.begin(), row.end());
      row.erase(std::unique(row.begin(), row.end()), row.end());
      ++lengths[row.size() <= 8 ? 0 : (row.size() <= 32 ? 1 : 2)];
    }
    // Three tasks first: their copy into place must not find a buffer that
    // the serial run left with the right columns (freed, then reused).
    // Each also from the cells around the points that the neighbours'
    // construction kept (emptied once read), and with kept lists of
    // another mesh (not used: built anew).
    mp::PointCells other;
    other.Start.assign(3, 0);
    for (int tasks : { 3, 1 })
    {
      for (int lists : { 0, 1, 2 })
      {
        mp::MeshView seen = view;
        mp::PointCells around;
        std::vector<mp::NeighborId> neighbors(
          static_cast<size_t>(view.NumberOfCells * view.CornersPerCell()));
        mp::BuildFaceNeighbors(view, neighbors.data(), mptest::ThreadRunner(tasks), &around);
        ASSERT_TRUE(around.Fit(view));
        ASSERT_EQ(
          around.Cells.size(), static_cast<size_t>(view.NumberOfCells * view.CornersPerCell()));
        seen.Around = lists == 1 ? &around : (lists == 2 ? &other : nullptr);
        mp::CsrMatrix m;
        mp::MassPattern(SpaceType::P1, seen, mptest::ThreadRunner(tasks), m);
        EXPECT_EQ(around.Start.empty(), lists == 1);
        EXPECT_EQ(other.Start.size(), 3u);
        ASSERT_EQ(m.Rows, n);
        ASSERT_EQ(m.Values.size(), m.ColumnIndex.size());
        for (Index p = 0; p < n; ++p)
        {
          const std::vector<int> row(
            m.ColumnIndex.begin() + m.RowStart[p], m.ColumnIndex.begin() + m.RowStart[p + 1]);
          EXPECT_EQ(row, expected[p]) << "row " << p << ", " << tasks << " tasks, lists " << lists;
        }
      }
    }
  }
  EXPECT_GT(lengths[0], 50);
  EXPECT_GT(lengths[1], 10);
  EXPECT_EQ(lengths[2], 1);
  EXPECT_EQ(split, 2);
}
