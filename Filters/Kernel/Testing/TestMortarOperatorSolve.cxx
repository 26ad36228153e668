// SPDX-License-Identifier: BSD-3-Clause
// The operator's solves and the systems they name (MortarOperator.h): a
// solve's progress and stop, ApplyResult's system (plain or aggregated), the
// fringe's functions without a stencil, M_tt completed after the search.
#include "GeneratedMeshes.h"
#include "MortarTestSupport.h"
#include "Threads.h"
#include "Transfer/MortarOperator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using mortartest::LShapeWithHole;
using mortartest::MeshPair;
using mortartest::Smooth;
using mp::Index;
using mptest::TestMesh;

// The solve reports how far it has come and stops when asked: the result
// with a progress hook that lets it go on is the one without, bit for bit;
// a hook that says stop ends it (false, no direct solver, WasStopped).
TEST(MortarProjector, SolveProgressAndStop)
{
  const TestMesh target = mptest::GridMesh(24, 22, 0.25, 141, 0, 0, 1, 1, LShapeWithHole);
  const TestMesh source = mptest::GridMesh(19, 27, 0.25, 142, 0, 0, 1, 1, LShapeWithHole);
  const std::vector<double> us = mptest::Sample(source, Smooth);
  mp::BoxGridLocator locator(source.View());
  mp::MortarOperator projector;
  ASSERT_TRUE(projector.Build(target.View(), source.View(), &locator));
  std::vector<double> plain(static_cast<size_t>(target.NumberOfPoints()));
  const mp::ApplyResult first = projector.Apply(us.data(), 1, plain.data(), std::nan(""));
  ASSERT_TRUE(first);
  EXPECT_FALSE(first.Stopped);
  EXPECT_FALSE(first.System.Aggregated);
  EXPECT_EQ(first.System.Valid, &projector.GetValid());
  EXPECT_EQ(first.System.CoveredIntegrals, &projector.GetCoveredIntegrals());
  EXPECT_EQ(first.System.NumberOfValid, projector.GetNumberOfValid());
  std::vector<double> reported;
  mp::SolveOptions watched;
  watched.Progress = [&reported](double done) {
    reported.push_back(done);
    return true;
  };
  std::vector<double> again(plain.size());
  ASSERT_TRUE(projector.Apply(us.data(), 1, again.data(), std::nan(""), watched));
  EXPECT_EQ(again, plain);
  ASSERT_GT(reported.size(), 5u);
  for (double f : reported)
  {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
  }
  EXPECT_GT(reported.back(), 0.7); // near the tolerance at the last iterations
  EXPECT_LT(reported.front(), 0.5);
  int calls = 0;
  mp::SolveOptions stopping;
  stopping.Progress = [&calls](double) { return ++calls < 3; };
  std::vector<double> stopped(plain.size());
  const mp::ApplyResult halted =
    projector.Apply(us.data(), 1, stopped.data(), std::nan(""), stopping);
  EXPECT_FALSE(halted);
  EXPECT_TRUE(halted.Stopped);
  EXPECT_EQ(calls, 3);
  // And the next solve is not taken for stopped.
  const mp::ApplyResult next = projector.Apply(us.data(), 1, again.data(), std::nan(""));
  ASSERT_TRUE(next);
  EXPECT_FALSE(next.Stopped);
}

// Each Apply says which system it solved: after AggregateFringe a
// consistent Apply solves the aggregated one (the fringe's least covered
// functions invalid and filled, their covered integrals given to their
// stencils: the same total), a lumped Apply M_tt's; the operator's getters
// stay M_tt's whatever the last Apply solved.
TEST(MortarProjector, ApplyResultNamesTheSystemItSolved)
{
  const TestMesh target = mptest::CubeMesh(7, 6, 5, 0.2, 151);
  TestMesh source = mptest::CubeMesh(6, 5, 7, 0.2, 152);
  for (size_t i = 0; i < source.Points.size(); ++i)
  {
    source.Points[i] = 0.9 * source.Points[i] + 0.17 * static_cast<double>(i % 3 + 1) - 0.2;
  }
  source.Finish();
  const std::vector<double> us = mptest::Sample(source, Smooth);
  mp::BoxGridLocator locator(source.View());
  mp::MortarOperator op;
  ASSERT_TRUE(op.Build(target.View(), source.View(), &locator));
  const mp::ProjectedSystem assembled = op.GetAssembledSystem();
  EXPECT_FALSE(assembled.Aggregated);
  EXPECT_EQ(assembled.Valid, &op.GetValid());
  EXPECT_EQ(assembled.NumberOfValid, op.GetNumberOfValid());
  ASSERT_GT(op.AggregateFringe(target.View(), 0.25, mp::SolverHooks()), 0);
  const double fill = -7.0;
  std::vector<double> consistent(static_cast<size_t>(target.NumberOfPoints()));
  const mp::ApplyResult solved = op.Apply(us.data(), 1, consistent.data(), fill);
  ASSERT_TRUE(solved);
  EXPECT_FALSE(solved.Stopped);
  ASSERT_TRUE(solved.System.Aggregated);
  const std::vector<char>& valid = *solved.System.Valid;
  ASSERT_EQ(valid.size(), consistent.size());
  Index count = 0, dropped = 0;
  for (size_t i = 0; i < valid.size(); ++i)
  {
    count += valid[i];
    dropped += op.GetValid()[i] && !valid[i];
    EXPECT_TRUE(!valid[i] || op.GetValid()[i]) << i; // dropping only
    if (!valid[i])
    {
      EXPECT_EQ(consistent[i], fill) << i;
    }
  }
  EXPECT_EQ(count, solved.System.NumberOfValid);
  EXPECT_GT(dropped, 0);
  EXPECT_EQ(op.GetNumberOfValid(), count + dropped); // the getters: M_tt's
  auto total = [](const std::vector<double>& v) {
    double t = 0.0;
    for (double x : v)
    {
      t += x;
    }
    return t;
  };
  const double whole = total(op.GetCoveredIntegrals());
  EXPECT_NEAR(total(*solved.System.CoveredIntegrals), whole, 1e-12 * whole);
  mp::ApplyOptions lumped;
  lumped.Mass = mp::MassType::Lumped;
  std::vector<double> means(consistent.size());
  const mp::ApplyResult averaged = op.Apply(us.data(), 1, means.data(), fill, lumped);
  ASSERT_TRUE(averaged);
  EXPECT_FALSE(averaged.System.Aggregated);
  EXPECT_EQ(averaged.System.Valid, &op.GetValid());
  EXPECT_EQ(averaged.System.NumberOfValid, op.GetNumberOfValid());
  // The first result still names its own system.
  EXPECT_TRUE(solved.System.Aggregated);
  EXPECT_EQ(solved.System.Valid, op.GetSystem(mp::MassType::Consistent).Valid);
}

// A source covering only a corner of a target cell: every function it
// reaches is covered a sliver of its support and has no well-covered
// point to be extended from (FringeExtension::Stranded). AggregateFringe
// aggregates none but drops them all: a consistent Apply leaves no value
// valid (each would be a fit to the sliver) and fills every one.
TEST(MortarProjector, FringeDropsFunctionsWithNoStencil)
{
  const TestMesh target = mptest::CubeMesh(5, 5, 5, 0.2, 161);
  TestMesh source = mptest::CubeMesh(2, 2, 2, 0.0, 162);
  for (double& x : source.Points)
  {
    x = 0.1 * x - 0.08; // the box [-0.08, 0.02]^3
  }
  source.Finish();
  const std::vector<double> us = mptest::Sample(source, Smooth);
  mp::BoxGridLocator locator(source.View());
  mp::MortarOperator op;
  ASSERT_TRUE(op.Build(target.View(), source.View(), &locator));
  ASSERT_GT(op.GetNumberOfValid(), 0);
  EXPECT_EQ(op.AggregateFringe(target.View(), 0.25, mp::SolverHooks()), 0);
  EXPECT_EQ(op.GetFringe().Stranded, op.GetNumberOfValid());
  const double fill = -7.0;
  std::vector<double> u(static_cast<size_t>(target.NumberOfPoints()));
  const mp::ApplyResult solved = op.Apply(us.data(), 1, u.data(), fill);
  ASSERT_TRUE(solved);
  ASSERT_TRUE(solved.System.Aggregated);
  EXPECT_EQ(solved.System.NumberOfValid, 0);
  for (size_t i = 0; i < u.size(); ++i)
  {
    EXPECT_FALSE((*solved.System.Valid)[i]) << i;
    EXPECT_EQ(u[i], fill) << i;
  }
}

// M_tt is assembled after the search, from the target alone: with
// DeferTargetMass the operator has no matrix, validity or solver until
// CompleteTargetMass, which then gives the very matrix a plain Build does;
// a view of the same meshes with 32-bit connectivity (what a renumbered
// copy holds) gives the same operator bit for bit; concurrent tasks the
// same pattern and values within 1e-15 (a cell's pieces come in the order
// of its task's front). P1 and P0 targets, 2D (covered in part: the
// source's boundary and hole cut target cells) and 3D.
TEST(MortarProjector, TargetMassAfterTheSearch)
{
  TestMesh shifted = mptest::CubeMesh(5, 6, 5, 0.2, 131);
  mptest::Move3D(shifted, 0.1, 0.05, 0.9, 0.1, 0.05, -0.05);
  const MeshPair pairs[] = {
    { "2D", mptest::GridMesh(31, 27, 0.25, 141, 0, 0, 1, 1, LShapeWithHole),
      mptest::GridMesh(23, 29, 0.25, 142, -0.1, 0.05, 1, 1, LShapeWithHole) },
    { "3D", mptest::CubeMesh(6, 5, 6, 0.2, 132), shifted }
  };
  for (const MeshPair& pair : pairs)
  {
    const mp::MeshView target = pair.Target.View();
    const mp::MeshView source = pair.Source.View();
    // The same meshes through 32-bit connectivity.
    std::vector<std::int32_t> narrow[2];
    mp::MeshView narrowViews[2] = { target, source };
    for (int m = 0; m < 2; ++m)
    {
      const mp::MeshView& v = m == 0 ? target : source;
      for (Index i = 0; i < v.NumberOfCells * v.CornersPerCell(); ++i)
      {
        narrow[m].push_back(static_cast<std::int32_t>(v.Connectivity[i]));
      }
      narrowViews[m].Connectivity = nullptr;
      narrowViews[m].Connectivity32 = narrow[m].data();
    }
    for (mp::SpaceType space : { mp::SpaceType::P1, mp::SpaceType::P0 })
    {
      const std::string name =
        std::string(pair.Name) + (space == mp::SpaceType::P1 ? " P1" : " P0");
      auto build = [&](const mp::MeshView& t, const mp::MeshView& s, int tasks, bool defer,
                     mp::MortarOperator& op) {
        mp::BoxGridLocator locator(s);
        mp::OperatorOptions options;
        options.TargetSpace = space;
        options.SourceSpace = space;
        options.DeferTargetMass = defer;
        options.Runner = tasks > 1 ? mptest::ThreadRunner(tasks) : mp::TaskRunner();
        EXPECT_TRUE(op.Build(t, s, &locator, options)) << name;
      };
      mp::MortarOperator plain;
      build(target, source, 1, false, plain);
      const mp::CsrMatrix& m = plain.GetTargetMass();
      ASSERT_GT(m.Values.size(), 0u) << name;
      std::vector<double> us(static_cast<size_t>(plain.GetNumberOfSourceFunctions()));
      for (size_t j = 0; j < us.size(); ++j)
      {
        us[j] = std::sin(0.7 * static_cast<double>(j)) + 2.0;
      }
      std::vector<double> expected(static_cast<size_t>(plain.GetNumberOfTargetFunctions()));
      ASSERT_TRUE(plain.Apply(us.data(), 1, expected.data(), -1.0)) << name;
      // Cells covered in part: the covered integrals fall short of the whole
      // cells' somewhere (else the blocks kept would not be tested).
      Index partial = 0;
      for (double f : plain.GetCoveredFraction())
      {
        partial += f > 0.0 && f < 1.0 - 1e-9;
      }
      EXPECT_GT(partial, 5) << name;
      // tolerance 0: bit for bit.
      auto same = [&](
                    const mp::MortarOperator& op, const std::string& what, double tolerance = 0.0) {
        const mp::CsrMatrix& o = op.GetTargetMass();
        ASSERT_EQ(o.Rows, m.Rows) << name << what;
        EXPECT_TRUE(
          std::equal(o.RowStart.begin(), o.RowStart.end(), m.RowStart.begin(), m.RowStart.end()))
          << name << what;
        EXPECT_TRUE(std::equal(
          o.ColumnIndex.begin(), o.ColumnIndex.end(), m.ColumnIndex.begin(), m.ColumnIndex.end()))
          << name << what;
        ASSERT_EQ(o.Values.size(), m.Values.size()) << name << what;
        double scale = 0.0;
        for (double v : m.Values)
        {
          scale = std::max(scale, std::fabs(v));
        }
        for (size_t i = 0; i < m.Values.size(); ++i)
        {
          ASSERT_LE(std::fabs(o.Values[i] - m.Values[i]), tolerance * scale)
            << name << what << ", entry " << i;
        }
        EXPECT_EQ(op.GetValid(), plain.GetValid()) << name << what;
        for (size_t i = 0; i < expected.size(); ++i)
        {
          ASSERT_LE(std::fabs(op.GetCoveredIntegrals()[i] - plain.GetCoveredIntegrals()[i]),
            tolerance * scale)
            << name << what;
        }
        for (size_t c = 0; c < plain.GetCoveredFraction().size(); ++c)
        {
          ASSERT_LE(
            std::fabs(op.GetCoveredFraction()[c] - plain.GetCoveredFraction()[c]), tolerance)
            << name << what;
        }
        std::vector<double> ut(expected.size());
        ASSERT_TRUE(op.Apply(us.data(), 1, ut.data(), -1.0)) << name << what;
        for (size_t i = 0; i < expected.size(); ++i)
        {
          // (The solve's own tolerance for a tolerance > 0.)
          ASSERT_NEAR(ut[i], expected[i], tolerance > 0.0 ? 1e-10 : 0.0)
            << name << what << ", function " << i;
        }
      };
      {
        mp::MortarOperator deferred;
        build(target, source, 1, true, deferred);
        EXPECT_EQ(deferred.GetNumberOfTargetFunctions(), m.Rows) << name;
        EXPECT_TRUE(deferred.GetValid().empty()) << name;
        EXPECT_EQ(deferred.GetTargetMass().Values.size(), 0u) << name;
        std::vector<double> ut(expected.size());
        EXPECT_FALSE(deferred.Apply(us.data(), 1, ut.data(), -1.0)) << name;
        deferred.CompleteTargetMass(target);
        same(deferred, " deferred");
        deferred.CompleteTargetMass(target); // a second call changes nothing
        same(deferred, " completed twice");
      }
      for (int tasks : { 2, 3, 7 })
      {
        mp::MortarOperator threaded;
        build(target, source, tasks, false, threaded);
        same(threaded, " " + std::to_string(tasks) + " tasks", 1e-15);
      }
      mp::MortarOperator narrowOp;
      build(narrowViews[0], narrowViews[1], 1, false, narrowOp);
      same(narrowOp, " 32-bit connectivity");
      EXPECT_TRUE(std::equal(narrowOp.GetSourceCovered().begin(), narrowOp.GetSourceCovered().end(),
        plain.GetSourceCovered().begin(), plain.GetSourceCovered().end()))
        << name;
    }
  }
}
