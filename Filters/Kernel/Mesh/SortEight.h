// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SortEight.h
 * @brief Eight values sorted by the 19 compare-exchanges of an optimal
 *        network: no data-dependent branch (an insertion sort of a few
 *        values mispredicts one or two per value).
 */
#ifndef MeshProjection_Kernel_SortEight_h
#define MeshProjection_Kernel_SortEight_h

namespace mp
{
/// Sorts v[0..8) in increasing order (pad shorter lists with the largest value).
template <class T>
inline void SortEight(T* v)
{
  auto exchange = [v](int i, int j) {
    const T a = v[i];
    const T b = v[j];
    v[i] = a < b ? a : b;
    v[j] = a < b ? b : a;
  };
  exchange(0, 2), exchange(1, 3), exchange(4, 6), exchange(5, 7);
  exchange(0, 4), exchange(1, 5), exchange(2, 6), exchange(3, 7);
  exchange(0, 1), exchange(2, 3), exchange(4, 5), exchange(6, 7);
  exchange(2, 4), exchange(3, 5);
  exchange(1, 4), exchange(3, 6);
  exchange(1, 2), exchange(3, 4), exchange(5, 6);
}
} // namespace mp

#endif
