// SPDX-License-Identifier: BSD-3-Clause
// The operator between two surfaces or two curves, with the reach and the
// normals' angle on the target's view: the surface and curve tests' harness.
#ifndef MeshProjection_Testing_ReachProjection_h
#define MeshProjection_Testing_ReachProjection_h

#include "GeneratedMeshes.h"
#include "Transfer/MortarOperator.h"

#include <cmath>
#include <functional>
#include <map>
#include <vector>

namespace mptest
{
struct ReachProjection
{
  mp::MortarOperator Op;
  bool Ok = false;
  ReachProjection(const TestMesh& target, const TestMesh& source, double reach = 0.5,
    double minCosine = 0.7071, mp::SearchMethod method = mp::SearchMethod::AdvancingFront)
  {
    mp::MeshView t = target.View();
    t.SurfaceReach = reach;
    t.SurfaceMinCosine = minCosine;
    mp::BoxGridLocator locator(source.View());
    mp::OperatorOptions options;
    options.Method = method;
    options.KeepPieces = true;
    this->Ok = this->Op.Build(t, source.View(), &locator, options);
  }
  std::vector<double> Apply(const std::vector<double>& us) const
  {
    std::vector<double> ut(this->Op.GetValid().size());
    this->Op.Apply(us.data(), 1, ut.data(), std::nan(""));
    return ut;
  }
  /// Per target cell, the summed measure of its pieces.
  std::map<Index, double> Covered() const
  {
    std::map<Index, double> measure;
    const auto& pieces = this->Op.GetPieces();
    for (Index i = 0; i < pieces.Size(); ++i)
    {
      measure[pieces.TargetCell[i]] += pieces.Measure[i];
    }
    return measure;
  }
  /// int u_t over the covered target (the row sums of M_tt times u_t) and
  /// sum of M_ts u_s, which conservation makes equal.
  std::pair<double, double> Integrals(
    const std::vector<double>& us, const std::vector<double>& ut) const
  {
    double target = 0.0;
    for (size_t i = 0; i < ut.size(); ++i)
    {
      target += this->Op.GetCoveredIntegrals()[i] * ut[i];
    }
    std::vector<double> rhs(ut.size(), 0.0);
    const mp::CsrMatrix& mts = this->Op.GetMixedMass();
    mts.MultiplyRows(us.data(), rhs.data(), 1, 0, mts.Rows);
    double source = 0.0;
    for (double r : rhs)
    {
      source += r;
    }
    return { target, source };
  }
};

/// f at every point of `m`.
inline std::vector<double> SampleAtPoints(const TestMesh& m, double (*f)(const double*))
{
  std::vector<double> u(static_cast<size_t>(m.NumberOfPoints()));
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    u[p] = f(&m.Points[3 * p]);
  }
  return u;
}

/// The largest |u - f| over the points of `m` (infinite when a value is not finite).
inline double MaxPointError(
  const TestMesh& m, const std::vector<double>& u, double (*f)(const double*))
{
  double error = 0.0;
  for (Index p = 0; p < m.NumberOfPoints(); ++p)
  {
    const double e = std::fabs(u[p] - f(&m.Points[3 * p]));
    error = std::isfinite(e) ? std::max(error, e) : HUGE_VAL;
  }
  return error;
}
} // namespace mptest

#endif
