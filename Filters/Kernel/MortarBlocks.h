// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MortarBlocks.h
 * @brief The local mortar blocks of a piece from its barycentric functions.
 *
 * Both intersectors write the target's and the source's barycentric
 * coordinates as affine functions of local coordinates (coefficient rows
 * lt[i], ls[j]) and integrate products of two affine functions from the
 * piece's moments (`product`). This adds the N x N blocks
 * Mts[i][j] += int lt_i ls_j and Mtt[i][k] += int lt_i lt_k (symmetric).
 *
 * When M_ts itself is not needed, AddFieldBlock adds the right-hand sides
 * rhs_i += int lt_i u directly, with u = sum_j u_j ls_j the source field on
 * the piece as one affine function: N products per component instead of the
 * N x N of the block.
 */
#ifndef MeshProjection_Kernel_MortarBlocks_h
#define MeshProjection_Kernel_MortarBlocks_h

namespace mp
{
template <int N, class Product>
void AddMortarBlocks(const double (&lt)[N][N], const double (&ls)[N][N], const Product& product,
  double Mts[N][N], double Mtt[N][N])
{
  for (int i = 0; i < N; ++i)
  {
    for (int j = 0; j < N; ++j)
    {
      Mts[i][j] += product(lt[i], ls[j]);
    }
    for (int k = i; k < N; ++k)
    {
      const double v = product(lt[i], lt[k]);
      Mtt[i][k] += v;
      if (k != i)
      {
        Mtt[k][i] += v;
      }
    }
  }
}
/// Mtt[i][k] += int lt_i lt_k (symmetric) only.
template <int N, class Product>
void AddTargetBlock(const double (&lt)[N][N], const Product& product, double Mtt[N][N])
{
  for (int i = 0; i < N; ++i)
  {
    for (int k = i; k < N; ++k)
    {
      const double v = product(lt[i], lt[k]);
      Mtt[i][k] += v;
      if (k != i)
      {
        Mtt[k][i] += v;
      }
    }
  }
}

/**
 * rhs[i][c] += int lt_i u_c for the source field with values u[j][c] at the
 * source corners (c < components).
 */
template <int N, class Product>
void AddFieldBlock(const double (&lt)[N][N], const double (&ls)[N][N], const Product& product,
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
    for (int i = 0; i < N; ++i)
    {
      rhs[i][c] += product(lt[i], field);
    }
  }
}
} // namespace mp

#endif
