// SPDX-License-Identifier: BSD-3-Clause
// The Bernstein form of a second-order target (Transfer/BernsteinForm.h),
// and the lumped and bounded projections made in it (MortarApply.cxx):
//  - per supported type, at random reference points: the Bernstein
//    functions are non-negative and sum to 1, and sum_n B_m(node n) N_n is
//    B_m (the change of basis is exact); the serendipity types' functions
//    of their form (7/16 of a mid-edge node on each corner) are
//    non-negative too, the pyramid's (1/4) dip below zero;
//  - on tri6 squares and tet10 cubes: C's rows are non-negative and sum to
//    1, FromNodes inverts ToNodes, and C^T of the nodal functions' integrals
//    (some zero or negative) is positive;
//  - Lumped onto tri6, tet10, curved tri6, tri6 surface and edge3 targets: a constant stays exact, the
//    integral is the source's; from a linear source a positive field stays
//    positive and a 0/1 indicator within [0, 1]; from a second-order one
//    (whose field overshoots its nodes) bounds bring it back;
//  - Lumped and bounded onto quad8 squares, affine (VTK's functions) and
//    jittered (the quad9 space with a hidden centre), in their signed
//    form: constants exact, the integral kept, and every node within the
//    source's range (a positive field positive) without asking for bounds,
//    also where the target reaches past the source; refused on a mesh
//    mixing hex20's edge share with tri6's.
#include "Geometry/NodalShapes.h"
#include "Search/CandidateLocator.h"
#include "Transfer/BernsteinForm.h"
#include "Transfer/MortarOperator.h"
#include "NodalMeshes.h"
#include "NodalTestCells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace
{
using mp::BernsteinForm;
using mp::Index;
using mp::NodalType;
using namespace nodaltest;

const NodalType Supported[] = { NodalType::Edge3, NodalType::Triangle6, NodalType::Tetra10,
  NodalType::Quad9, NodalType::Hexa27, NodalType::Wedge18, NodalType::Quad8, NodalType::Hexa20,
  NodalType::Wedge15, NodalType::Pyramid13 };

TEST(BernsteinForm, FunctionsOfEveryType)
{
  std::mt19937 rng(7);
  for (NodalType type : AllTypes)
  {
    const bool supported =
      std::find(std::begin(Supported), std::end(Supported), type) != std::end(Supported);
    EXPECT_EQ(BernsteinForm::Supports(type), supported) << int(type);
    if (!supported)
    {
      continue;
    }
    const int n = mp::NodalNodeCount(type);
    const std::vector<double> nodes = ReferenceNodes(type);
    // C_nm = B_m(node n)
    std::vector<double> C(size_t(n * n));
    for (int k = 0; k < n; ++k)
    {
      BernsteinForm::Values(type, &nodes[3 * k], &C[size_t(k * n)]);
    }
    const bool signedForm = BernsteinForm::Signed(type);
    double lowest = 1.0;
    for (int trial = 0; trial < 20; ++trial)
    {
      double xi[3];
      RandomReferencePoint(type, rng, 0.0, xi);
      double B[mp::MaxNodalNodes], N[mp::MaxNodalNodes];
      BernsteinForm::Values(type, xi, B);
      mp::NodalValues(type, xi, N);
      double sum = 0.0;
      for (int m = 0; m < n; ++m)
      {
        EXPECT_TRUE(type == NodalType::Pyramid13 || B[m] >= 0.0) << int(type) << " function " << m;
        lowest = std::min(lowest, B[m]);
        sum += B[m];
        double fromNodes = 0.0;
        for (int k = 0; k < n; ++k)
        {
          fromNodes += C[size_t(k * n + m)] * N[k];
        }
        EXPECT_NEAR(fromNodes, B[m], 1e-14) << int(type) << " function " << m;
      }
      EXPECT_NEAR(sum, 1.0, 1e-14) << int(type);
    }
    if (type == NodalType::Pyramid13)
    {
      EXPECT_LT(lowest, -1e-3); // (its corners' functions dip below zero)
    }
    EXPECT_EQ(signedForm,
      type == NodalType::Quad8 || type == NodalType::Hexa20 || type == NodalType::Wedge15 ||
        type == NodalType::Pyramid13)
      << int(type);
  }
}

void ExpectForm(const NodalMesh& mesh)
{
  const mp::MeshView view = mesh.View(false);
  ASSERT_TRUE(BernsteinForm::Covers(view));
  BernsteinForm form;
  form.Build(view);
  const mp::CsrMatrix& C = form.GetMatrix();
  ASSERT_EQ(C.Rows, mesh.NumberOfPoints());
  for (Index i = 0; i < C.Rows; ++i)
  {
    double sum = 0.0;
    for (Index p = C.RowStart[i]; p < C.RowStart[i + 1]; ++p)
    {
      EXPECT_GT(C.Values[p], 0.0);
      sum += C.Values[p];
    }
    EXPECT_EQ(sum, 1.0) << "row " << i;
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(size_t(2 * C.Rows)), nodes(b.size()), back(b.size());
  for (double& v : b)
  {
    v = u(rng);
  }
  form.ToNodes(b.data(), 2, nodes.data());
  form.FromNodes(nodes.data(), 2, back.data());
  for (size_t i = 0; i < b.size(); ++i)
  {
    EXPECT_NEAR(back[i], b[i], 1e-14);
  }
  // The lumped weights: the nodal functions' integrals (the mesh onto
  // itself) are zero or less at the corners, the Bernstein ones positive,
  // and both sum to the measure.
  const mp::MeshView s = mesh.View();
  mp::BoxGridLocator locator(s);
  mp::MortarOperator op;
  ASSERT_TRUE(op.Build(mesh.View(), s, &locator)) << op.GetError();
  const std::vector<double>& nodal = op.GetCoveredIntegrals();
  std::vector<double> weights(nodal.size());
  form.Transpose(nodal.data(), 1, weights.data());
  EXPECT_LE(*std::min_element(nodal.begin(), nodal.end()), 1e-15);
  double sumNodal = 0.0, sumBernstein = 0.0;
  for (size_t i = 0; i < weights.size(); ++i)
  {
    EXPECT_GT(weights[i], 0.0) << "function " << i;
    sumNodal += nodal[i];
    sumBernstein += weights[i];
  }
  EXPECT_NEAR(sumBernstein, sumNodal, 1e-13);
  EXPECT_NEAR(sumBernstein, op.GetCoveredMeasure(), 1e-13);
}

TEST(BernsteinForm, MatrixOnMeshes)
{
  ExpectForm(Square(3, 0.2, 11));
  ExpectForm(Cube(2, 0.15, 12));
}

struct Lumped
{
  mp::MortarOperator Op;
  std::vector<double> Source, Target;
  Lumped(const NodalMesh& target, const NodalMesh& source, double (*f)(const double*),
    bool bounded = false)
  {
    const mp::MeshView s = source.View();
    mp::BoxGridLocator locator(s);
    EXPECT_TRUE(this->Op.Build(target.View(), s, &locator)) << this->Op.GetError();
    for (Index p = 0; p < source.NumberOfPoints(); ++p)
    {
      this->Source.push_back(f(source.Point(p)));
    }
    this->Target.assign(size_t(target.NumberOfPoints()), 0.0);
    mp::ApplyOptions options;
    options.Mass = mp::MassType::Lumped;
    options.Bounded = bounded;
    EXPECT_TRUE(this->Op.Apply(this->Source.data(), 1, this->Target.data(), -1.0, options).Ok);
  }
  /// The integrals over the covered part of the target and of the source field.
  std::pair<double, double> Integrals() const
  {
    double target = 0.0, source = 0.0;
    for (size_t i = 0; i < this->Target.size(); ++i)
    {
      target += this->Op.GetCoveredIntegrals()[i] * this->Target[i];
    }
    const std::vector<double> rhs = [&] {
      std::vector<double> r(this->Target.size());
      this->Op.GetMixedMass().MultiplyRows(this->Source.data(), r.data(), 1, 0, Index(r.size()));
      return r;
    }();
    for (double r : rhs)
    {
      source += r;
    }
    return { target, source };
  }
};

double Constant(const double*)
{
  return 3.5;
}
double Bump(const double* x)
{
  return std::exp(-30.0 * ((x[0] - 0.4) * (x[0] - 0.4) + (x[1] - 0.6) * (x[1] - 0.6)));
}
double Step(const double* x)
{
  return x[0] + 0.3 * x[1] > 0.55 ? 1.0 : 0.0;
}

/// Every value of `target` within [low, high] (to rounding: a mean of
/// ones is 1 to an ulp).
void ExpectWithin(const std::vector<double>& values, double low, double high)
{
  for (double v : values)
  {
    EXPECT_GE(v, low - 1e-14);
    EXPECT_LE(v, high + 1e-14);
  }
}

// From a linear source (P1 on the split of a second-order mesh: every
// function non-negative) the lumped values are means of node values; from
// a second-order source, means of its field, which overshoots its nodes
// next to a step: bounds clip them back.
TEST(BernsteinForm, LumpedOnSecondOrderTargets)
{
  // tri6 squares, tet10 cubes, curved tri6 disks, tri6 surfaces in space,
  // edge3 curves.
  const std::vector<std::array<NodalMesh, 2>> pairs = { { Square(4, 0.2, 21), Square(6, 0.2, 22) },
    { Cube(2, 0.15, 23), Cube(3, 0.15, 24) }, { Disk(4), Disk(5) },
    { Tilted(Square(4, 0.2, 25)), Tilted(Square(5, 0.2, 26)) }, { Line(5, 27), Line(7, 28) } };
  for (auto pair : pairs)
  {
    // (Copies: their Nodal views pointed into the list's elements.)
    NodalMesh& target = pair[0];
    target.Finish();
    pair[1].Finish();
    NodalMesh linear = pair[1];
    linear.Linear = true;
    for (const NodalMesh* source : std::vector<const NodalMesh*>{ &pair[1], &linear })
    {
      Lumped l(target, *source, Constant);
      EXPECT_TRUE(l.Op.HasBernsteinForm());
      ExpectWithin(l.Target, 3.5 * (1 - 1e-12), 3.5 * (1 + 1e-12));
      for (auto f : { Bump, Step })
      {
        Lumped l(target, *source, f);
        const auto integrals = l.Integrals();
        EXPECT_NEAR(integrals.first, integrals.second, 1e-12);
        if (source == &linear)
        {
          ExpectWithin(l.Target, 0.0, 1.0);
          if (f == Bump)
          {
            EXPECT_GT(*std::min_element(l.Target.begin(), l.Target.end()), 0.0);
          }
        }
      }
      Lumped bounded(target, *source, Step, true);
      const auto integrals = bounded.Integrals();
      EXPECT_NEAR(integrals.first, integrals.second, 1e-12);
      ExpectWithin(bounded.Target, 0.0, 1.0);
    }
    if (target.Dimension > 1 && target.Space == 0)
    {
      // (What the bounds are for: a second-order source's step overshoots.)
      Lumped overshoots(target, pair[1], Step);
      EXPECT_LT(*std::min_element(overshoots.Target.begin(), overshoots.Target.end()), -1e-3);
    }
  }
}

/// Quad8 cells of an n x n grid of quadrilaterals (corners jittered by up
/// to `jitter`: then not parallelograms), each split on its nodes into its
/// 4 corner triangles and the 2 of its mid nodes' quadrilateral.
NodalMesh Quads8(int n, double jitter, unsigned seed)
{
  const Grid g{ n, 2 };
  NodalMesh mesh;
  mesh.Points = GridCorners(g, jitter, seed);
  PlaceMidNodes(g, mesh.Points);
  for (int j = 0; j + 2 < g.Size(); j += 2)
  {
    for (int i = 0; i + 2 < g.Size(); i += 2)
    {
      const std::array<Index, 8> q = { g.Id(i, j), g.Id(i + 2, j), g.Id(i + 2, j + 2),
        g.Id(i, j + 2), g.Id(i + 1, j), g.Id(i + 2, j + 1), g.Id(i + 1, j + 2), g.Id(i, j + 1) };
      mesh.Types.push_back(NodalType::Quad8);
      mesh.Nodes.insert(mesh.Nodes.end(), q.begin(), q.end());
      mesh.Offsets.push_back(Index(mesh.Nodes.size()));
      mesh.Simplex({ q[0], q[4], q[7] });
      mesh.Simplex({ q[4], q[1], q[5] });
      mesh.Simplex({ q[5], q[2], q[6] });
      mesh.Simplex({ q[7], q[6], q[3] });
      mesh.Simplex({ q[4], q[5], q[6] });
      mesh.Simplex({ q[4], q[6], q[7] });
    }
  }
  mesh.Finish();
  return mesh;
}

/// The values of the points some cell of `mesh` uses (a grid's quadrilateral centres are not).
std::vector<double> Used(const NodalMesh& mesh, const std::vector<double>& values)
{
  std::vector<char> used(values.size(), 0);
  for (Index node : mesh.Nodes)
  {
    used[size_t(node)] = 1;
  }
  std::vector<double> kept;
  for (size_t i = 0; i < values.size(); ++i)
  {
    if (used[i])
    {
      kept.push_back(values[i]);
    }
  }
  return kept;
}

// Quad8 targets in their signed form: the lumped coefficients are no means
// (the functions dip below zero), clipped to their rows' bounds without
// being asked: constants exact, the integral kept, every node within the
// source's range. On jittered squares the cells are the quad9 space with a
// hidden centre (Geometry/HiddenNodes.h), on the affine ones VTK's own.
TEST(BernsteinForm, LumpedOnSerendipityTargets)
{
  for (double jitter : { 0.0, 0.2 })
  {
    NodalMesh target = Quads8(5, jitter, 31);
    ASSERT_TRUE(BernsteinForm::Covers(target.View(false)));
    NodalMesh source = Square(6, 0.2, 32);
    NodalMesh linear = source;
    linear.Linear = true;
    linear.Finish();
    for (const NodalMesh* from : { &source, &linear })
    {
      Lumped constant(target, *from, Constant);
      EXPECT_TRUE(constant.Op.HasBernsteinForm());
      ExpectWithin(Used(target, constant.Target), 3.5 * (1 - 1e-12), 3.5 * (1 + 1e-12));
      for (bool bounded : { false, true })
      {
        for (auto f : { Bump, Step })
        {
          Lumped l(target, *from, f, bounded);
          const auto integrals = l.Integrals();
          EXPECT_NEAR(integrals.first, integrals.second, 1e-12) << jitter;
          const std::vector<double> nodes = Used(target, l.Target);
          ExpectWithin(nodes, 0.0, 1.0);
          if (f == Bump)
          {
            EXPECT_GT(*std::min_element(nodes.begin(), nodes.end()), 0.0) << jitter;
          }
        }
      }
    }
    // The weights of the signed functions are positive, the nodal ones not.
    BernsteinForm form;
    form.Build(target.View(false));
    EXPECT_TRUE(form.IsSigned());
    const mp::MeshView s = source.View();
    mp::BoxGridLocator locator(s);
    mp::MortarOperator op;
    ASSERT_TRUE(op.Build(target.View(), s, &locator)) << op.GetError();
    const std::vector<double>& nodal = op.GetCoveredIntegrals();
    std::vector<double> weights(nodal.size());
    form.Transpose(nodal.data(), 1, weights.data());
    const std::vector<double> used = Used(target, weights);
    EXPECT_LT(*std::min_element(nodal.begin(), nodal.end()), 0.0);
    EXPECT_GT(*std::min_element(used.begin(), used.end()), 0.0);
  }
}

// A quad8 target reaching past the source: functions covered in part;
// every valid node still keeps a constant and stays within the source's
// range. (Their functions being non-negative on these nearly affine
// cells, none weighs zero or less here.)
TEST(BernsteinForm, LumpedOnSerendipityCoveredInPart)
{
  NodalMesh target = Quads8(5, 0.2, 34);
  for (size_t i = 0; i < target.Points.size(); i += 3)
  {
    target.Points[i] = 0.5 + 1.3 * (target.Points[i] - 0.5);
    target.Points[i + 1] = 0.5 + 1.3 * (target.Points[i + 1] - 0.5);
  }
  NodalMesh source = Square(6, 0.2, 35);
  const double fill = -1.0;
  Lumped constant(target, source, Constant);
  int valid = 0;
  for (double v : constant.Target)
  {
    valid += v != fill;
    EXPECT_TRUE(v == fill || std::abs(v - 3.5) <= 3.5e-12) << v;
  }
  EXPECT_GT(valid, 0);
  for (bool bounded : { false, true })
  {
    for (auto f : { Bump, Step })
    {
      Lumped l(target, source, f, bounded);
      for (double v : l.Target)
      {
        EXPECT_TRUE(v == fill || (v >= -1e-14 && v <= 1 + 1e-14)) << v;
        EXPECT_TRUE(f != Bump || v == fill || v > 0.0) << v;
      }
    }
  }
}

TEST(BernsteinForm, RefusedOnMixedEdgeShares)
{
  // A tri6 and a hex20 in one mesh (the shares are read per parent: no
  // split needed).
  NodalMesh mesh = Square(1, 0.0, 33);
  mesh.Types.push_back(NodalType::Hexa20);
  for (Index k = 0; k < 20; ++k)
  {
    mesh.Nodes.push_back(k % mesh.NumberOfPoints());
  }
  mesh.Offsets.push_back(Index(mesh.Nodes.size()));
  mesh.Finish();
  const mp::MeshView view = mesh.View(false);
  EXPECT_EQ(BernsteinForm::EdgeShares(view),
    BernsteinForm::QuarterShare | BernsteinForm::SevenSixteenthsShare);
  EXPECT_FALSE(BernsteinForm::Covers(view));
}
} // namespace
