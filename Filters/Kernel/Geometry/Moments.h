// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Moments.h
 * @brief Moments of pieces (measure, first and second moments, K = D + 1
 *        rows) moved from one origin to another and summed.
 */
#ifndef MeshProjection_Kernel_Moments_h
#define MeshProjection_Kernel_Moments_h

namespace mp
{
/**
 * The moment matrix M of a piece, taken about the point o, as `shifted`,
 * taken about the point o - d (d = o minus the new origin): first moments
 * gain d m0, second moments d m1^T + m1 d^T + d d^T m0. Always inlined:
 * called, its entries stored one by one were read back by the caller's
 * two-lane loads, which wait for such stores to retire (a sizeable part of
 * the search's own time, with TriangleIntersector::Moments alike).
 */
template <int K>
inline __attribute__((always_inline)) void ShiftMoments(
  const double (&M)[K][K], const double* d, double (&shifted)[K][K])
{
  constexpr int D = K - 1;
  shifted[0][0] = M[0][0];
  double first[D];
  for (int a = 0; a < D; ++a)
  {
    first[a] = M[0][a + 1] + d[a] * M[0][0];
    shifted[0][a + 1] = first[a];
    shifted[a + 1][0] = first[a];
  }
  for (int a = 0; a < D; ++a)
  {
    for (int b = a; b < D; ++b)
    {
      // With the shifted first moments: m2 + d m1^T + m1' d^T, m1' = m1 + d m0.
      const double v = M[a + 1][b + 1] + d[a] * M[0][b + 1] + first[a] * d[b];
      shifted[a + 1][b + 1] = v;
      shifted[b + 1][a + 1] = v;
    }
  }
}

/**
 * Adds the moment matrix M of a piece, taken about the point o, to
 * `moments`, taken about the point o - d (d = o minus the new origin):
 * first moments gain d m0, second moments d m1^T + m1 d^T + d d^T m0.
 * Summing the pieces of a target cell about one of its corners gives the
 * moments of the covered part of the cell, from which its target mass
 * block follows once per cell instead of once per piece.
 */
template <int K>
void AddShiftedMoments(const double (&M)[K][K], const double* d, double (&moments)[K][K])
{
  double shifted[K][K];
  ShiftMoments<K>(M, d, shifted);
  for (int a = 0; a < K; ++a)
  {
    for (int b = 0; b < K; ++b)
    {
      moments[a][b] += shifted[a][b];
    }
  }
}
} // namespace mp

#endif
