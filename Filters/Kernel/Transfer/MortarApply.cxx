// SPDX-License-Identifier: BSD-3-Clause
// MortarOperator (MortarOperator.h), the projection of fields: the
// right-hand sides M_ts u_s, the solve with M_tt (or its lumped rows), the
// optional bounds (clip and assured sum) and the fill of invalid functions.
#include "Transfer/MortarOperator.h"

#include "Transfer/StageClock.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <vector>

namespace mp
{
ApplyResult MortarOperator::Apply(const double* sourceValues, int components, double* targetValues,
  double fill, const SolveOptions& solve, const SolverHooks& hooks) const
{
  ApplyOptions options;
  options.Solve = solve;
  return this->Apply(sourceValues, components, targetValues, fill, options, hooks);
}

namespace
{
/**
 * Clip and assured sum on column `k` of x (rows x c): each valid value into
 * [low_i, high_i], then the difference to `total` (sum of w_i x_i wanted)
 * spread in proportion to w_i times the room left. On a distributed system
 * the sums are over the rows each part counts, summed over the parts (`w`,
 * `low`, `high` and x complete in shared rows, so every part clips them
 * alike).
 */
void ClipAndAssuredSum(double* x, int c, int k, const std::vector<double>& w,
  const std::vector<char>& valid, const std::vector<double>& low, const std::vector<double>& high,
  double total, const SolverHooks& hooks)
{
  const Index n = static_cast<Index>(w.size());
  const char* counted = hooks.Counted;
  double clipped = 0.0;
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      double& v = x[i * c + k];
      v = std::min(high[i], std::max(low[i], v));
      clipped += !counted || counted[i] ? w[i] * v : 0.0;
    }
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&clipped, 1);
  }
  const double missing = total - clipped;
  double room = 0.0;
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i] && (!counted || counted[i]))
    {
      room += w[i] * (missing > 0 ? high[i] - x[i * c + k] : x[i * c + k] - low[i]);
    }
  }
  if (hooks.Reduce)
  {
    hooks.Reduce(&room, 1);
  }
  if (!(room > 0.0) || missing == 0.0)
  {
    return; // nothing to give back, or no room (then the sum was already at a bound)
  }
  const double scale = missing / room;
  for (Index i = 0; i < n; ++i)
  {
    if (valid[i])
    {
      double& v = x[i * c + k];
      v += scale * (missing > 0 ? high[i] - v : v - low[i]);
    }
  }
}

/**
 * Each row's bounds for component k: the Source values of its columns (a
 * shared row's columns are spread over the parts: their extremes,
 * completed).
 */
void RowBounds(const CsrMatrix& mixed, Index n, const double* sourceValues, int components, int k,
  const SolverHooks& hooks, std::vector<double>& low, std::vector<double>& high)
{
  for (Index i = 0; i < n; ++i)
  {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (Index p = mixed.RowStart[i]; p < mixed.RowStart[i + 1]; ++p)
    {
      const double u = sourceValues[static_cast<Index>(mixed.ColumnIndex[p]) * components + k];
      lo = std::min(lo, u);
      hi = std::max(hi, u);
    }
    low[i] = lo;
    high[i] = hi;
  }
  if (hooks.ExchangeMinimum)
  {
    // The largest as the smallest of the negated values.
    std::vector<double> extremes(2 * static_cast<size_t>(n));
    for (Index i = 0; i < n; ++i)
    {
      extremes[2 * i] = low[i];
      extremes[2 * i + 1] = -high[i];
    }
    hooks.ExchangeMinimum(extremes.data(), 2);
    for (Index i = 0; i < n; ++i)
    {
      low[i] = extremes[2 * i];
      high[i] = -extremes[2 * i + 1];
    }
  }
}

/**
 * Bound preservation (ApplyOptions::Bounded), on x (n rows x
 * `components`): per component, every row's bounds (RowBounds) and the
 * integral wanted (sum_i over the rows `counted` of rhs_i: the integral of
 * u_s over the covered part), then ClipAndAssuredSum of the rows `clip`
 * with `weights` (complete in shared rows); the rows `centred` (if given)
 * then take the middle of their bounds. Apply has checked that M_ts and
 * the hooks this needs are there.
 */
void ClipToLocalBounds(const CsrMatrix& mixed, const std::vector<char>& clip,
  const std::vector<char>& counted, const std::vector<double>& weights, Index n,
  const double* sourceValues, int components, const double* rhs, double* x,
  const SolverHooks& hooks, const std::vector<char>* centred = nullptr)
{
  std::vector<double> low(static_cast<size_t>(n)), high(static_cast<size_t>(n));
  for (int k = 0; k < components; ++k)
  {
    double total = 0.0;
    for (Index i = 0; i < n; ++i)
    {
      if (counted[i] && (!hooks.Counted || hooks.Counted[i]))
      {
        total += rhs[i * components + k]; // sum_i (M_ts u_s)_i = int u_s over the covered part
      }
    }
    if (hooks.Reduce)
    {
      hooks.Reduce(&total, 1);
    }
    RowBounds(mixed, n, sourceValues, components, k, hooks, low, high);
    ClipAndAssuredSum(x, components, k, weights, clip, low, high, total, hooks);
    for (Index i = 0; centred && i < n; ++i)
    {
      if ((*centred)[i])
      {
        x[i * components + k] = 0.5 * (low[i] + high[i]);
      }
    }
  }
}
} // namespace

bool MortarOperator::SolveWithHalo(const double* rhs, double* targetValues, int components,
  const SolveOptions& solve, const SolverHooks& haloHooks) const
{
  const Index n = this->TargetMass.Rows;
  const Index rows = this->FringeMass.Rows;
  LargeVector<double> x(static_cast<size_t>(rows) * components, 0.0);
  if (solve.StartFromX)
  {
    // A ghost row starts from its owner's value (the only one counted).
    for (Index i = 0; i < n; ++i)
    {
      if (!haloHooks.Counted || haloHooks.Counted[i])
      {
        std::copy(targetValues + i * components, targetValues + (i + 1) * components,
          x.begin() + i * components);
      }
    }
    haloHooks.Exchange(x.data(), components);
  }
  const bool ok = this->FringeSolver->Solve(rhs, x.data(), components, solve, haloHooks);
  ExtendFromFree(this->Fringe, x.data(), components);
  std::copy(x.begin(), x.begin() + n * components, targetValues);
  return ok;
}

bool MortarOperator::RightHandSides(const double* sourceValues, int components,
  LargeVector<double>& product, bool copy, const double*& rhs) const
{
  if (this->Options.Fields)
  {
    if (sourceValues != this->Options.Fields || components != this->Options.FieldComponents)
    {
      return false; // built for other fields: M_ts was not stored
    }
    if (!copy)
    {
      rhs = this->Rhs.data();
      return true;
    }
    product.assign(this->Rhs.begin(), this->Rhs.end());
    rhs = product.data();
    return true;
  }
  const Index n = this->TargetMass.Rows;
  product.resize(static_cast<size_t>(n) * components);
  this->Options.Runner.ForRanges(n, [&](Index begin, Index end) {
    this->MixedMass.MultiplyRows(sourceValues, product.data(), components, begin, end);
    return 0.0;
  });
  rhs = product.data();
  return true;
}

void MortarOperator::RestrictRightHandSides(
  const double* b, int components, LargeVector<double>& product) const
{
  // With a halo the aggregated system has the extended rows (this part's,
  // then its ghosts', which start at 0).
  const Index n = this->TargetMass.Rows;
  const Index rows = this->FringeMass.Rows;
  LargeVector<double> padded;
  if (rows > n)
  {
    padded.assign(static_cast<size_t>(rows) * components, 0.0);
    std::copy(b, b + n * components, padded.begin());
    b = padded.data();
  }
  LargeVector<double> restricted(static_cast<size_t>(rows) * components);
  RestrictToFree(this->Fringe, b, restricted.data(), components);
  product.swap(restricted);
}

ProjectedSystem MortarOperator::GetAssembledSystem() const
{
  ProjectedSystem system;
  system.Valid = &this->Valid;
  system.CoveredIntegrals = &this->RowSums;
  system.NumberOfValid = this->NumberOfValid;
  return system;
}

ProjectedSystem MortarOperator::GetSystem(MassType mass) const
{
  if (!this->FringeSystem || mass != MassType::Consistent)
  {
    return this->GetAssembledSystem();
  }
  ProjectedSystem system;
  system.Aggregated = true;
  system.Valid = &this->FringeValid;
  system.CoveredIntegrals = &this->FringeRowSums;
  system.NumberOfValid = this->NumberOfValid - this->FringeDropped;
  return system;
}

bool MortarOperator::Solve(const ApplyOptions& options, const double* rhs, double* targetValues,
  int components, const SolverHooks& hooks, const SolverHooks& rowHooks, ApplyResult& result) const
{
  const Index n = this->TargetMass.Rows;
  const bool aggregated = result.System.Aggregated;
  if (options.Solve.StartFromX)
  {
    // Invalid functions hold the fill value of a previous Apply (NaN, say):
    // their rows and columns of M_tt are zero but for the diagonal, yet
    // 0 * NaN would spread it through the products. Their solution is 0.
    for (Index i = 0; i < n; ++i)
    {
      if (!this->Valid[i] || (aggregated && this->Fringe.Aggregated[i]))
      {
        std::fill(targetValues + i * components, targetValues + (i + 1) * components, 0.0);
      }
    }
  }
  if (options.Mass == MassType::Lumped)
  {
    // Row sums of M_tt completed across parts like the right-hand sides.
    std::vector<double> sums(this->RowSums);
    if (hooks.Exchange)
    {
      hooks.Exchange(sums.data(), 1);
    }
    for (Index i = 0; i < n; ++i)
    {
      for (int k = 0; k < components; ++k)
      {
        targetValues[i * components + k] = sums[i] > 0.0 ? rhs[i * components + k] / sums[i] : 0.0;
      }
    }
    return true;
  }
  bool ok = false;
  if (aggregated && this->HaloPoints >= 0)
  {
    ok = this->SolveWithHalo(rhs, targetValues, components, options.Solve, rowHooks);
  }
  else if (aggregated)
  {
    ok = this->FringeSolver->Solve(rhs, targetValues, components, options.Solve, hooks);
    ExtendFromFree(this->Fringe, targetValues, components);
  }
  else
  {
    ok = this->Solver->Solve(rhs, targetValues, components, options.Solve, hooks);
  }
  result.Stopped = (aggregated ? this->FringeSolver : this->Solver)->WasStopped();
  return ok;
}

bool MortarOperator::KeepWithinBounds(const ApplyOptions& options, const ProjectedSystem& system,
  const double* sourceValues, int components, const double* rhs, double* targetValues,
  const SolverHooks& hooks) const
{
  if (options.Mass != MassType::Consistent)
  {
    return true; // lumped values are means of source values: within every bound
  }
  const Index n = this->TargetMass.Rows;
  if (!options.Bounded)
  {
    return true;
  }
  if (!this->HasMixedMass() || (hooks.Exchange && !hooks.ExchangeMinimum))
  {
    return false; // local bounds need M_ts's rows (and, shared, their parts' extremes)
  }
  if (!this->NodalTarget)
  {
    // The weights: M_tt's row sums, completed like the right-hand sides.
    std::vector<double> weights(*system.CoveredIntegrals);
    if (hooks.Exchange)
    {
      hooks.Exchange(weights.data(), 1);
    }
    ClipToLocalBounds(this->MixedMass, *system.Valid, *system.Valid, weights, n, sourceValues,
      components, rhs, targetValues, hooks);
    return true;
  }
  if (this->Bernstein.Empty())
  {
    return false; // nodal values of quadratic functions have no positive weights
  }
  // The Bernstein coefficients clipped: each within the bounds of its
  // node's row (the Source on its support), every coefficient a valid node
  // reads (M_tt's valid functions: also those an aggregated fringe drops),
  // with the Bernstein functions' integrals as weights.
  std::vector<double> weights(static_cast<size_t>(n));
  this->Bernstein.Transpose(system.CoveredIntegrals->data(), 1, weights.data());
  if (hooks.Exchange)
  {
    hooks.Exchange(weights.data(), 1);
  }
  LargeVector<double> b(static_cast<size_t>(n) * components);
  this->Bernstein.FromNodes(targetValues, components, b.data());
  // (A signed function covered in part may weigh zero or less: its
  // coefficient the middle of its bounds, as LumpBernstein does.)
  std::vector<char> clip(this->Valid), orphans(static_cast<size_t>(n), 0);
  bool anyOrphan = false;
  const bool signedForm = options.Signed || this->Bernstein.IsSigned();
  for (Index m = 0; signedForm && m < n; ++m)
  {
    orphans[m] = clip[m] && !(weights[m] > 0.0);
    clip[m] = clip[m] && !orphans[m];
    anyOrphan = anyOrphan || orphans[m];
  }
  ClipToLocalBounds(this->MixedMass, clip, *system.Valid, weights, n, sourceValues, components, rhs,
    b.data(), hooks, anyOrphan ? &orphans : nullptr);
  this->Bernstein.ToNodes(b.data(), components, targetValues);
  return true;
}

bool MortarOperator::LumpBernstein(const ApplyOptions& options, const double* sourceValues,
  int components, const double* rhs, double* targetValues, const SolverHooks& hooks) const
{
  // rhs: the Bernstein functions' right-hand sides int B_m u_s, completed;
  // their integrals over the covered part alike, from the nodal ones.
  const Index n = this->TargetMass.Rows;
  std::vector<double> integrals(static_cast<size_t>(n));
  this->Bernstein.Transpose(this->RowSums.data(), 1, integrals.data());
  if (hooks.Exchange)
  {
    hooks.Exchange(integrals.data(), 1);
  }
  std::vector<char> usable(static_cast<size_t>(n));
  LargeVector<double> b(static_cast<size_t>(n) * components);
  for (Index m = 0; m < n; ++m)
  {
    usable[m] = this->Valid[m] && integrals[m] > 0.0;
    for (int k = 0; k < components; ++k)
    {
      b[m * components + k] = usable[m] ? rhs[m * components + k] / integrals[m] : 0.0;
    }
  }
  const bool signedForm = options.Signed || this->Bernstein.IsSigned();
  if (options.Bounded || signedForm)
  {
    // Means of the Source field, within the bounds of its node values when
    // its functions are non-negative; a second-order Source's field may
    // leave them between its nodes. A signed form's (serendipity cells,
    // pyramids) are no means: always clipped.
    if (!this->HasMixedMass() || (hooks.Exchange && !hooks.ExchangeMinimum))
    {
      return false;
    }
    // A signed function covered in part may integrate to zero or less
    // there: a valid node's coefficient all the same, the middle of its
    // bounds (its share of the integral is then not the Source's).
    std::vector<char> orphans(static_cast<size_t>(n), 0);
    bool anyOrphan = false;
    for (Index m = 0; m < n; ++m)
    {
      orphans[m] = signedForm && this->Valid[m] && !usable[m];
      anyOrphan = anyOrphan || orphans[m];
    }
    ClipToLocalBounds(this->MixedMass, usable, usable, integrals, n, sourceValues, components, rhs,
      b.data(), hooks, anyOrphan ? &orphans : nullptr);
    for (Index m = 0; anyOrphan && m < n; ++m)
    {
      usable[m] = usable[m] || orphans[m];
    }
  }
  this->Bernstein.ToNodes(b.data(), components, usable, targetValues);
  return true;
}

ApplyResult MortarOperator::Apply(const double* sourceValues, int components, double* targetValues,
  double fill, const ApplyOptions& options, const SolverHooks& hooks) const
{
  const auto start = std::chrono::steady_clock::now();
  const Index n = this->TargetMass.Rows;
  // A fringe aggregated (AggregateFringe) and a consistent solve: the
  // system P^T M_tt P (with a halo: over the extended rows, completed by
  // the halo's hooks, on every part alike as the options are).
  ApplyResult result;
  result.System = this->GetSystem(options.Mass);
  auto done = [&](bool ok) {
    result.Ok = ok;
    result.Seconds = this->Timings.Solve = SecondsSince(start);
    return result;
  };
  // A part without rows of a distributed system still takes part in its sums.
  if (!this->Solver || components <= 0 || (n == 0 && !hooks.Reduce && !hooks.Exchange))
  {
    return done(this->Solver != nullptr || components <= 0);
  }
  const bool aggregated = result.System.Aggregated;
  const bool halo = aggregated && this->HaloPoints >= 0;
  if (halo && !options.FringeHooks)
  {
    return done(false);
  }
  const bool bernstein = options.Mass == MassType::Lumped && this->NodalTarget;
  if (bernstein && this->Bernstein.Empty())
  {
    // Second-order functions without a Bernstein form (MassType::Lumped):
    // refused rather than guessed.
    return done(false);
  }
  const SolverHooks& rowHooks = halo ? *options.FringeHooks : hooks;
  // The right-hand sides: summed during the search for the build's fields,
  // else M_ts u_s; P^T b when aggregated (before the shared rows are
  // completed: each part gives its share of an aggregated row to the
  // stencil); then completed across parts.
  LargeVector<double> product;
  const double* rhs = nullptr;
  if (!this->RightHandSides(sourceValues, components, product, hooks.Exchange != nullptr, rhs))
  {
    return done(false);
  }
  if (aggregated)
  {
    this->RestrictRightHandSides(rhs, components, product);
    rhs = product.data();
  }
  if (bernstein)
  {
    // The Bernstein functions' right-hand sides, C^T b, from each part's
    // share before the shared rows are completed (a shared corner's
    // Bernstein function reads the mid nodes of every part around it).
    LargeVector<double> onBernstein(static_cast<size_t>(n) * components);
    this->Bernstein.Transpose(rhs, components, onBernstein.data());
    product.swap(onBernstein);
    rhs = product.data();
  }
  if (rowHooks.Exchange)
  {
    rowHooks.Exchange(product.data(), components);
  }
  const bool ok = bernstein
    ? this->LumpBernstein(options, sourceValues, components, rhs, targetValues, hooks)
    : this->Solve(options, rhs, targetValues, components, hooks, rowHooks, result) &&
      this->KeepWithinBounds(
        options, result.System, sourceValues, components, rhs, targetValues, hooks);
  const std::vector<char>& valid = *result.System.Valid;
  for (Index i = 0; i < n; ++i)
  {
    if (!valid[i])
    {
      std::fill(targetValues + i * components, targetValues + (i + 1) * components, fill);
    }
  }
  return done(ok);
}
} // namespace mp
