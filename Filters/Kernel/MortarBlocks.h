// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarBlocks.h
 * @brief The local mortar blocks of a piece from its barycentric functions.
 *
 * Both intersectors write the target's and the source's barycentric
 * coordinates as affine functions of local coordinates (coefficient rows
 * lt[i], ls[j]: constant first, then the gradient) and hand over the piece's
 * moments up to order 2 as the symmetric matrix M (M[0][0] = measure,
 * M[0][a] = first moments, M[a][b] = second moments), so that the integral
 * of the product of two affine functions f, g over the piece is f^T M g.
 * With M g computed once per function g, a block of such products costs
 * N^2 multiplications per function instead of N^2 per product.
 *
 * This adds the N x N blocks Mts[i][j] += int lt_i ls_j and
 * Mtt[i][k] += int lt_i lt_k (symmetric). When M_ts itself is not needed,
 * AddFieldBlock adds the right-hand sides rhs_i += int lt_i u directly, with
 * u = sum_j u_j ls_j the source field on the piece as one affine function.
 */
#ifndef MeshProjection_Kernel_MortarBlocks_h
#define MeshProjection_Kernel_MortarBlocks_h

#include <cmath>

namespace mp
{
/// Mg = M g for the moment matrix M (symmetric) and the affine function g.
template <int N>
inline void MomentTimes(const double (&M)[N][N], const double* g, double (&Mg)[N])
{
  for (int a = 0; a < N; ++a)
  {
    double sum = 0.0;
    for (int b = 0; b < N; ++b)
    {
      sum += M[a][b] * g[b];
    }
    Mg[a] = sum;
  }
}

template <int N>
inline double DotN(const double* f, const double (&g)[N])
{
  double sum = 0.0;
  for (int a = 0; a < N; ++a)
  {
    sum += f[a] * g[a];
  }
  return sum;
}

/// Mtt[i][k] += int lt_i lt_k (symmetric).
template <int N>
void AddTargetBlock(const double (&lt)[N][N], const double (&M)[N][N], double Mtt[N][N])
{
  for (int k = 0; k < N; ++k)
  {
    double Mg[N];
    MomentTimes<N>(M, lt[k], Mg);
    for (int i = 0; i <= k; ++i)
    {
      const double v = DotN<N>(lt[i], Mg);
      Mtt[i][k] += v;
      if (i != k)
      {
        Mtt[k][i] += v;
      }
    }
  }
}

/// Mts[i][j] += int lt_i ls_j.
template <int N>
void AddMixedBlock(
  const double (&lt)[N][N], const double (&ls)[N][N], const double (&M)[N][N], double Mts[N][N])
{
  for (int j = 0; j < N; ++j)
  {
    double Mg[N];
    MomentTimes<N>(M, ls[j], Mg);
    for (int i = 0; i < N; ++i)
    {
      Mts[i][j] += DotN<N>(lt[i], Mg);
    }
  }
}

/// Mts[i][j] += int lt_i ls_j and Mtt[i][k] += int lt_i lt_k.
template <int N>
void AddMortarBlocks(const double (&lt)[N][N], const double (&ls)[N][N], const double (&M)[N][N],
  double Mts[N][N], double Mtt[N][N])
{
  AddMixedBlock<N>(lt, ls, M, Mts);
  AddTargetBlock<N>(lt, M, Mtt);
}

/**
 * rhs[i][c] += int lt_i u_c for the source field with values u[j][c] at the
 * source corners (c < components).
 */
template <int N>
void AddFieldBlock(const double (&lt)[N][N], const double (&ls)[N][N], const double (&M)[N][N],
  const double* const (&u)[N], int components, double* const (&rhs)[N])
{
  for (int c = 0; c < components; ++c)
  {
    double field[N];
    for (int k = 0; k < N; ++k)
    {
      field[k] = 0.0;
      for (int j = 0; j < N; ++j)
      {
        field[k] += u[j][c] * ls[j][k];
      }
    }
    double Mf[N];
    MomentTimes<N>(M, field, Mf);
    for (int i = 0; i < N; ++i)
    {
      rhs[i][c] += DotN<N>(lt[i], Mf);
    }
  }
}
/**
 * Adds the moment matrix M of a piece, taken about the point o, to
 * `moments`, taken about the point o - d (d = o minus the new origin):
 * first moments gain d m0, second moments d m1^T + m1 d^T + d d^T m0.
 * Summing the pieces of a target cell about one of its corners gives the
 * moments of the covered part of the cell, from which its M_tt block
 * follows once per cell instead of once per piece (TargetMassFromMoments).
 */
template <int N>
void AddShiftedMoments(const double (&M)[N][N], const double* d, double (&moments)[N][N])
{
  constexpr int D = N - 1;
  moments[0][0] += M[0][0];
  double first[D];
  for (int a = 0; a < D; ++a)
  {
    first[a] = M[0][a + 1] + d[a] * M[0][0];
    moments[0][a + 1] += first[a];
    moments[a + 1][0] += first[a];
  }
  for (int a = 0; a < D; ++a)
  {
    for (int b = a; b < D; ++b)
    {
      // With the shifted first moments: m2 + d m1^T + m1' d^T, m1' = m1 + d m0.
      const double v = M[a + 1][b + 1] + d[a] * M[0][b + 1] + first[a] * d[b];
      moments[a + 1][b + 1] += v;
      if (b != a)
      {
        moments[b + 1][a + 1] += v;
      }
    }
  }
}

/**
 * The M_tt block of a target cell from the moments of its covered part
 * about its corner 0 (`inverse`: the rows of the inverse Jacobian, which map
 * x - corner 0 to barycentric coordinates 1..N-1). A cell covered whole (the
 * pieces add up to its measure within 1e-12) gets the exact element mass
 * matrix, measure (1 + delta_ik) d! / (d + 2)!, free of any cancellation.
 */
template <int N>
void TargetMassFromMoments(const double (&inverse)[N - 1][N - 1], const double (&moments)[N][N],
  double measure, double (&Mtt)[N][N])
{
  constexpr int D = N - 1;
  const double covered = moments[0][0];
  if (std::fabs(covered - measure) <= 1e-12 * measure)
  {
    const double unit = covered / ((D + 1) * (D + 2)); // d! / (d + 2)! = 1 / ((d + 1)(d + 2))
    for (int i = 0; i < N; ++i)
    {
      for (int k = 0; k < N; ++k)
      {
        Mtt[i][k] = unit * (i == k ? 2.0 : 1.0);
      }
    }
    return;
  }
  double lt[N][N];
  for (int r = 0; r < D; ++r)
  {
    lt[r + 1][0] = 0.0;
    for (int a = 0; a < D; ++a)
    {
      lt[r + 1][a + 1] = inverse[r][a];
    }
  }
  for (int k = 0; k < N; ++k)
  {
    double sum = 0.0;
    for (int r = 1; r < N; ++r)
    {
      sum += lt[r][k];
    }
    lt[0][k] = (k == 0 ? 1.0 : 0.0) - sum;
  }
  for (int i = 0; i < N; ++i)
  {
    for (int k = 0; k < N; ++k)
    {
      Mtt[i][k] = 0.0;
    }
  }
  AddTargetBlock<N>(lt, moments, Mtt);
}
} // namespace mp

#endif
