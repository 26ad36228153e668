// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarBlocks.h
 * @brief The local mortar blocks of a piece from its moments.
 *
 * A piece (Geometry) gives its moments up to order 2 about a point o as the
 * symmetric K x K matrix M (K = d + 1: M[0][0] the measure, M[0][a] the
 * first moments, M[a][b] the second moments of x - o). A space (Space.h)
 * gives its basis functions on a cell as affine functions of x - o,
 * coefficient rows l[i] (constant first, then the gradient). The integral
 * of the product of two affine functions f, g over the piece is f^T M g;
 * with M g formed once per function g, a block of such products costs K^2
 * multiplications per function instead of per product.
 */
#ifndef MeshProjection_Kernel_MortarBlocks_h
#define MeshProjection_Kernel_MortarBlocks_h

#include "Geometry/Moments.h"

#include <cmath>

namespace mp
{
/// Mg = M g for the moment matrix M (symmetric) and the affine function g.
template <int K>
inline void MomentTimes(const double (&M)[K][K], const double* g, double (&Mg)[K])
{
  for (int a = 0; a < K; ++a)
  {
    double sum = 0.0;
    for (int b = 0; b < K; ++b)
    {
      sum += M[a][b] * g[b];
    }
    Mg[a] = sum;
  }
}

template <int K>
inline double DotK(const double* f, const double (&g)[K])
{
  double sum = 0.0;
  for (int a = 0; a < K; ++a)
  {
    sum += f[a] * g[a];
  }
  return sum;
}

/// Mtt[i][k] += int lt_i lt_k (symmetric), for N functions.
template <int N, int K>
void AddTargetBlock(const double (&lt)[N][K], const double (&M)[K][K], double (&Mtt)[N][N])
{
  for (int k = 0; k < N; ++k)
  {
    double Mg[K];
    MomentTimes<K>(M, lt[k], Mg);
    for (int i = 0; i <= k; ++i)
    {
      const double v = DotK<K>(lt[i], Mg);
      Mtt[i][k] += v;
      if (i != k)
      {
        Mtt[k][i] += v;
      }
    }
  }
}

/// Mts[i][j] += int lt_i ls_j, for Nt target and Ns source functions.
template <int Nt, int Ns, int K>
void AddMixedBlock(const double (&lt)[Nt][K], const double (&ls)[Ns][K], const double (&M)[K][K],
  double (&Mts)[Nt][Ns])
{
  for (int j = 0; j < Ns; ++j)
  {
    double Mg[K];
    MomentTimes<K>(M, ls[j], Mg);
    for (int i = 0; i < Nt; ++i)
    {
      Mts[i][j] += DotK<K>(lt[i], Mg);
    }
  }
}

/**
 * field[c * K + a] += (M u_c)[a] for the source fields u_c = sum_j u[j][c]
 * ls_j (u[j]: the values of source function j), all affine functions about
 * the origin of the moments M: the integrals of u_c against any affine
 * function f are then f^T field_c, summed over pieces first. Always
 * inlined into the assembler, as the moments it reads (Moments.h).
 */
template <int Ns, int K>
inline __attribute__((always_inline)) void AddFieldMoments(const double (&ls)[Ns][K],
  const double (&M)[K][K], const double* const (&u)[Ns], int components, double* field)
{
  for (int c = 0; c < components; ++c)
  {
    double f[K];
    for (int k = 0; k < K; ++k)
    {
      f[k] = 0.0;
      for (int j = 0; j < Ns; ++j)
      {
        f[k] += u[j][c] * ls[j][k];
      }
    }
    double Mf[K];
    MomentTimes<K>(M, f, Mf);
    for (int a = 0; a < K; ++a)
    {
      field[c * K + a] += Mf[a];
    }
  }
}

} // namespace mp

#endif
