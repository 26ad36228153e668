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
} // namespace mp

#endif
