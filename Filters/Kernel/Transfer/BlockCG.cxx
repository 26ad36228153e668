// SPDX-License-Identifier: BSD-3-Clause
#include "Transfer/BlockCG.h"

#include "Mesh/LargeArray.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>

namespace mp
{
namespace
{
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, Index>;
using Triplet = Eigen::Triplet<double, Index>;

/// Per column sums, added component-wise (for TaskRunner::ForRanges).
struct Sums
{
  std::vector<double> Values;
  Sums() = default;
  explicit Sums(size_t n)
    : Values(n, 0.0)
  {
  }
  Sums& operator+=(const Sums& o)
  {
    for (size_t k = 0; k < this->Values.size(); ++k)
    {
      this->Values[k] += o.Values[k];
    }
    return *this;
  }
};
/**
 * Where a range's partial sums are added up: for compile-time widths a
 * local array (kept in registers: added through part.Values, each term
 * would be a load and a store that the next row waits for), copied into
 * `part` at the end; else part's own values. The same additions in the
 * same order either way.
 */
template <int FixedC, int PerColumn>
struct LocalSums
{
  double Local[FixedC > 0 ? PerColumn * FixedC : 1] = {};
  Sums& Part;
  explicit LocalSums(Sums& part)
    : Part(part)
  {
  }
  double& operator[](int k)
  {
    if constexpr (FixedC > 0)
    {
      return this->Local[k];
    }
    else
    {
      return this->Part.Values[k];
    }
  }
  Sums& Done()
  {
    if constexpr (FixedC > 0)
    {
      std::copy(this->Local, this->Local + PerColumn * FixedC, this->Part.Values.begin());
    }
    return this->Part;
  }
};
/**
 * A range's read-only copy of per-column values (step lengths, factors,
 * flags): for compile-time widths a local array, which the compiler keeps
 * in registers (read through the vector, each value would be reloaded
 * after every store to the solver's vectors); else the vector itself.
 */
template <int FixedC, class T>
struct LocalValues
{
  T Local[FixedC > 0 ? FixedC : 1];
  const T* Source;
  explicit LocalValues(const std::vector<T>& values)
    : Source(values.data())
  {
    if constexpr (FixedC > 0)
    {
      std::copy(values.begin(), values.begin() + FixedC, this->Local);
    }
  }
  T operator[](int k) const
  {
    if constexpr (FixedC > 0)
    {
      return this->Local[k];
    }
    else
    {
      return this->Source[k];
    }
  }
};
} // namespace

struct BlockCG::Direct
{
  std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix>> Solver;
};

BlockCG::BlockCG(const CsrMatrix& matrix, const TaskRunner& runner, const double* rowSums)
  : A(matrix)
  , Runner(runner)
  , RowSums(rowSums)
{
}

BlockCG::~BlockCG() = default;

int BlockCG::Iterate(const double* B, double* X, int c, const SolveOptions& options,
  std::vector<char>& converged, const SolverHooks& hooks) const
{
  // Compile-time widths for the usual few fields (scalars, vectors).
  switch (c)
  {
    case 1:
      return this->IterateFixed<1>(B, X, c, options, converged, hooks);
    case 2:
      return this->IterateFixed<2>(B, X, c, options, converged, hooks);
    case 3:
      return this->IterateFixed<3>(B, X, c, options, converged, hooks);
    case 4:
      return this->IterateFixed<4>(B, X, c, options, converged, hooks);
    default:
      return this->IterateFixed<0>(B, X, c, options, converged, hooks);
  }
}

template <int FixedC>
int BlockCG::IterateFixed(const double* B, double* X, int dynamicC, const SolveOptions& options,
  std::vector<char>& converged, const SolverHooks& hooks) const
{
  const int c = FixedC > 0 ? FixedC : dynamicC;
  const Index n = this->A.Rows;
  const size_t size = static_cast<size_t>(n) * c;
  const char* counted = hooks.Counted;
  auto reduce = [&hooks](Sums& s) {
    if (hooks.Reduce)
    {
      hooks.Reduce(s.Values.data(), static_cast<int>(s.Values.size()));
    }
  };
  auto exchange = [&hooks](double* v, int width) {
    if (hooks.Exchange)
    {
      hooks.Exchange(v, width);
    }
  };
  // The preconditioned residual z = D^-1 r is never stored: it is formed
  // where it is used (one vector less to hold and to stream).
  // Written whole by the row ranges' tasks below before they are read (not
  // zeroed first: each task is the first to touch its pages).
  UninitializedLargeVector<double> r(size);
  UninitializedLargeVector<double> p(size);
  UninitializedLargeVector<double> q(size);
  UninitializedLargeVector<double> inverseDiagonal(static_cast<size_t>(n));
  // The row sums for the lumped start: given (a serial system's), or summed
  // here (a distributed one's are completed across the parts in place).
  const bool given = this->RowSums && !hooks.Exchange;
  UninitializedLargeVector<double> rowSums(options.StartFromX || given ? 0 : static_cast<size_t>(n));
  const double* sumOf = given ? this->RowSums : rowSums.data();
  converged.assign(static_cast<size_t>(c), 0);
  this->Runner.ForRanges(n, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i)
    {
      // (A row of a distributed system may be empty on this part: 0, the
      // other parts complete it.)
      inverseDiagonal[i] = this->A.Entry(i, i);
      if (!options.StartFromX && !given)
      {
        double rowSum = 0.0;
        for (Index k = this->A.RowStart[i]; k < this->A.RowStart[i + 1]; ++k)
        {
          rowSum += this->A.Values[k];
        }
        rowSums[i] = rowSum;
      }
    }
    return 0.0;
  });
  exchange(inverseDiagonal.data(), 1);
  if (!options.StartFromX && !given)
  {
    exchange(rowSums.data(), 1);
  }
  // Started from the lumped-mass solution x_i = b_i / sum_k A_ik (already
  // second-order accurate for smooth fields: fewer iterations), or from X.
  Sums bb = this->Runner.ForRanges(n, [&](Index begin, Index end) {
    Sums part(c);
    LocalSums<FixedC, 1> sum(part);
    for (Index i = begin; i < end; ++i)
    {
      inverseDiagonal[i] = 1.0 / inverseDiagonal[i];
      for (int k = 0; k < c; ++k)
      {
        const double b = B[i * c + k];
        if (!options.StartFromX)
        {
          X[i * c + k] = sumOf[i] > 0.0 ? b / sumOf[i] : 0.0;
        }
        if (!counted || counted[i])
        {
          sum[k] += b * b;
        }
      }
    }
    return sum.Done();
  });
  reduce(bb);
  UninitializedLargeVector<double>().swap(rowSums); // only the start needed them
  std::vector<double> goal(static_cast<size_t>(c));
  for (int k = 0; k < c; ++k)
  {
    goal[k] = options.Tolerance * options.Tolerance * bb.Values[k];
  }
  this->Runner.ForRanges(n, [&](Index begin, Index end) {
    this->A.Multiply<FixedC>(X, q.data(), c, begin, end);
    return 0.0;
  });
  exchange(q.data(), c);
  // Residuals, and the first direction; per column |r|^2 and r.z.
  Sums sums = this->Runner.ForRanges(n, [&](Index begin, Index end) {
    Sums part(2 * c);
    LocalSums<FixedC, 2> sum(part);
    for (Index i = begin; i < end; ++i)
    {
      const bool count = !counted || counted[i];
      for (int k = 0; k < c; ++k)
      {
        const Index e = i * c + k;
        r[e] = B[e] - q[e];
        const double z = inverseDiagonal[i] * r[e];
        p[e] = z;
        if (count)
        {
          sum[k] += r[e] * r[e];
          sum[c + k] += r[e] * z;
        }
      }
    }
    return sum.Done();
  });
  reduce(sums);
  std::vector<double> rz(static_cast<size_t>(c));
  std::vector<double> alpha(static_cast<size_t>(c));
  std::vector<double> beta(static_cast<size_t>(c));
  int open = 0;
  for (int k = 0; k < c; ++k)
  {
    // A zero field is converged at its start, at zero (a restart may have
    // started it elsewhere).
    if (bb.Values[k] == 0.0)
    {
      for (Index i = 0; i < n; ++i)
      {
        X[i * c + k] = 0.0;
      }
    }
    converged[k] = bb.Values[k] == 0.0 || sums.Values[k] <= goal[k];
    open += !converged[k];
    rz[k] = sums.Values[c + k];
  }
  // Each column's squared residual at the start, for the progress.
  const std::vector<double> start(sums.Values.begin(), sums.Values.begin() + c);
  this->Stopped = false;
  int iteration = 0;
  for (; iteration < options.MaxIterations && open > 0; ++iteration)
  {
    if (options.Progress && iteration > 0)
    {
      double done = 1.0;
      for (int k = 0; k < c; ++k)
      {
        // log(r0 / r) / log(r0 / goal), the squares' ratios alike.
        if (!converged[k] && start[k] > goal[k] && sums.Values[k] > 0.0)
        {
          const double f = std::log(start[k] / sums.Values[k]) / std::log(start[k] / goal[k]);
          done = std::min(done, std::max(0.0, f));
        }
      }
      if (!options.Progress(std::min(1.0, done)))
      {
        this->Stopped = true;
        break;
      }
    }
    // q = A p and p.q: in one pass over each range (q still in cache)
    // unless shared rows must be completed in between.
    auto dot = [&](Index begin, Index end) {
      Sums part(c);
      LocalSums<FixedC, 1> sum(part);
      for (Index i = begin; i < end; ++i)
      {
        if (counted && !counted[i])
        {
          continue;
        }
        for (int k = 0; k < c; ++k)
        {
          sum[k] += p[i * c + k] * q[i * c + k];
        }
      }
      return sum.Done();
    };
    Sums pq;
    if (hooks.Exchange)
    {
      this->Runner.ForRanges(n, [&](Index begin, Index end) {
        this->A.Multiply<FixedC>(p.data(), q.data(), c, begin, end);
        return 0.0;
      });
      exchange(q.data(), c);
      pq = this->Runner.ForRanges(n, dot);
    }
    else
    {
      pq = this->Runner.ForRanges(n, [&](Index begin, Index end) {
        this->A.Multiply<FixedC>(p.data(), q.data(), c, begin, end);
        return dot(begin, end);
      });
    }
    reduce(pq);
    for (int k = 0; k < c; ++k)
    {
      alpha[k] = converged[k] ? 0.0 : rz[k] / pq.Values[k];
    }
    // x, r and z in one pass, with |r|^2 and r.z.
    sums = this->Runner.ForRanges(n, [&](Index begin, Index end) {
      Sums part(2 * c);
      LocalSums<FixedC, 2> sum(part);
      const LocalValues<FixedC, double> step(alpha);
      for (Index i = begin; i < end; ++i)
      {
        const bool count = !counted || counted[i];
        for (int k = 0; k < c; ++k)
        {
          const Index e = i * c + k;
          X[e] += step[k] * p[e];
          r[e] -= step[k] * q[e];
          if (count)
          {
            sum[k] += r[e] * r[e];
            sum[c + k] += r[e] * (inverseDiagonal[i] * r[e]);
          }
        }
      }
      return sum.Done();
    });
    reduce(sums);
    for (int k = 0; k < c; ++k)
    {
      if (converged[k])
      {
        continue; // its direction is zeroed below
      }
      if (sums.Values[k] <= goal[k])
      {
        converged[k] = 1;
        --open;
        continue;
      }
      beta[k] = sums.Values[c + k] / rz[k];
      rz[k] = sums.Values[c + k];
    }
    if (open == 0)
    {
      ++iteration;
      break;
    }
    this->Runner.ForRanges(n, [&](Index begin, Index end) {
      const LocalValues<FixedC, double> factor(beta);
      const LocalValues<FixedC, char> done(converged);
      for (Index i = begin; i < end; ++i)
      {
        for (int k = 0; k < c; ++k)
        {
          const Index e = i * c + k;
          const double z = inverseDiagonal[i] * r[e];
          p[e] = done[k] ? 0.0 : z + factor[k] * p[e];
        }
      }
      return 0.0;
    });
  }
  return iteration;
}

bool BlockCG::Solve(const double* B, double* X, int c, const SolveOptions& options,
  const SolverHooks& hooks) const
{
  const Index n = this->A.Rows;
  this->Stopped = false;
  // A part without rows still takes part in the distributed sums.
  if (c <= 0 || (n <= 0 && !hooks.Reduce && !hooks.Exchange))
  {
    return true;
  }
  std::vector<char> converged;
  this->Iterate(B, X, c, options, converged, hooks);
  if (this->Stopped)
  {
    return false; // asked to stop: no direct solver either
  }
  if (std::all_of(converged.begin(), converged.end(), [](char done) { return done != 0; }))
  {
    return true;
  }
  if (hooks.Exchange)
  {
    // Rows shared by parts: the matrix is factored where its parts are
    // gathered (all columns left at once; every part takes part).
    return hooks.Direct && hooks.Direct(this->A, B, X, c, converged);
  }
  // This part's rows are its own (one part, or parts that share no row):
  // factored here, and with several parts every part learns whether any
  // failed (the same number of sums on every part: the columns left are
  // the same everywhere).
  bool solved = true;
  LargeVector<double> b;
  for (int k = 0; k < c && solved && n > 0; ++k)
  {
    if (converged[k])
    {
      continue;
    }
    if (!this->Factor)
    {
      SparseMatrix matrix(n, n);
      std::vector<Triplet> entries;
      entries.reserve(this->A.Values.size());
      for (Index i = 0; i < n; ++i)
      {
        for (Index p = this->A.RowStart[i]; p < this->A.RowStart[i + 1]; ++p)
        {
          entries.emplace_back(i, this->A.ColumnIndex[p], this->A.Values[p]);
        }
      }
      matrix.setFromTriplets(entries.begin(), entries.end());
      this->Factor.reset(new Direct);
      this->Factor->Solver.reset(new Eigen::SimplicialLDLT<SparseMatrix>(matrix));
    }
    solved = this->Factor->Solver->info() == Eigen::Success;
    if (!solved)
    {
      break;
    }
    b.resize(static_cast<size_t>(n));
    for (Index i = 0; i < n; ++i)
    {
      b[i] = B[i * c + k];
    }
    const Eigen::VectorXd solution =
      this->Factor->Solver->solve(Eigen::Map<const Eigen::VectorXd>(b.data(), n));
    for (Index i = 0; i < n; ++i)
    {
      X[i * c + k] = solution[i];
    }
  }
  if (hooks.Reduce)
  {
    double failed = solved ? 0.0 : 1.0;
    hooks.Reduce(&failed, 1);
    solved = failed == 0.0;
  }
  return solved;
}

bool BlockCG::SolveEntries(Index rows, const std::vector<Index>& row,
  const std::vector<Index>& column, const std::vector<double>& value, const double* B, double* X,
  int c)
{
  if (rows <= 0 || c <= 0)
  {
    return true;
  }
  std::vector<Triplet> entries;
  entries.reserve(value.size());
  for (size_t e = 0; e < value.size(); ++e)
  {
    entries.emplace_back(row[e], column[e], value[e]);
  }
  SparseMatrix matrix(rows, rows);
  matrix.setFromTriplets(entries.begin(), entries.end()); // duplicates summed
  Eigen::SimplicialLDLT<SparseMatrix> solver(matrix);
  if (solver.info() != Eigen::Success)
  {
    return false;
  }
  Eigen::VectorXd b(rows);
  for (int k = 0; k < c; ++k)
  {
    for (Index i = 0; i < rows; ++i)
    {
      b[i] = B[i * c + k];
    }
    const Eigen::VectorXd solution = solver.solve(b);
    if (solver.info() != Eigen::Success)
    {
      return false;
    }
    for (Index i = 0; i < rows; ++i)
    {
      X[i * c + k] = solution[i];
    }
  }
  return true;
}
} // namespace mp
