// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Lanes.h
 * @brief Two doubles per vector for the intersectors' filters.
 *
 * GCC/Clang vector extensions: two SSE2 lanes on x86-64, plain code
 * elsewhere. Each lane's arithmetic is the scalar expression's, in the
 * same order, so a vectorized filter gives the values one at a time would.
 * A comparison gives a Mask2 (-1 true, 0 false per lane).
 */
#ifndef MeshProjection_Kernel_Lanes_h
#define MeshProjection_Kernel_Lanes_h

#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mp
{
typedef double Doubles2 __attribute__((vector_size(16)));
typedef long long Mask2 __attribute__((vector_size(16)));

/// Lanes a, a + 1 of `values` (need not be aligned).
inline Doubles2 LoadLanes(const double* values)
{
  Doubles2 v;
  std::memcpy(&v, values, sizeof v);
  return v;
}

/// Bit l of the result: lane l of a comparison's mask is true.
inline unsigned LaneBits(Mask2 mask)
{
#if defined(__SSE2__)
  return static_cast<unsigned>(_mm_movemask_pd(reinterpret_cast<__m128d>(mask)));
#else
  return static_cast<unsigned>((mask[0] & 1) | (mask[1] & 2));
#endif
}

/// Bit l of the result: lane l's sign bit is set (negative, or -0).
inline unsigned SignBits(Doubles2 v)
{
  Mask2 bits;
  std::memcpy(&bits, &v, sizeof v);
#if defined(__SSE2__)
  return static_cast<unsigned>(_mm_movemask_pd(reinterpret_cast<__m128d>(bits)));
#else
  return static_cast<unsigned>((bits[0] < 0) | ((bits[1] < 0) << 1));
#endif
}

/// |v| per lane (the sign bit cleared).
inline Doubles2 Magnitude(Doubles2 v)
{
  const Mask2 magnitude = { 0x7FFFFFFFFFFFFFFFLL, 0x7FFFFFFFFFFFFFFFLL };
  Mask2 bits;
  std::memcpy(&bits, &v, sizeof v);
  bits &= magnitude;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}
} // namespace mp

#endif
