// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BlockCG.h
 * @brief Conjugate gradients for several right-hand sides at once, with hooks.
 *
 * Solves A X = B for the symmetric positive definite A (the target mass
 * matrix) and `c` right-hand sides stored side by side (row i of B holds
 * entries i*c .. i*c + c-1), iterated in lockstep with a Jacobi
 * preconditioner: each column has its own step lengths, a converged column
 * stops changing, and every iteration reads the matrix once for all.
 * Row ranges run as concurrent tasks (TaskRunner).
 *
 * Every global quantity goes through SolverHooks, so that a distributed
 * solve (rows split over MPI ranks, rows at partition interfaces held
 * partially by several ranks) adds its communication without touching the
 * algorithm: Reduce sums the local dot products over all ranks, Exchange
 * completes the shared rows after each matrix-vector product (and of the
 * diagonal and row sums), and Counted tells which rows a rank counts in its
 * dot products. With the default hooks the solve is serial.
 *
 * Where the iterations do not converge (targets covered only in slivers
 * make the matrix ill conditioned) DirectSolve factors the matrix (a sparse
 * LDL^T, Eigen) for the columns concerned.
 */
#ifndef MeshProjection_Kernel_BlockCG_h
#define MeshProjection_Kernel_BlockCG_h

#include "Mesh/Tasks.h"
#include "Transfer/CsrMatrix.h"

#include <functional>
#include <memory>
#include <vector>

namespace mp
{
struct SolverHooks
{
  /// Sums `count` local partial sums over all parts of the system, in place.
  std::function<void(double* values, int count)> Reduce;
  /// Completes the rows shared with other parts in `vectors` (rows x width).
  std::function<void(double* vectors, int width)> Exchange;
  /// As Exchange, with the smallest of the parts' values instead of their
  /// sum (the bounds of PreserveBounds); may be null where Exchange is.
  std::function<void(double* vectors, int width)> ExchangeMinimum;
  /**
   * Solves the whole distributed system A X = B directly for the columns
   * k with converged[k] == 0 (collective: every part calls it with the same
   * flags), writing this part's rows of X; false when the factorization
   * fails. Used where rows are shared (Exchange set); null there: no direct
   * fallback. (Parts that share no row factor their own rows.)
   */
  std::function<bool(
    const CsrMatrix& A, const double* B, double* X, int c, const std::vector<char>& converged)>
    Direct;
  /// Per row: 1 when this part counts it in dot products (null: every row).
  const char* Counted = nullptr;
};

struct SolveOptions
{
  double Tolerance = 1e-14; ///< relative residual per column, |r| <= tolerance |b|
  int MaxIterations = 500;  ///< before the direct solver takes over
  /// Start from the X given (e.g. the previous time step's solution)
  /// rather than from the lumped solution x_i = b_i / sum_k A_ik.
  bool StartFromX = false;
  /**
   * Called after each iteration with how far the solve has come, in [0, 1]
   * (for the column furthest from its tolerance: the reduction of its
   * residual so far over the reduction asked, in logarithms); false stops
   * it: Solve then returns false at once (no direct solver) and
   * BlockCG::WasStopped() says so. Null: not called. Serial systems: a
   * distributed solve must stop on every part at once (leave it null).
   */
  std::function<bool(double done)> Progress;
};

class BlockCG
{
public:
  /// `rowSums`, when given, are the row sums of `matrix` summed in row
  /// order (the same bits Iterate would sum; 0 allowed for rows whose only
  /// entry is a decoupling 1, whose right-hand side is 0): the lumped start
  /// of a serial system reads them instead of summing the matrix again.
  /// They must outlive the solver. `lumpedStart` false: the iterations
  /// start from 0 instead (matrices whose row sums are no weights: the
  /// second-order cells' own functions sum to zero or less at corners).
  BlockCG(const CsrMatrix& matrix, const TaskRunner& runner, const double* rowSums = nullptr,
    bool lumpedStart = true);
  ~BlockCG();

  /**
   * Iterates on A X = B (`c` columns); converged[k] tells whether column k
   * reached the tolerance. Returns the number of iterations.
   */
  int Iterate(const double* B, double* X, int c, const SolveOptions& options,
    std::vector<char>& converged, const SolverHooks& hooks = SolverHooks()) const;

  /**
   * Solves A X = B: the iterations, then the sparse direct solver for the
   * columns that did not converge: this part's own matrix, or, where rows
   * are shared with other parts, through the Direct hook (without one it
   * returns false for them). False when that fails too.
   */
  bool Solve(const double* B, double* X, int c, const SolveOptions& options,
    const SolverHooks& hooks = SolverHooks()) const;
  /// Whether the last Iterate or Solve was stopped by SolveOptions::Progress.
  bool WasStopped() const { return this->Stopped; }

  /**
   * The sparse direct solver (LDL^T) on a matrix given by its entries
   * (duplicates summed: a distributed matrix's parts gathered in one
   * place): solves for `c` right-hand sides B (rows x c), into X. False
   * when the factorization fails.
   */
  static bool SolveEntries(Index rows, const std::vector<Index>& row,
    const std::vector<Index>& column, const std::vector<double>& value, const double* B, double* X,
    int c);

private:
  template <int FixedC>
  int IterateFixed(const double* B, double* X, int c, const SolveOptions& options,
    std::vector<char>& converged, const SolverHooks& hooks) const;
  struct Direct;
  const CsrMatrix& A;
  TaskRunner Runner;
  const double* RowSums = nullptr;
  bool LumpedStart = true;
  mutable std::unique_ptr<Direct> Factor; ///< built on the first need
  mutable bool Stopped = false;
};
} // namespace mp

#endif
