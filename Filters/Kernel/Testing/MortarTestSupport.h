// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarTestSupport.h
 * @brief What the operator's kernel tests (TestMortarProjector.cxx,
 *        TestMortarOperatorSolve.cxx) share: a built projection, matrix
 *        entries as the former projector gave them, and the fields and
 *        domains they project.
 */
#ifndef MeshProjection_Kernel_Testing_MortarTestSupport_h
#define MeshProjection_Kernel_Testing_MortarTestSupport_h

#include "GeneratedMeshes.h"
#include "Search/CandidateLocator.h"
#include "Transfer/MortarOperator.h"

#include <cmath>
#include <vector>

namespace mortartest
{
using mp::Index;
using mptest::TestMesh;

/// A named target and source.
struct MeshPair
{
  const char* Name;
  TestMesh Target;
  TestMesh Source;
};

struct Projection
{
  mp::MortarOperator Projector;
  bool Ok = false;
  Projection(const TestMesh& target, const TestMesh& source,
    mp::SearchMethod method = mp::SearchMethod::AdvancingFront, bool keepPieces = false)
  {
    mp::BoxGridLocator locator(source.View());
    mp::OperatorOptions options;
    options.Method = method;
    options.KeepPieces = keepPieces;
    this->Ok = this->Projector.Build(target.View(), source.View(), &locator, options);
  }
  std::vector<double> Apply(const std::vector<double>& us, int components = 1) const
  {
    std::vector<double> ut(this->Projector.GetValid().size() * components);
    this->Projector.Apply(us.data(), components, ut.data(), std::nan(""));
    return ut;
  }
};

/// M_ts entry (i, j), as the projector's former MixedMassEntry.
inline double MixedMassEntry(const mp::MortarOperator& op, Index i, Index j)
{
  return op.GetMixedMass().Entry(i, j);
}

/// M_tt entry (i, k), as the projector's former TargetMassEntry: 0 on the
/// rows of invalid target points (GetTargetMass() holds 1 on their diagonal).
inline double TargetMassEntry(const mp::MortarOperator& op, Index i, Index k)
{
  return op.GetValid()[i] ? op.GetTargetMass().Entry(i, k) : 0.0;
}

inline double Smooth(double x, double y)
{
  return std::sin(3 * x) * std::cos(2 * y) + 0.5 * x;
}
inline double Linear(double x, double y)
{
  return 1.0 + 2.0 * x - 3.0 * y;
}
inline bool LShapeWithHole(double x, double y)
{
  return !(x > 0.5 && y > 0.5) && !(x > 0.25 && x < 0.5 && y > 0.25 && y < 0.5);
}
} // namespace mortartest

#endif
