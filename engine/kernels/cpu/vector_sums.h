// SPDX-License-Identifier: MIT
// The horizontal sums of a register that the vectorized kernels end their rows with, one fixed
// order each (a row's bits depend on it, so every kernel that promises the same bits calls these).
#pragma once
#include "kernels/cpu/cpu_features.h"

#ifdef SILK_KERNELS_X86
namespace silk {

// The eight lanes: high half onto low, then pairs, then the last two.
SILK_TARGET_AVX2 inline float Sum8(__m256 v) {
  __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  s = _mm_add_ps(s, _mm_movehl_ps(s, s));
  s = _mm_add_ss(s, _mm_movehdup_ps(s));
  return _mm_cvtss_f32(s);
}

// The sixteen lanes: the register's two 256-bit halves added, then Sum8.
SILK_TARGET_AVX512F inline float SumHalves(__m512 v) {
  const __m512d both = _mm512_castps_pd(v);
  return Sum8(
      _mm256_add_ps(_mm256_castpd_ps(_mm512_castpd512_pd256(both)), _mm256_castpd_ps(_mm512_extractf64x4_pd(both, 1))));
}

SILK_AVX512_CODE_BEGIN
// SumHalves of sixteen registers at once, lane j the sum of v[j], each by SumHalves' additions
// (the same pairs, so the same bits; a float sum's operands commute) in a quarter of the
// instructions: the pairs of every register are added side by side, halving the lanes each step.
SILK_TARGET_AVX512F inline __m512 SumHalvesOf16(const __m512 (&v)[16]) {
  __m512 w[8], z[4];
  for (int p = 0; p < 8; ++p)  // lanes 0-7: v[2p]'s high half onto its low half; 8-15: v[2p + 1]'s
    w[p] = _mm512_add_ps(_mm512_shuffle_f32x4(v[2 * p], v[2 * p + 1], _MM_SHUFFLE(1, 0, 1, 0)),
                         _mm512_shuffle_f32x4(v[2 * p], v[2 * p + 1], _MM_SHUFFLE(3, 2, 3, 2)));
  for (int p = 0; p < 4; ++p)  // quarter c: register 4p + c's four lanes of Sum8's first step
    z[p] = _mm512_add_ps(_mm512_shuffle_f32x4(w[2 * p], w[2 * p + 1], _MM_SHUFFLE(2, 0, 2, 0)),
                         _mm512_shuffle_f32x4(w[2 * p], w[2 * p + 1], _MM_SHUFFLE(3, 1, 3, 1)));
  __m512d u[2];
  for (int p = 0; p < 2; ++p) {  // quarter c: two lanes of register 8p + c, then of 8p + 4 + c
    const __m512d a = _mm512_castps_pd(z[2 * p]), b = _mm512_castps_pd(z[2 * p + 1]);
    u[p] = _mm512_castps_pd(
        _mm512_add_ps(_mm512_castpd_ps(_mm512_unpacklo_pd(a, b)), _mm512_castpd_ps(_mm512_unpackhi_pd(a, b))));
  }
  const __m512 lo = _mm512_castpd_ps(u[0]), hi = _mm512_castpd_ps(u[1]);
  // Lane 4c + e now holds register 4e + c's sum: transposed back.
  const __m512 sums = _mm512_add_ps(_mm512_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0)),
                                    _mm512_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1)));
  return _mm512_permutexvar_ps(_mm512_setr_epi32(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15), sums);
}
SILK_AVX512_CODE_END

}  // namespace silk
#endif
