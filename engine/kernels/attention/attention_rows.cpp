// SPDX-License-Identifier: MIT
// Scalar, AVX2 and AVX-512 row primitives for CachedAttention (float32, float16 and int8 + scale
// rows); the vectorized ones are compiled for their instruction sets with a target attribute
// (kernels/cpu/cpu_features.h) and used only when the CPU reports them.
#include "kernels/attention/attention_rows.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <type_traits>
#include <vector>

#include "kernels/cpu/cpu_features.h"
#include "kernels/cpu/float16.h"
#include "kernels/cpu/vector_sums.h"

namespace silk {

namespace {

inline float Widen(float x) { return x; }
inline float Widen(uint16_t h) { return HalfToFloat(h); }
inline float Widen(int8_t q) { return static_cast<float>(q); }

// A row of d values of E: elements to the next row, and the factor its values are multiplied by
// (int8: the float32 scale stored after the d values; 1 otherwise, an exact no-op).
template <typename E>
constexpr int64_t Stride(int64_t d) {
  return std::is_same<E, int8_t>::value ? d + 4 : d;
}
template <typename E>
inline float RowScale(const E* row, int64_t d) {
  if constexpr (!std::is_same<E, int8_t>::value) {
    (void)row, (void)d;
    return 1.0f;
  } else {
    float s;
    std::memcpy(&s, row + d, 4);
    return s;
  }
}

// x / scale rounded to nearest even and clamped to [-127, 127] (NaN -> -127: never UB).
inline int8_t QuantizeOne(float x, float scale) {
  float v = std::nearbyint(x / scale);
  v = v > -127.0f ? v : -127.0f;
  v = v < 127.0f ? v : 127.0f;
  return static_cast<int8_t>(v);
}

void StoreInt8Scalar(const float* src, int8_t* row, int64_t d) {
  float top = 0.0f;
  for (int64_t i = 0; i < d; ++i) top = std::max(top, std::fabs(src[i]));
  const float scale = top / 127.0f;
  for (int64_t i = 0; i < d; ++i) row[i] = scale > 0.0f ? QuantizeOne(src[i], scale) : 0;
  std::memcpy(row + d, &scale, 4);
}

template <typename E>
void StoreScalar(const float* src, void* row, int64_t d) {
  E* r = static_cast<E*>(row);
  if constexpr (std::is_same<E, int8_t>::value) {
    StoreInt8Scalar(src, r, d);
  } else {
    for (int64_t i = 0; i < d; ++i) {
      if constexpr (sizeof(E) == 4)
        r[i] = src[i];
      else
        r[i] = FloatToHalf(src[i]);
    }
  }
}

// The query of an int8-row dot product: rounded once to int16 (scale = max|q| / 32767, nearest
// even), so that each row's dot is exact in integers; factor = scale * the query's scale (NaN when
// the query is not finite, so its scores are NaN as the float path's would be). Built once per
// (position, head) pair, so head sizes up to kInline stay on the stack.
class Query16 {
 public:
  Query16(const float* q, int64_t d, float scale) {
    float top = 0.0f;
    bool finite = true;
    for (int64_t i = 0; i < d; ++i) {
      finite = finite && std::isfinite(q[i]);
      top = std::max(top, std::fabs(q[i]));
    }
    if (d > kInline) heap_.resize(static_cast<size_t>(d));
    int16_t* out = heap_.empty() ? inline_ : heap_.data();
    const float inverse = finite && top > 0.0f ? 32767.0f / top : 0.0f;
    for (int64_t i = 0; i < d; ++i) out[i] = static_cast<int16_t>(std::nearbyint(q[i] * inverse));
    factor_ = finite ? scale * (top / 32767.0f) : std::nanf("");
  }
  Query16(const Query16&) = delete;
  Query16& operator=(const Query16&) = delete;
  const int16_t* data() const { return heap_.empty() ? inline_ : heap_.data(); }
  float factor() const { return factor_; }

 private:
  static constexpr int64_t kInline = 512;
  int16_t inline_[kInline];
  std::vector<int16_t> heap_;
  float factor_ = 0.0f;
};

// out[j] = (sum of int16 q * int8 k, exact) * row scale * factor: the int8 rows' scores, the
// same value from every path.
void DotsInt8Scalar(const float* q, const void* rows, int64_t n, int64_t d, float scale, float* out) {
  const Query16 q16(q, d, scale);
  const int16_t* qi = q16.data();
  const int8_t* r = static_cast<const int8_t*>(rows);
  for (int64_t j = 0; j < n; ++j, r += Stride<int8_t>(d)) {
    int64_t acc = 0;
    for (int64_t i = 0; i < d; ++i) acc += int64_t{qi[i]} * r[i];
    out[j] = (static_cast<float>(acc) * RowScale(r, d)) * q16.factor();
  }
}

template <typename E>
void DotsScalar(const float* q, const void* rows, int64_t n, int64_t d, float scale, float* out) {
  if constexpr (std::is_same<E, int8_t>::value) {
    DotsInt8Scalar(q, rows, n, d, scale, out);
  } else {
    const E* r = static_cast<const E*>(rows);
    for (int64_t j = 0; j < n; ++j, r += d) {
      float acc = 0.0f;
      for (int64_t i = 0; i < d; ++i) acc += q[i] * Widen(r[i]);
      out[j] = scale * acc;
    }
  }
}

float ExpShiftedScalar(float* x, int64_t n, float top) {
  float sum = 0.0f;
  for (int64_t j = 0; j < n; ++j) sum += (x[j] = std::exp(x[j] - top));
  return sum;
}

template <typename E>
void WeightedSumScalar(const float* w, const void* rows, int64_t n, int64_t d, float factor, float* out) {
  const E* r = static_cast<const E*>(rows);
  for (int64_t j = 0; j < n; ++j, r += Stride<E>(d)) {
    const float wj = w[j] * RowScale(r, d);
    for (int64_t i = 0; i < d; ++i) out[i] += factor * wj * Widen(r[i]);
  }
}

#ifdef SILK_KERNELS_X86
#define SILK_AVX2 SILK_TARGET_AVX2

SILK_AVX2 inline __m256 Load8(const float* p) { return _mm256_loadu_ps(p); }
SILK_AVX2 inline __m256 Load8(const uint16_t* p) {
  return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}
SILK_AVX2 inline __m256 Load8(const int8_t* p) {
  return _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
}

// Eight int8 of x / scale (nearest even: the default MXCSR rounding), clamped as QuantizeOne.
SILK_AVX2 inline void Quantize8(const float* x, __m256 scale, int8_t* out) {
  __m256 v = _mm256_round_ps(_mm256_div_ps(_mm256_loadu_ps(x), scale), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  v = _mm256_min_ps(_mm256_max_ps(v, _mm256_set1_ps(-127.0f)), _mm256_set1_ps(127.0f));
  const __m256i i32 = _mm256_cvtps_epi32(v);
  const __m128i i16 = _mm_packs_epi32(_mm256_castsi256_si128(i32), _mm256_extracti128_si256(i32, 1));
  _mm_storel_epi64(reinterpret_cast<__m128i*>(out), _mm_packs_epi16(i16, i16));
}

SILK_AVX2 void StoreInt8Avx2(const float* src, int8_t* row, int64_t d) {
  const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  __m256 top = _mm256_setzero_ps();
  for (int64_t i = 0; i < d; i += 8) top = _mm256_max_ps(_mm256_and_ps(_mm256_loadu_ps(src + i), abs_mask), top);
  __m128 t = _mm_max_ps(_mm256_castps256_ps128(top), _mm256_extractf128_ps(top, 1));
  t = _mm_max_ps(t, _mm_movehl_ps(t, t));
  t = _mm_max_ss(t, _mm_movehdup_ps(t));
  const float scale = _mm_cvtss_f32(t) / 127.0f;
  if (scale > 0.0f) {
    for (int64_t i = 0; i < d; i += 8) Quantize8(src + i, _mm256_set1_ps(scale), row + i);
  } else {
    std::memset(row, 0, static_cast<size_t>(d));
  }
  std::memcpy(row + d, &scale, 4);
}

template <typename E>
SILK_AVX2 void StoreAvx2(const float* src, void* row, int64_t d) {
  if constexpr (std::is_same<E, int8_t>::value) {
    StoreInt8Avx2(src, static_cast<int8_t*>(row), d);
  } else if constexpr (sizeof(E) == 4) {
    std::memcpy(row, src, static_cast<size_t>(d) * sizeof(float));
  } else {
    uint16_t* r = static_cast<uint16_t*>(row);
    for (int64_t i = 0; i < d; i += 8)
      _mm_storeu_si128(reinterpret_cast<__m128i*>(r + i),
                       _mm256_cvtps_ph(_mm256_loadu_ps(src + i), _MM_FROUND_TO_NEAREST_INT));
  }
}

// Cache rows are read this far ahead with software prefetch: on a VM whose two cores each stream
// ~12 GB/s the hardware prefetcher alone left the int8 rows at ~16 GB/s (measured: 1-4 KB
// ahead gives 20 GB/s, benchmarks.md "Time to mesh").
constexpr int64_t kPrefetchBytes = 2048;

// The cache lines of `count` consecutive elements starting kPrefetchBytes past `at`.
template <typename E>
SILK_AVX2 inline void PrefetchAhead(const E* at, int64_t count) {
  const char* p = reinterpret_cast<const char*>(at) + kPrefetchBytes;
  for (int64_t b = 0; b < count * static_cast<int64_t>(sizeof(E)); b += 64) _mm_prefetch(p + b, _MM_HINT_T0);
}

template <typename E>
SILK_AVX2 inline float RowDot(const float* q, const E* r, int64_t d) {
  __m256 a = _mm256_setzero_ps();
  for (int64_t i = 0; i < d; i += 8) a = _mm256_fmadd_ps(_mm256_loadu_ps(q + i), Load8(r + i), a);
  return Sum8(a);
}

// float32 and float16 rows (int8 rows: DotsInt8Avx2 below).
// head_dim 64 (every registered architecture): the query held in registers, two rows per
// iteration with two accumulators each, so four independent chains hide the FMA latency.
template <typename E>
SILK_AVX2 void Dots64(const float* q, const E* r, int64_t n, float scale, float* out) {
  constexpr int64_t d = 64;
  __m256 qv[8];
  for (int k = 0; k < 8; ++k) qv[k] = _mm256_loadu_ps(q + 8 * k);
  int64_t j = 0;
  for (; j + 1 < n; j += 2, r += 2 * d) {
    PrefetchAhead(r, 2 * d);
    const E* r1 = r + d;
    __m256 a0 = _mm256_mul_ps(qv[0], Load8(r)), a1 = _mm256_mul_ps(qv[1], Load8(r + 8));
    __m256 b0 = _mm256_mul_ps(qv[0], Load8(r1)), b1 = _mm256_mul_ps(qv[1], Load8(r1 + 8));
    for (int k = 2; k < 8; k += 2) {
      a0 = _mm256_fmadd_ps(qv[k], Load8(r + 8 * k), a0);
      a1 = _mm256_fmadd_ps(qv[k + 1], Load8(r + 8 * k + 8), a1);
      b0 = _mm256_fmadd_ps(qv[k], Load8(r1 + 8 * k), b0);
      b1 = _mm256_fmadd_ps(qv[k + 1], Load8(r1 + 8 * k + 8), b1);
    }
    out[j] = scale * Sum8(_mm256_add_ps(a0, a1));
    out[j + 1] = scale * Sum8(_mm256_add_ps(b0, b1));
  }
  if (j < n) out[j] = scale * RowDot(q, r, d);
}

// One int8 row against the int16 query: 16 products per pmaddwd, eight int32 partial sums.
SILK_AVX2 inline __m256i RowDot16(const int8_t* r, const int16_t* q, int64_t d) {
  __m256i s = _mm256_setzero_si256();
  for (int64_t i = 0; i < d; i += 16) {
    const __m256i k = _mm256_cvtepi8_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(r + i)));
    s = _mm256_add_epi32(s, _mm256_madd_epi16(k, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q + i))));
  }
  return s;
}

// The scores of four consecutive int8 rows from their eight-lane int32 sums a..d (the sums are
// exact, so how the lanes are added does not matter): (sum * row scale) * factor.
SILK_AVX2 inline void FourScores(__m256i a, __m256i b, __m256i c, __m256i e, const int8_t* r, int64_t stride, int64_t d,
                                 float factor, float* out) {
  const __m256i h = _mm256_hadd_epi32(_mm256_hadd_epi32(a, b), _mm256_hadd_epi32(c, e));
  const __m128i sums = _mm_add_epi32(_mm256_castsi256_si128(h), _mm256_extracti128_si256(h, 1));
  const __m128 scales =
      _mm_setr_ps(RowScale(r, d), RowScale(r + stride, d), RowScale(r + 2 * stride, d), RowScale(r + 3 * stride, d));
  _mm_storeu_ps(out, _mm_mul_ps(_mm_mul_ps(_mm_cvtepi32_ps(sums), scales), _mm_set1_ps(factor)));
}

// DotsInt8Scalar's values for an int16 query already built, four rows per step; the int32 sums
// cannot overflow for d <= 512 (d * 32767 * 127 < 2^31), the caller's condition.
SILK_AVX2 void DotsInt8Avx2(const Query16& q16, const int8_t* r, int64_t n, int64_t d, float* out) {
  const int64_t stride = Stride<int8_t>(d);
  const int16_t* qi = q16.data();
  int64_t j = 0;
  for (; j + 3 < n; j += 4, r += 4 * stride) {
    PrefetchAhead(r, 4 * stride);
    FourScores(RowDot16(r, qi, d), RowDot16(r + stride, qi, d), RowDot16(r + 2 * stride, qi, d),
               RowDot16(r + 3 * stride, qi, d), r, stride, d, q16.factor(), out + j);
  }
  for (; j < n; ++j, r += stride) {
    const __m256i s = RowDot16(r, qi, d);
    __m128i t = _mm_add_epi32(_mm256_castsi256_si128(s), _mm256_extracti128_si256(s, 1));
    t = _mm_add_epi32(t, _mm_shuffle_epi32(t, 0x4e));
    t = _mm_add_epi32(t, _mm_shuffle_epi32(t, 0xb1));
    out[j] = (static_cast<float>(_mm_cvtsi128_si32(t)) * RowScale(r, d)) * q16.factor();
  }
}

template <typename E>
SILK_AVX2 void DotsAvx2(const float* q, const void* rows, int64_t n, int64_t d, float scale, float* out) {
  const E* r = static_cast<const E*>(rows);
  if constexpr (std::is_same<E, int8_t>::value) {
    if (d % 16 == 0 && d <= 512)
      DotsInt8Avx2(Query16(q, d, scale), r, n, d, out);
    else
      DotsInt8Scalar(q, rows, n, d, scale, out);
  } else if (d == 64) {
    Dots64(q, r, n, scale, out);
  } else {
    for (int64_t j = 0; j < n; ++j, r += d) {
      PrefetchAhead(r, d);
      out[j] = scale * RowDot(q, r, d);
    }
  }
}

// exp(x) for x in [-87, 0]: x = n ln2 + r, |r| <= ln2 / 2, e^r by its degree-6 Taylor polynomial
// (relative error < 2e-7), 2^n put into the exponent bits.
SILK_AVX2 inline __m256 ExpNonPositive(__m256 x) {
  x = _mm256_max_ps(x, _mm256_set1_ps(-87.0f));
  const __m256 n = _mm256_round_ps(_mm256_mul_ps(x, _mm256_set1_ps(1.44269504088896341f)),
                                   _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
  __m256 r = _mm256_fnmadd_ps(n, _mm256_set1_ps(0.693145751953125f), x);
  r = _mm256_fnmadd_ps(n, _mm256_set1_ps(1.428606765330187e-06f), r);
  __m256 p = _mm256_set1_ps(1.0f / 720);
  for (float c : {1.0f / 120, 1.0f / 24, 1.0f / 6, 0.5f, 1.0f, 1.0f}) p = _mm256_fmadd_ps(p, r, _mm256_set1_ps(c));
  const __m256i e = _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvtps_epi32(n), _mm256_set1_epi32(127)), 23);
  return _mm256_mul_ps(p, _mm256_castsi256_ps(e));
}

SILK_AVX2 float ExpShiftedAvx2(float* x, int64_t n, float top) {
  const __m256 t = _mm256_set1_ps(top);
  __m256 sum = _mm256_setzero_ps();
  int64_t j = 0;
  for (; j + 8 <= n; j += 8) {
    const __m256 e = ExpNonPositive(_mm256_sub_ps(_mm256_loadu_ps(x + j), t));
    _mm256_storeu_ps(x + j, e);
    sum = _mm256_add_ps(sum, e);
  }
  float total = Sum8(sum);
  for (; j < n; ++j) total += (x[j] = std::exp(x[j] - top));
  return total;
}

// Up to 64 columns [i0, i0 + 8 * kLanes) of out accumulated in registers over every row (kLanes
// lanes of eight; a compile-time count, so the accumulators stay in registers).
template <typename E, int kLanes>
SILK_AVX2 void WeightedSumLanes(const float* w, const E* rows, int64_t n, int64_t d, int64_t i0, float factor,
                                float* out) {
  __m256 acc[kLanes];  // (every loop over it is unrolled: GCC -O2 otherwise kept it in memory, a
                       // load and a store around each fma)
#pragma GCC unroll 8
  for (int k = 0; k < kLanes; ++k) acc[k] = _mm256_setzero_ps();
  const E* row = rows;
  for (int64_t j = 0; j < n; ++j, row += Stride<E>(d)) {
    PrefetchAhead(row, Stride<E>(d));
    const __m256 wj = _mm256_set1_ps(w[j] * RowScale(row, d));
#pragma GCC unroll 8
    for (int k = 0; k < kLanes; ++k) acc[k] = _mm256_fmadd_ps(wj, Load8(row + i0 + 8 * k), acc[k]);
  }
  const __m256 f = _mm256_set1_ps(factor);
#pragma GCC unroll 8
  for (int k = 0; k < kLanes; ++k) {
    float* o = out + i0 + 8 * k;
    _mm256_storeu_ps(o, _mm256_fmadd_ps(f, acc[k], _mm256_loadu_ps(o)));
  }
}

// Columns in blocks of 64 (head_dim 64: one pass over the rows), a last narrower block by its
// own lane count.
template <typename E>
SILK_AVX2 void WeightedSumAvx2(const float* w, const void* rows, int64_t n, int64_t d, float factor, float* out) {
  using Fn = void (*)(const float*, const E*, int64_t, int64_t, int64_t, float, float*);
  static constexpr Fn kByLanes[8] = {WeightedSumLanes<E, 1>, WeightedSumLanes<E, 2>, WeightedSumLanes<E, 3>,
                                     WeightedSumLanes<E, 4>, WeightedSumLanes<E, 5>, WeightedSumLanes<E, 6>,
                                     WeightedSumLanes<E, 7>, WeightedSumLanes<E, 8>};
  const E* r = static_cast<const E*>(rows);
  for (int64_t i0 = 0; i0 < d; i0 += 64) kByLanes[std::min<int64_t>(d - i0, 64) / 8 - 1](w, r, n, d, i0, factor, out);
}

// The 512-bit rows: the same values as the AVX2 rows above, bit for bit, in half the
// instructions (measured in the release decoder at 8 rows, depth 2,000: the int8 cache passes
// 51-53 ms a call against 57-59 with the 256-bit rows; one row no slower). Each
// lane of a 512-bit weighted sum does the AVX2 lane's operations in its order; a float dot product
// keeps the AVX2 one's two accumulators as the two halves of one register; an int8 dot product is
// exact in integers, so its order is free.
#define SILK_AVX512 SILK_TARGET_AVX512_VNNI
SILK_AVX512_CODE_BEGIN

SILK_AVX512 inline __m512 Load16(const float* p) { return _mm512_loadu_ps(p); }
SILK_AVX512 inline __m512 Load16(const uint16_t* p) {
  return _mm512_cvtph_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
}
SILK_AVX512 inline __m512 Load16(const int8_t* p) {
  return _mm512_cvtepi32_ps(_mm512_cvtepi8_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))));
}

// Dots64 with a0 in the low half and a1 in the high half of one register: elements 16k..16k + 15
// are Dots64's steps 2k (low) and 2k + 1 (high), and SumHalves is Dots64's Sum8(a0 + a1).
template <typename E>
SILK_AVX512 void Dots64Avx512(const float* q, const E* r, int64_t n, float scale, float* out) {
  constexpr int64_t d = 64;
  __m512 qv[4];
  for (int k = 0; k < 4; ++k) qv[k] = _mm512_loadu_ps(q + 16 * k);
  int64_t j = 0;
  for (; j + 1 < n; j += 2, r += 2 * d) {
    PrefetchAhead(r, 2 * d);
    const E* r1 = r + d;
    __m512 a = _mm512_mul_ps(qv[0], Load16(r)), b = _mm512_mul_ps(qv[0], Load16(r1));
#pragma GCC unroll 4
    for (int k = 1; k < 4; ++k) {
      a = _mm512_fmadd_ps(qv[k], Load16(r + 16 * k), a);
      b = _mm512_fmadd_ps(qv[k], Load16(r1 + 16 * k), b);
    }
    out[j] = scale * SumHalves(a);
    out[j + 1] = scale * SumHalves(b);
  }
  if (j < n) out[j] = scale * RowDot(q, r, d);
}

// One int8 row against the int16 query, 32 products per vpdpwssd: sixteen int32 partial sums.
SILK_AVX512 inline __m512i RowDot16Avx512(const int8_t* r, const int16_t* q, int64_t d) {
  __m512i s = _mm512_setzero_si512();
  for (int64_t i = 0; i < d; i += 32) {
    const __m512i k = _mm512_cvtepi8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(r + i)));
    s = _mm512_dpwssd_epi32(s, k, _mm512_loadu_si512(q + i));
  }
  return s;
}

// A row's sixteen partial sums folded to eight (the int32 sum is exact in any order).
SILK_AVX512 inline __m256i Fold(__m512i s) {
  return _mm256_add_epi32(_mm512_castsi512_si256(s), _mm512_extracti64x4_epi64(s, 1));
}

// DotsInt8Avx2's values (the same exact int32 sums, the same float products), for d a multiple
// of 32 up to 512; the last n % 4 rows by DotsInt8Avx2 with the same query.
SILK_AVX512 void DotsInt8Avx512(const float* q, const int8_t* r, int64_t n, int64_t d, float scale, float* out) {
  const Query16 q16(q, d, scale);
  const int64_t stride = Stride<int8_t>(d);
  const int16_t* qi = q16.data();
  int64_t j = 0;
  for (; j + 3 < n; j += 4, r += 4 * stride) {
    PrefetchAhead(r, 4 * stride);
    FourScores(Fold(RowDot16Avx512(r, qi, d)), Fold(RowDot16Avx512(r + stride, qi, d)),
               Fold(RowDot16Avx512(r + 2 * stride, qi, d)), Fold(RowDot16Avx512(r + 3 * stride, qi, d)), r, stride, d,
               q16.factor(), out + j);
  }
  if (j < n) DotsInt8Avx2(q16, r, n - j, d, out + j);
}

template <typename E>
SILK_AVX512 void DotsAvx512(const float* q, const void* rows, int64_t n, int64_t d, float scale, float* out) {
  const E* r = static_cast<const E*>(rows);
  if constexpr (std::is_same<E, int8_t>::value) {
    if (d % 32 == 0 && d <= 512) return DotsInt8Avx512(q, r, n, d, scale, out);
  } else {
    if (d == 64) return Dots64Avx512(q, r, n, scale, out);
  }
  DotsAvx2<E>(q, rows, n, d, scale, out);
}

// WeightedSumLanes for 16 columns per register: each column's operations as there, in its order.
template <typename E, int kLanes>
SILK_AVX512 void WeightedSumLanes16(const float* w, const E* rows, int64_t n, int64_t d, int64_t i0, float factor,
                                    float* out) {
  __m512 acc[kLanes];  // (unrolled loops: kept in registers)
#pragma GCC unroll 4
  for (int k = 0; k < kLanes; ++k) acc[k] = _mm512_setzero_ps();
  const E* row = rows;
  for (int64_t j = 0; j < n; ++j, row += Stride<E>(d)) {
    PrefetchAhead(row, Stride<E>(d));
    const __m512 wj = _mm512_set1_ps(w[j] * RowScale(row, d));
#pragma GCC unroll 4
    for (int k = 0; k < kLanes; ++k) acc[k] = _mm512_fmadd_ps(wj, Load16(row + i0 + 16 * k), acc[k]);
  }
  const __m512 f = _mm512_set1_ps(factor);
#pragma GCC unroll 4
  for (int k = 0; k < kLanes; ++k) {
    float* o = out + i0 + 16 * k;
    _mm512_storeu_ps(o, _mm512_fmadd_ps(f, acc[k], _mm512_loadu_ps(o)));
  }
}

// Columns in blocks of 64 (head_dim 64: one pass over the rows), for d a multiple of 16; others
// by the AVX2 rows.
template <typename E>
SILK_AVX512 void WeightedSumAvx512(const float* w, const void* rows, int64_t n, int64_t d, float factor, float* out) {
  if (d % 16 != 0) return WeightedSumAvx2<E>(w, rows, n, d, factor, out);
  using Fn = void (*)(const float*, const E*, int64_t, int64_t, int64_t, float, float*);
  static constexpr Fn kByLanes[4] = {WeightedSumLanes16<E, 1>, WeightedSumLanes16<E, 2>, WeightedSumLanes16<E, 3>,
                                     WeightedSumLanes16<E, 4>};
  const E* r = static_cast<const E*>(rows);
  for (int64_t i0 = 0; i0 < d; i0 += 64) kByLanes[std::min<int64_t>(d - i0, 64) / 16 - 1](w, r, n, d, i0, factor, out);
}

// The many-query rows (head_dim 64; float32 or float16 rows): blocks of 16 rows widened once to
// float32 on the stack, then each query's products over the block. A query's operations on a row,
// and their order, are Dots64Avx512's and WeightedSumLanes16's, so it gets their bits; only the
// widening (exact) is shared. Measured in the release decoder, 8 rows sharing one mesh's cross K/V:
// see docs/benchmarks.md, "Cross attention: one widening for the rows of a mesh".
constexpr int64_t kManyBlock = 16;

// `count` (<= kManyBlock) rows as float32: float32 rows in place, float16 ones into `buffer`.
template <typename E>
SILK_AVX512 inline const float* WidenRows(const E* rows, int64_t count, float* buffer) {
  PrefetchAhead(rows, kManyBlock * 64);
  if constexpr (sizeof(E) == 4) {
    (void)buffer, (void)count;
    return rows;
  } else {
    for (int64_t i = 0; i < count * 64; i += 16) _mm512_store_ps(buffer + i, Load16(rows + i));
    return buffer;
  }
}

// Sixteen rows' dots with one query, each as Dots64Avx512's pair loop computes a row.
SILK_AVX512 inline __m512 SixteenDots(const float* q, const float* k) {
  const __m512 q0 = _mm512_loadu_ps(q), q1 = _mm512_loadu_ps(q + 16), q2 = _mm512_loadu_ps(q + 32),
               q3 = _mm512_loadu_ps(q + 48);
  __m512 acc[kManyBlock];
#pragma GCC unroll 16
  for (int j = 0; j < kManyBlock; ++j) {
    const float* row = k + 64 * j;
    __m512 a = _mm512_mul_ps(q0, _mm512_loadu_ps(row));
    a = _mm512_fmadd_ps(q1, _mm512_loadu_ps(row + 16), a);
    a = _mm512_fmadd_ps(q2, _mm512_loadu_ps(row + 32), a);
    acc[j] = _mm512_fmadd_ps(q3, _mm512_loadu_ps(row + 48), a);
  }
  return SumHalvesOf16(acc);
}

template <typename E>
SILK_AVX512 void DotsMany64Avx512(const float* const* q, int64_t queries, const void* rows, int64_t n, int64_t d,
                                  float scale, float* const* out) {
  (void)d;  // 64
  const E* r = static_cast<const E*>(rows);
  alignas(64) float buffer[kManyBlock * 64];
  const __m512 s = _mm512_set1_ps(scale);
  int64_t j0 = 0;
  for (; j0 + kManyBlock <= n; j0 += kManyBlock) {
    const float* k = WidenRows(r + 64 * j0, kManyBlock, buffer);
    for (int64_t i = 0; i < queries; ++i) _mm512_storeu_ps(out[i] + j0, _mm512_mul_ps(s, SixteenDots(q[i], k)));
  }
  if (j0 < n)  // the last rows as Dots64Avx512 takes them (j0 is even: the same pairs)
    for (int64_t i = 0; i < queries; ++i) Dots64Avx512(q[i], r + 64 * j0, n - j0, scale, out[i] + j0);
}

// Up to kManyQueries queries' four accumulators each, kept on the stack between blocks.
constexpr int64_t kManyQueries = 8;

// acc[16k..16k + 15] += w[j] * row j's columns 16k.. for `count` rows of float32 `k` (stride 64).
SILK_AVX512 inline void AccumulateRows(const float* w, const float* k, int64_t count, float* acc) {
  __m512 a0 = _mm512_load_ps(acc), a1 = _mm512_load_ps(acc + 16), a2 = _mm512_load_ps(acc + 32),
         a3 = _mm512_load_ps(acc + 48);
  for (int64_t j = 0; j < count; ++j, k += 64) {
    const __m512 wj = _mm512_set1_ps(w[j] * 1.0f);  // WeightedSumLanes16's w[j] * RowScale (1 here)
    a0 = _mm512_fmadd_ps(wj, _mm512_loadu_ps(k), a0);
    a1 = _mm512_fmadd_ps(wj, _mm512_loadu_ps(k + 16), a1);
    a2 = _mm512_fmadd_ps(wj, _mm512_loadu_ps(k + 32), a2);
    a3 = _mm512_fmadd_ps(wj, _mm512_loadu_ps(k + 48), a3);
  }
  _mm512_store_ps(acc, a0), _mm512_store_ps(acc + 16, a1), _mm512_store_ps(acc + 32, a2), _mm512_store_ps(acc + 48, a3);
}

template <typename E>
SILK_AVX512 void WeightedSumMany64Avx512(const float* const* w, int64_t queries, const void* rows, int64_t n, int64_t d,
                                         const float* factor, float* const* out) {
  const E* r = static_cast<const E*>(rows);
  alignas(64) float buffer[kManyBlock * 64], acc[kManyQueries * 64];
  for (int64_t first = 0; first < queries; first += kManyQueries) {
    const int64_t count = std::min(kManyQueries, queries - first);
    std::fill(acc, acc + count * 64, 0.0f);
    for (int64_t j0 = 0; j0 < n; j0 += kManyBlock) {
      const int64_t block = std::min(kManyBlock, n - j0);
      const float* k = WidenRows(r + 64 * j0, block, buffer);
      for (int64_t i = 0; i < count; ++i) AccumulateRows(w[first + i] + j0, k, block, acc + 64 * i);
    }
    for (int64_t i = 0; i < count; ++i) {
      const __m512 f = _mm512_set1_ps(factor[first + i]);
      float* o = out[first + i];
      for (int64_t c = 0; c < d; c += 16)
        _mm512_storeu_ps(o + c, _mm512_fmadd_ps(f, _mm512_load_ps(acc + 64 * i + c), _mm512_loadu_ps(o + c)));
    }
  }
}
SILK_AVX512_CODE_END
#endif

template <typename E>
AttentionRows RowsOf(int64_t head_dim, RowKernels kernels) {
#ifdef SILK_KERNELS_X86
  if (kernels == RowKernels::kBest && head_dim % 8 == 0 && CpuHasAvx512Vnni()) {
    AttentionRows rows{true, StoreAvx2<E>, DotsAvx512<E>, ExpShiftedAvx2, WeightedSumAvx512<E>};
    if constexpr (!std::is_same<E, int8_t>::value) {
      if (head_dim == 64) rows.dots_many = DotsMany64Avx512<E>, rows.weighted_sum_many = WeightedSumMany64Avx512<E>;
    }
    return rows;
  }
  if (kernels != RowKernels::kScalar && head_dim % 8 == 0 && CpuHasAvx2())
    return AttentionRows{true, StoreAvx2<E>, DotsAvx2<E>, ExpShiftedAvx2, WeightedSumAvx2<E>};
#endif
  (void)head_dim;
  (void)kernels;
  return AttentionRows{false, StoreScalar<E>, DotsScalar<E>, ExpShiftedScalar, WeightedSumScalar<E>};
}

}  // namespace

void AttentionRows::DotsOfMany(const float* const* q, int64_t queries, const void* rows, int64_t n, int64_t d,
                               float scale, float* const* out) const {
  if (dots_many) return dots_many(q, queries, rows, n, d, scale, out);
  for (int64_t i = 0; i < queries; ++i) dots(q[i], rows, n, d, scale, out[i]);
}

void AttentionRows::WeightedSumsOfMany(const float* const* w, int64_t queries, const void* rows, int64_t n, int64_t d,
                                       const float* factor, float* const* out) const {
  if (weighted_sum_many) return weighted_sum_many(w, queries, rows, n, d, factor, out);
  for (int64_t i = 0; i < queries; ++i) weighted_sum(w[i], rows, n, d, factor[i], out[i]);
}

AttentionRows AttentionRowsFor(CacheElement element, int64_t head_dim, RowKernels kernels) {
  switch (element) {
    case CacheElement::kFloat16:
      return RowsOf<uint16_t>(head_dim, kernels);
    case CacheElement::kInt8:
      return RowsOf<int8_t>(head_dim, kernels);
    default:
      return RowsOf<float>(head_dim, kernels);
  }
}

}  // namespace silk
