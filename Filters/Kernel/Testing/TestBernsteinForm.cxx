// SPDX-License-Identifier: BSD-3-Clause
// The Bernstein form of a second-order target (Transfer/BernsteinForm.h),
// and the lumped and bounded projections made in it (MortarApply.cxx):
//  - per supported type, at random reference points: the Bernstein
//    functions are non-negative and sum to 1, and sum_n B_m(node n) N_n is
//    B_m (the change of basis is exact); the serendipity types and the
//    pyramid are not supported;
//  - on tri6 squares and tet10 cubes: C's rows are non-negative and sum to
//    1, FromNodes inverts ToNodes, and C^T of the nodal functions' integrals
//    (some zero or negative) is positive;
//  - Lumped onto tri6, tet10, curved tri6, tri6 surface and edge3 targets: a constant stays exact, the
//    integral is the source's; from a linear source a positive field stays
//    positive and a 0/1 indicator within [0, 1]; from a second-order one
//    (whose field overshoots its nodes) bounds bring it back; refused on a
//    quad8 target.
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
  NodalType::Quad9, NodalType::Hexa27, NodalType::Wedge18 };

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
        EXPECT_GE(B[m], 0.0) << int(type) << " function " << m;
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

TEST(BernsteinForm, LumpedRefusedOnSerendipity)
{
  // One quad8 on the unit square, split on its nodes (corner triangles,
  // the inner quadrilateral of the mid nodes in two).
  NodalMesh mesh;
  mesh.Points = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0, 0, 1, 0.5, 0, 0.5, 1, 0, 0, 0.5, 0 };
  mesh.Types.push_back(NodalType::Quad8);
  mesh.Nodes = { 0, 1, 2, 3, 4, 5, 6, 7 };
  mesh.Offsets.push_back(8);
  mesh.Simplex({ 0, 4, 7 });
  mesh.Simplex({ 4, 1, 5 });
  mesh.Simplex({ 5, 2, 6 });
  mesh.Simplex({ 7, 6, 3 });
  mesh.Simplex({ 4, 5, 6 });
  mesh.Simplex({ 4, 6, 7 });
  mesh.Finish();
  EXPECT_FALSE(BernsteinForm::Covers(mesh.View(false)));
  const mp::MeshView s = mesh.View();
  mp::BoxGridLocator locator(s);
  mp::MortarOperator op;
  ASSERT_TRUE(op.Build(mesh.View(), s, &locator)) << op.GetError();
  EXPECT_TRUE(op.HasNodalTarget());
  EXPECT_FALSE(op.HasBernsteinForm());
  std::vector<double> u(size_t(mesh.NumberOfPoints()), 1.0), v(u.size());
  mp::ApplyOptions options;
  options.Mass = mp::MassType::Lumped;
  EXPECT_FALSE(op.Apply(u.data(), 1, v.data(), 0.0, options).Ok);
  options.Mass = mp::MassType::Consistent;
  options.Bounded = true;
  EXPECT_FALSE(op.Apply(u.data(), 1, v.data(), 0.0, options).Ok);
}
} // namespace
