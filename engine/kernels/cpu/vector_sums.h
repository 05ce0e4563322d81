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

}  // namespace silk
#endif
