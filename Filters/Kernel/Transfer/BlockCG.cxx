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
  {}
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
  double Local[FixedC > 0 ? PerColumn* FixedC : 1] = {};
  Sums& Part;
  explicit LocalSums(Sums& part)
    : Part(part)
  {}
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

/**
 * One run of BlockCG::Iterate's iterations on `c` columns (FixedC of them
 * known at compile time, 0: at run time only): the vectors and per-column
 * scalars of Jacobi-preconditioned CG, each step one or two passes over the
 * row ranges (in the runner's tasks), each global sum through the hooks.
 */
template <int FixedC>
class CGIterations
{
public:
  CGIterations(const CsrMatrix& a, const TaskRunner& runner, const double* givenRowSums,
    bool lumpedStart, const double* b, double* x, int c, const SolveOptions& options,
    std::vector<char>& converged, const SolverHooks& hooks)
    : A(a)
    , Runner(runner)
    , B(b)
    , X(x)
    , C(c)
    , N(a.Rows)
    , Options(options)
    , Converged(converged)
    , Hooks(hooks)
    , Counted(hooks.Counted)
    // Written whole by the row ranges' tasks below before they are read (not
    // zeroed first: each task is the first to touch its pages).
    , R(static_cast<size_t>(a.Rows) * c)
    , P(static_cast<size_t>(a.Rows) * c)
    , Q(static_cast<size_t>(a.Rows) * c)
    , InverseDiagonal(static_cast<size_t>(a.Rows))
    // The row sums for the lumped start: given (a serial system's), or summed
    // here (a distributed one's are completed across the parts in place).
    // (A distributed system sums and exchanges them even for a start from 0:
    // every part makes the same exchanges, whatever its own cells.)
    , Lumped(lumpedStart && !options.StartFromX)
    , Given(givenRowSums && !hooks.Exchange)
    , RowSums(options.StartFromX || this->Given ? 0 : static_cast<size_t>(a.Rows))
    , SumOf(this->Given ? givenRowSums : this->RowSums.data())
  {
    converged.assign(static_cast<size_t>(c), 0);
  }

  /// The start: the preconditioner, the lumped (or given) X, its residuals
  /// and first directions, and the columns converged already.
  void Start()
  {
    this->ReadDiagonal();
    this->StartX();
    this->FirstResiduals();
  }

  /// The columns not converged yet.
  int Open() const { return this->Opened; }

  /// How far the solve has come (SolveOptions::Progress): for the column
  /// furthest from its goal, log(r0 / r) / log(r0 / goal).
  double Progress() const
  {
    const int c = FixedC > 0 ? FixedC : this->C;
    double done = 1.0;
    for (int k = 0; k < c; ++k)
    {
      // log(r0 / r) / log(r0 / goal), the squares' ratios alike.
      if (!this->Converged[k] && this->Initial[k] > this->Goal[k] &&
        this->Residuals.Values[k] > 0.0)
      {
        const double f = std::log(this->Initial[k] / this->Residuals.Values[k]) /
          std::log(this->Initial[k] / this->Goal[k]);
        done = std::min(done, std::max(0.0, f));
      }
    }
    return std::min(1.0, done);
  }

  /// One iteration up to the new residuals: the step lengths along the
  /// directions, X and r moved, the columns that reach their goal marked.
  /// True when none is left open (then no new directions are needed).
  bool Step()
  {
    const int c = FixedC > 0 ? FixedC : this->C;
    Sums pq = this->DirectionProducts();
    this->Reduce(pq);
    for (int k = 0; k < c; ++k)
    {
      this->Alpha[k] = this->Converged[k] ? 0.0 : this->Rz[k] / pq.Values[k];
    }
    this->MoveAlong();
    this->Reduce(this->Residuals);
    for (int k = 0; k < c; ++k)
    {
      if (this->Converged[k])
      {
        continue; // its direction is zeroed below
      }
      if (this->Residuals.Values[k] <= this->Goal[k])
      {
        this->Converged[k] = 1;
        --this->Opened;
        continue;
      }
      this->Beta[k] = this->Residuals.Values[c + k] / this->Rz[k];
      this->Rz[k] = this->Residuals.Values[c + k];
    }
    return this->Opened == 0;
  }

  /// The next directions p = z + beta p (zero for converged columns).
  void NextDirections()
  {
    const int c = FixedC > 0 ? FixedC : this->C;
    const double* inverseDiagonal = this->InverseDiagonal.data();
    const double* r = this->R.data();
    double* p = this->P.data();
    this->Runner.ForRanges(this->N, [&](Index begin, Index end) {
      const LocalValues<FixedC, double> factor(this->Beta);
      const LocalValues<FixedC, char> done(this->Converged);
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

private:
  void Reduce(Sums& s) const
  {
    if (this->Hooks.Reduce)
    {
      this->Hooks.Reduce(s.Values.data(), static_cast<int>(s.Values.size()));
    }
  }
  void Exchange(double* v, int width) const
  {
    if (this->Hooks.Exchange)
    {
      this->Hooks.Exchange(v, width);
    }
  }

  /// The diagonal (inverted in StartX) and, for the lumped start, the row
  /// sums, completed across the parts.
  void ReadDiagonal()
  {
    const bool sum = !this->Options.StartFromX && !this->Given;
    double* inverseDiagonal = this->InverseDiagonal.data();
    double* rowSums = this->RowSums.data();
    this->Runner.ForRanges(this->N, [&](Index begin, Index end) {
      for (Index i = begin; i < end; ++i)
      {
        // (A row of a distributed system may be empty on this part: 0, the
        // other parts complete it.)
        inverseDiagonal[i] = this->A.Entry(i, i);
        if (sum)
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
    this->Exchange(this->InverseDiagonal.data(), 1);
    if (sum)
    {
      this->Exchange(this->RowSums.data(), 1);
    }
  }

  /// Started from the lumped-mass solution x_i = b_i / sum_k A_ik (already
  /// second-order accurate for smooth fields: fewer iterations), or from X;
  /// each column's goal from |b|^2.
  void StartX()
  {
    const int c = FixedC > 0 ? FixedC : this->C;
    const double* B = this->B;
    double* X = this->X;
    const char* counted = this->Counted;
    const double* sumOf = this->SumOf;
    const bool startFromX = this->Options.StartFromX;
    double* inverseDiagonal = this->InverseDiagonal.data();
    this->Bb = this->Runner.ForRanges(this->N, [&](Index begin, Index end) {
      Sums part(c);
      LocalSums<FixedC, 1> sum(part);
      for (Index i = begin; i < end; ++i)
      {
        inverseDiagonal[i] = 1.0 / inverseDiagonal[i];
        for (int k = 0; k < c; ++k)
        {
          const double b = B[i * c + k];
          if (!startFromX)
          {
            X[i * c + k] = this->Lumped && sumOf[i] > 0.0 ? b / sumOf[i] : 0.0;
          }
          if (!counted || counted[i])
          {
            sum[k] += b * b;
          }
        }
      }
      return sum.Done();
    });
    this->Reduce(this->Bb);
    UninitializedLargeVector<double>().swap(this->RowSums); // only the start needed them
    this->Goal.resize(static_cast<size_t>(c));
    for (int k = 0; k < c; ++k)
    {
      this->Goal[k] = this->Options.Tolerance * this->Options.Tolerance * this->Bb.Values[k];
    }
  }

  /// Residuals, and the first directions; per column |r|^2 and r.z, and
  /// which columns are converged at the start.
  void FirstResiduals()
  {
    const int c = FixedC > 0 ? FixedC : this->C;
    const Index n = this->N;
    const double* B = this->B;
    double* X = this->X;
    const char* counted = this->Counted;
    double* r = this->R.data();
    double* p = this->P.data();
    double* q = this->Q.data();
    const double* inverseDiagonal = this->InverseDiagonal.data();
    this->Runner.ForRanges(n, [&](Index begin, Index end) {
      this->A.template Multiply<FixedC>(X, q, c, begin, end);
      return 0.0;
    });
    this->Exchange(q, c);
    this->Residuals = this->Runner.ForRanges(n, [&](Index begin, Index end) {
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
    this->Reduce(this->Residuals);
    this->Rz.resize(static_cast<size_t>(c));
    this->Alpha.resize(static_cast<size_t>(c));
    this->Beta.resize(static_cast<size_t>(c));
    for (int k = 0; k < c; ++k)
    {
      // A zero field is converged at its start, at zero (a restart may have
      // started it elsewhere).
      if (this->Bb.Values[k] == 0.0)
      {
        for (Index i = 0; i < n; ++i)
        {
          X[i * c + k] = 0.0;
        }
      }
      this->Converged[k] = this->Bb.Values[k] == 0.0 || this->Residuals.Values[k] <= this->Goal[k];
      this->Opened += !this->Converged[k];
      this->Rz[k] = this->Residuals.Values[c + k];
    }
    // Each column's squared residual at the start, for the progress.
    this->Initial.assign(this->Residuals.Values.begin(), this->Residuals.Values.begin() + c);
  }

  /// q = A p and p.q: in one pass over each range (q still in cache)
  /// unless shared rows must be completed in between.
  Sums DirectionProducts()
  {
    const int c = FixedC > 0 ? FixedC : this->C;
    const Index n = this->N;
    const char* counted = this->Counted;
    const double* p = this->P.data();
    double* q = this->Q.data();
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
    if (this->Hooks.Exchange)
    {
      this->Runner.ForRanges(n, [&](Index begin, Index end) {
        this->A.template Multiply<FixedC>(p, q, c, begin, end);
        return 0.0;
      });
      this->Exchange(q, c);
      return this->Runner.ForRanges(n, dot);
    }
    return this->Runner.ForRanges(n, [&](Index begin, Index end) {
      this->A.template Multiply<FixedC>(p, q, c, begin, end);
      return dot(begin, end);
    });
  }

  /// x, r and z in one pass, with |r|^2 and r.z (into Residuals).
  void MoveAlong()
  {
    const int c = FixedC > 0 ? FixedC : this->C;
    double* X = this->X;
    const char* counted = this->Counted;
    double* r = this->R.data();
    const double* p = this->P.data();
    const double* q = this->Q.data();
    const double* inverseDiagonal = this->InverseDiagonal.data();
    this->Residuals = this->Runner.ForRanges(this->N, [&](Index begin, Index end) {
      Sums part(2 * c);
      LocalSums<FixedC, 2> sum(part);
      const LocalValues<FixedC, double> step(this->Alpha);
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
  }

  const CsrMatrix& A;
  const TaskRunner& Runner;
  const double* B;
  double* X;
  // (Each step reads `FixedC > 0 ? FixedC : this->C`: a constant expression
  // where FixedC is given, which the passes' loops over columns unroll.)
  const int C;
  const Index N;
  const SolveOptions& Options;
  std::vector<char>& Converged;
  const SolverHooks& Hooks;
  const char* Counted; ///< rows this part counts in dot products (null: all)
  // The preconditioned residual z = D^-1 r is never stored: it is formed
  // where it is used (one vector less to hold and to stream).
  UninitializedLargeVector<double> R;
  UninitializedLargeVector<double> P;
  UninitializedLargeVector<double> Q;
  UninitializedLargeVector<double> InverseDiagonal;
  const bool Lumped; ///< X starts as the lumped-mass solution (else from 0)
  const bool Given;  ///< the row sums are the solver's own (BlockCG's rowSums)
  UninitializedLargeVector<double> RowSums;
  const double* SumOf;
  Sums Bb;        ///< per column |b|^2
  Sums Residuals; ///< per column |r|^2, then r.z
  std::vector<double> Goal;
  std::vector<double> Rz;
  std::vector<double> Alpha;
  std::vector<double> Beta;
  std::vector<double> Initial; ///< each column's |r|^2 at the start
  int Opened = 0;
};
} // namespace

struct BlockCG::Direct
{
  std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix>> Solver;
};

BlockCG::BlockCG(
  const CsrMatrix& matrix, const TaskRunner& runner, const double* rowSums, bool lumpedStart)
  : A(matrix)
  , Runner(runner)
  , RowSums(rowSums)
  , LumpedStart(lumpedStart)
{}

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
  CGIterations<FixedC> cg(
    this->A, this->Runner, this->RowSums, this->LumpedStart, B, X, c, options, converged, hooks);
  cg.Start();
  this->Stopped = false;
  int iteration = 0;
  for (; iteration < options.MaxIterations && cg.Open() > 0; ++iteration)
  {
    if (options.Progress && iteration > 0 && !options.Progress(cg.Progress()))
    {
      this->Stopped = true;
      break;
    }
    if (cg.Step())
    {
      ++iteration;
      break;
    }
    cg.NextDirections();
  }
  return iteration;
}

bool BlockCG::Solve(
  const double* B, double* X, int c, const SolveOptions& options, const SolverHooks& hooks) const
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
