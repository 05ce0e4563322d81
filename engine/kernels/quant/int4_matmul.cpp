// SPDX-License-Identifier: MIT
// Int4MatMul: each activation row is quantized once to int8 groups of 32 (scale max|a| / 127),
// then every weight row is one pass of integer dot products over its packed nibbles, scaled per
// group, with the weight stream prefetched ahead; rows are spread over the caller's pool.
#include "kernels/quant/int4_matmul.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "kernels/cpu/cpu_features.h"

namespace silk {

namespace {

constexpr int64_t kGroup = kInt4ActivationGroup;
constexpr int64_t kRowsPerTask = 256;  // weight rows per unit of parallel work (measured: 256-512 best)

// One activation row in int8 groups, laid out for the nibble order of the weights: the even
// elements of each group (which meet low nibbles) apart from the odd ones (high nibbles). A view
// into QuantizedRows' storage.
struct QuantizedRow {
  int8_t* even;       // [groups * 16]
  int8_t* odd;        // [groups * 16]
  float* scale;       // [groups]: a ~= q * scale
  float* lane_scale;  // [groups * 4]: the scale repeated per int32 lane of a group
  int32_t* offset;    // [groups * 4]: lane 0 = -8 * sum(q) (the weights' zero point), others 0
};

// The activation rows of one call, each kind of value in one allocation (the generation loop
// makes thousands of calls with one row each).
class QuantizedRows {
 public:
  QuantizedRows(int64_t m, int64_t k)
      : groups_(k / kGroup), bytes_(Size(m, 32)), floats_(Size(m, 5)), offsets_(Size(m, 4)) {  // offsets: 0
    rows_.reserve(static_cast<size_t>(m));
    for (int64_t r = 0; r < m; ++r) {
      int8_t* b = bytes_.data() + r * groups_ * 32;
      float* f = floats_.data() + r * groups_ * 5;
      rows_.push_back({b, b + groups_ * 16, f, f + groups_, offsets_.data() + r * groups_ * 4});
    }
  }
  const QuantizedRow& operator[](int64_t r) const { return rows_[static_cast<size_t>(r)]; }
  QuantizedRow* row(int64_t r) { return &rows_[static_cast<size_t>(r)]; }

 private:
  size_t Size(int64_t m, int64_t per_group) const { return static_cast<size_t>(m * groups_ * per_group); }
  int64_t groups_;
  std::vector<int8_t> bytes_;     // per row: even, odd
  std::vector<float> floats_;     // per row: scale, lane_scale
  std::vector<int32_t> offsets_;  // per row: offset
  std::vector<QuantizedRow> rows_;
};

// One group of kGroup activations as int8 values in int32 (nearest even of x * 127 / max|x|,
// clamped to [-127, 127], NaN -> 0); returns the group's scale max|x| / 127 (NaN ignored by max).
using GroupValuesFn = float (*)(const float* x, int32_t* values);

float GroupValuesScalar(const float* x, int32_t* values) {
  float top = 0.0f;
  for (int64_t i = 0; i < kGroup; ++i) top = std::max(top, std::fabs(x[i]));  // NaN: ignored by max
  const float inverse = top > 0.0f && std::isfinite(top) ? 127.0f / top : 0.0f;
  for (int64_t i = 0; i < kGroup; ++i) {
    const float r = std::nearbyint(x[i] * inverse);
    values[i] = r >= 127.0f ? 127 : r <= -127.0f ? -127 : r == r ? static_cast<int>(r) : 0;
  }
  return top / 127.0f;
}

void QuantizeRow(const float* a, int64_t k, GroupValuesFn group_values, QuantizedRow* q) {
  const int64_t groups = k / kGroup;
  for (int64_t g = 0; g < groups; ++g) {
    alignas(32) int32_t values[kGroup];
    const float scale = group_values(a + g * kGroup, values);
    int32_t sum = 0;
    for (int64_t i = 0; i < kGroup; ++i) {
      const int8_t v = static_cast<int8_t>(values[i]);
      int8_t* half = i % 2 ? q->odd : q->even;  // (as an lvalue, GCC 12's -O0 UBSan build computed a wild address)
      half[g * 16 + i / 2] = v;
      sum += v;
    }
    q->scale[g] = scale;
    for (int j = 0; j < 4; ++j) q->lane_scale[g * 4 + j] = scale;
    q->offset[g * 4] = -8 * sum;
  }
}

// Scale of weight row `row`'s block holding group g.
inline float WeightScale(const float* scales, int64_t blocks, int64_t row, int64_t g, int64_t block) {
  return scales[row * blocks + g * kGroup / block];
}

// Group g of weight row r against the activation row: the integer dot product (zero point
// included) times both scales.
inline float GroupScalar(const Int4MatMulShape& s, const QuantizedRow& q, const uint8_t* w, const float* scales,
                         int64_t r, int64_t g) {
  int32_t dot = q.offset[g * 4];
  for (int64_t i = 0; i < 16; ++i) {
    const uint8_t byte = w[g * 16 + i];
    dot += (byte & 0x0f) * q.even[g * 16 + i] + (byte >> 4) * q.odd[g * 16 + i];
  }
  return static_cast<float>(dot) * (WeightScale(scales, s.k / s.block, r, g, s.block) * q.scale[g]);
}

void RowsScalar(const Int4MatMulShape& s, const QuantizedRow& q, const uint8_t* packed, const float* scales, int64_t r0,
                int64_t r1, float* out) {
  const int64_t groups = s.k / kGroup;
  for (int64_t r = r0; r < r1; ++r) {
    const uint8_t* w = packed + r * (s.k / 2);
    float acc = 0.0f;
    for (int64_t g = 0; g < groups; ++g) acc += GroupScalar(s, q, w, scales, r, g);
    out[r] = acc;
  }
}

// The activation rows of a call two by two, interleaved per step (32 bytes of row 2j, then 32
// of row 2j + 1; likewise the offsets and lane scales), so one 512-bit load, 64-byte aligned,
// feeds both halves. An odd last row is paired with itself.
class PairedRows {
 public:
  PairedRows(const QuantizedRows& rows, int64_t m, int64_t k)
      : steps_(k / (2 * kGroup)), pairs_((m + 1) / 2), bytes_(Size(128) + 64), words_(Size(32) + 16) {
    bytes0_ = bytes_.data() + (64 - reinterpret_cast<uintptr_t>(bytes_.data()) % 64) % 64;
    words0_ = words_.data() + (64 - reinterpret_cast<uintptr_t>(words_.data()) % 64) % 64 / 4;
    for (int64_t j = 0; j < pairs_; ++j)
      for (int h = 0; h < 2; ++h) {
        const QuantizedRow& q = rows[std::min(2 * j + h, m - 1)];
        for (int64_t p = 0; p < steps_; ++p) {
          int8_t* b = Bytes(j, p) + 32 * h;
          std::memcpy(b, q.even + p * 32, 32);
          std::memcpy(b + 64, q.odd + p * 32, 32);
          int32_t* w = Words(j, p) + 8 * h;
          std::memcpy(w, q.offset + p * 8, 32);
          std::memcpy(w + 16, q.lane_scale + p * 8, 32);  // floats, stored as their bits
        }
      }
  }
  // Step p of pair j: even[64], odd[64]; and offsets[16], lane scales[16].
  const int8_t* Bytes(int64_t j, int64_t p) const { return bytes0_ + (j * steps_ + p) * 128; }
  const int32_t* Words(int64_t j, int64_t p) const { return words0_ + (j * steps_ + p) * 32; }
  int64_t pairs() const { return pairs_; }

 private:
  int8_t* Bytes(int64_t j, int64_t p) { return bytes0_ + (j * steps_ + p) * 128; }
  int32_t* Words(int64_t j, int64_t p) { return words0_ + (j * steps_ + p) * 32; }
  size_t Size(int64_t per_step) const { return static_cast<size_t>(pairs_ * steps_ * per_step); }
  int64_t steps_, pairs_;
  std::vector<int8_t> bytes_;  // 64 bytes over, for the alignment
  std::vector<int32_t> words_;
  int8_t* bytes0_;
  int32_t* words0_;
};

#ifdef SILK_KERNELS_X86
#define SILK_AVX2 SILK_TARGET_AVX2

constexpr int64_t kPrefetchBytes = 4096;  // ahead in the weight stream (measured: 2-4 KB best here)

// GroupValuesScalar's values, eight lanes at a time (the same products, rounding and clamps; max
// is exact, so its order does not matter, and MAXPS keeps the running maximum where x is NaN).
SILK_AVX2 float GroupValuesAvx2(const float* x, int32_t* values) {
  const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  __m256 v[4], top = _mm256_setzero_ps();
  for (int i = 0; i < 4; ++i) {
    v[i] = _mm256_loadu_ps(x + 8 * i);
    top = _mm256_max_ps(_mm256_and_ps(v[i], abs_mask), top);
  }
  __m128 t = _mm_max_ps(_mm256_castps256_ps128(top), _mm256_extractf128_ps(top, 1));
  t = _mm_max_ps(t, _mm_movehl_ps(t, t));
  const float peak = _mm_cvtss_f32(_mm_max_ss(t, _mm_movehdup_ps(t)));
  const __m256 inverse = _mm256_set1_ps(peak > 0.0f && std::isfinite(peak) ? 127.0f / peak : 0.0f);
  for (int i = 0; i < 4; ++i) {
    __m256 r = _mm256_round_ps(_mm256_mul_ps(v[i], inverse), _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    r = _mm256_and_ps(r, _mm256_cmp_ps(r, r, _CMP_ORD_Q));  // NaN -> 0
    r = _mm256_min_ps(_mm256_max_ps(r, _mm256_set1_ps(-127.0f)), _mm256_set1_ps(127.0f));
    _mm256_store_si256(reinterpret_cast<__m256i*>(values + 8 * i), _mm256_cvtps_epi32(r));
  }
  return peak / 127.0f;
}

// Two groups per step: 32 packed bytes against 32 even and 32 odd activations; maddubs + madd
// give one int32 per 4 bytes (lanes 0-3 group 2p, 4-7 group 2p + 1), scaled per lane. An odd
// last group (K = 32 modulo 64) is added in plain C++. The step's pieces below are shared by the
// one-row and the many-row kernels, so both do the same operations in the same order.

// Step p of a weight row: its low and high nibbles.
SILK_AVX2 inline void StepNibbles(const uint8_t* w, int64_t p, __m256i* lo, __m256i* hi) {
  _mm_prefetch(reinterpret_cast<const char*>(w + p * 32 + kPrefetchBytes), _MM_HINT_T0);
  const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(w + p * 32));
  const __m256i low4 = _mm256_set1_epi8(0x0f);
  *lo = _mm256_and_si256(x, low4), *hi = _mm256_and_si256(_mm256_srli_epi16(x, 4), low4);
}

// Step p's weight scale per lane (ws: the weight row's scales).
template <bool kScalePerGroup>
SILK_AVX2 inline __m256 StepScale(const float* ws, int64_t p, int64_t groups_per_block) {
  if constexpr (kScalePerGroup) {
    double two;  // the two groups' weight scales
    std::memcpy(&two, ws + 2 * p, 8);
    const __m256i pick = _mm256_set_epi32(1, 1, 1, 1, 0, 0, 0, 0);
    return _mm256_permutevar8x32_ps(_mm256_castps128_ps256(_mm_castpd_ps(_mm_set_sd(two))), pick);
  } else {
    (void)groups_per_block;
    return _mm256_set1_ps(ws[2 * p / groups_per_block]);
  }
}

// acc + step p of one activation row: the int32 dots (zero point included) times both scales.
SILK_AVX2 inline __m256 StepAccumulate(__m256i lo, __m256i hi, __m256 wscale, const QuantizedRow& q, int64_t p,
                                       __m256 acc) {
  const __m256i e = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q.even + p * 32));
  const __m256i o = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q.odd + p * 32));
  const __m256i pairs16 = _mm256_add_epi16(_mm256_maddubs_epi16(lo, e), _mm256_maddubs_epi16(hi, o));
  const __m256i dot = _mm256_add_epi32(_mm256_madd_epi16(pairs16, _mm256_set1_epi16(1)),
                                       _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q.offset + p * 8)));
  const __m256 lane = _mm256_mul_ps(wscale, _mm256_loadu_ps(q.lane_scale + p * 8));
  return _mm256_fmadd_ps(_mm256_cvtepi32_ps(dot), lane, acc);
}

// The row's output: the eight lanes summed, plus an odd last group.
SILK_AVX2 inline float RowSum(__m256 acc, const Int4MatMulShape& s, const QuantizedRow& q, const uint8_t* w,
                              const float* scales, int64_t r) {
  __m128 h = _mm_add_ps(_mm256_castps256_ps128(acc), _mm256_extractf128_ps(acc, 1));
  h = _mm_add_ps(h, _mm_movehl_ps(h, h));
  float sum = _mm_cvtss_f32(_mm_add_ss(h, _mm_movehdup_ps(h)));
  if (s.k % (2 * kGroup)) sum += GroupScalar(s, q, w, scales, r, s.k / (2 * kGroup) * 2);
  return sum;
}

template <bool kScalePerGroup>
SILK_AVX2 void RowsAvx2(const Int4MatMulShape& s, const QuantizedRow& q, const uint8_t* packed, const float* scales,
                        int64_t r0, int64_t r1, float* out) {
  const int64_t pairs = s.k / (2 * kGroup), blocks = s.k / s.block, groups_per_block = s.block / kGroup;
  for (int64_t r = r0; r < r1; ++r) {
    const uint8_t* w = packed + r * (s.k / 2);
    __m256 acc = _mm256_setzero_ps();
    for (int64_t p = 0; p < pairs; ++p) {
      __m256i lo, hi;
      StepNibbles(w, p, &lo, &hi);
      acc = StepAccumulate(lo, hi, StepScale<kScalePerGroup>(scales + r * blocks, p, groups_per_block), q, p, acc);
    }
    out[r] = RowSum(acc, s, q, w, scales, r);
  }
}

// RowsAvx2 for kRows activation rows at once (a batch of sequences, or a chunk of positions):
// each 32-byte step of the weight stream is loaded and split into nibbles once and applied to
// every row, each row accumulated in its own register by exactly RowsAvx2's operations in
// RowsAvx2's order, so each row's outputs are those of RowsAvx2 alone, bit for bit.
template <bool kScalePerGroup, int kRows>
SILK_AVX2 void RowsAvx2Batch(const Int4MatMulShape& s, const QuantizedRow* q, const uint8_t* packed,
                             const float* scales, int64_t r0, int64_t r1, float* out) {
  const int64_t pairs = s.k / (2 * kGroup), blocks = s.k / s.block, groups_per_block = s.block / kGroup;
  for (int64_t r = r0; r < r1; ++r) {
    const uint8_t* w = packed + r * (s.k / 2);
    __m256 acc[kRows];
#pragma GCC unroll 4
    for (int i = 0; i < kRows; ++i) acc[i] = _mm256_setzero_ps();
    for (int64_t p = 0; p < pairs; ++p) {
      __m256i lo, hi;
      StepNibbles(w, p, &lo, &hi);
      const __m256 wscale = StepScale<kScalePerGroup>(scales + r * blocks, p, groups_per_block);
#pragma GCC unroll 4
      for (int i = 0; i < kRows; ++i) acc[i] = StepAccumulate(lo, hi, wscale, q[i], p, acc[i]);
    }
    for (int i = 0; i < kRows; ++i) out[i * s.n + r] = RowSum(acc[i], s, q[i], w, scales, r);
  }
}

// Two activation rows per 512-bit register: each row in its own 256-bit half doing RowsAvx2's
// float operations in RowsAvx2's order, so each row is still bit-identical to it alone. The
// integer dot products use VNNI (vpdpbusd), which gives the same exact int32 sums as
// maddubs + madd (no product or partial sum of 4-bit weights and int8 activations saturates).
#define SILK_AVX512 SILK_TARGET_AVX512_VNNI
SILK_AVX512_CODE_BEGIN

// Step p of every pair of activation rows against one weight row's step: acc[j] as StepAccumulate
// computes it, for both rows of pair j at once.
template <int kPairs>
SILK_AVX512 inline void StepPairs(__m512i lo, __m512i hi, __m512 wscale, const PairedRows& a, int64_t j0, int64_t p,
                                  __m512* acc) {
#pragma GCC unroll 4
  for (int j = 0; j < kPairs; ++j) {
    const int8_t* b = a.Bytes(j0 + j, p);
    const int32_t* w = a.Words(j0 + j, p);
    __m512i dot = _mm512_loadu_si512(w);
    dot = _mm512_dpbusd_epi32(dot, lo, _mm512_loadu_si512(b));
    dot = _mm512_dpbusd_epi32(dot, hi, _mm512_loadu_si512(b + 64));
    const __m512 lane = _mm512_mul_ps(wscale, _mm512_loadu_ps(reinterpret_cast<const float*>(w + 16)));
    acc[j] = _mm512_fmadd_ps(_mm512_cvtepi32_ps(dot), lane, acc[j]);
  }
}

// Pairs [j0, j0 + kPairs) (activation rows 2 * j0 ...) against weight rows [r0, r1); out is
// activation row 0's, rows past m are not written.
template <bool kScalePerGroup, int kPairs>
SILK_AVX512 void RowsAvx512Pairs(const Int4MatMulShape& s, const QuantizedRows& q, const PairedRows& a, int64_t j0,
                                 const uint8_t* packed, const float* scales, int64_t r0, int64_t r1, float* out) {
  const int64_t pairs = s.k / (2 * kGroup), blocks = s.k / s.block, groups_per_block = s.block / kGroup;
  const __m512i low4 = _mm512_set1_epi8(0x0f);
  for (int64_t r = r0; r < r1; ++r) {
    const uint8_t* w = packed + r * (s.k / 2);
    __m512 acc[kPairs];  // (the loops over it are unrolled, so it stays in registers)
#pragma GCC unroll 4
    for (int j = 0; j < kPairs; ++j) acc[j] = _mm512_setzero_ps();
    for (int64_t p = 0; p < pairs; ++p) {
      _mm_prefetch(reinterpret_cast<const char*>(w + p * 32 + kPrefetchBytes), _MM_HINT_T0);
      const __m512i x = _mm512_broadcast_i64x4(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(w + p * 32)));
      const __m512i lo = _mm512_and_si512(x, low4), hi = _mm512_and_si512(_mm512_srli_epi16(x, 4), low4);
      const __m256 ws = StepScale<kScalePerGroup>(scales + r * blocks, p, groups_per_block);
      const __m512 wscale = _mm512_castpd_ps(_mm512_broadcast_f64x4(_mm256_castps_pd(ws)));
      StepPairs<kPairs>(lo, hi, wscale, a, j0, p, acc);
    }
#pragma GCC unroll 4
    for (int j = 0; j < kPairs; ++j)
      for (int h = 0; h < 2; ++h) {
        const int64_t m = 2 * (j0 + j) + h;
        if (m >= s.m) break;
        const __m512d both = _mm512_castps_pd(acc[j]);
        const __m256 half = _mm256_castpd_ps(h ? _mm512_extractf64x4_pd(both, 1) : _mm512_castpd512_pd256(both));
        out[m * s.n + r] = RowSum(half, s, q[m], w, scales, r);
      }
  }
}
SILK_AVX512_CODE_END
#endif

GroupValuesFn PickGroupValues(RowKernels kernels) {
#ifdef SILK_KERNELS_X86
  if (kernels == RowKernels::kBest && CpuHasAvx2()) return GroupValuesAvx2;
#endif
  (void)kernels;
  return GroupValuesScalar;
}

using RowsFn = void (*)(const Int4MatMulShape&, const QuantizedRow&, const uint8_t*, const float*, int64_t, int64_t,
                        float*);

RowsFn PickRows(const Int4MatMulShape& s, RowKernels kernels) {
#ifdef SILK_KERNELS_X86
  if (kernels == RowKernels::kBest && CpuHasAvx2()) return s.block == kGroup ? RowsAvx2<true> : RowsAvx2<false>;
#endif
  (void)s, (void)kernels;
  return RowsScalar;
}

// kRows activation rows at once (1..kMaxBatchRows) against weight rows [r0, r1); out is row 0's.
using BatchFn = void (*)(const Int4MatMulShape&, const QuantizedRow*, const uint8_t*, const float*, int64_t, int64_t,
                         float*);
constexpr int kMaxBatchRows = 4;  // activation rows per pass over a tile (measured: bench/kernel_rows)

BatchFn PickBatch(const Int4MatMulShape& s, RowKernels kernels, int64_t rows) {
#ifdef SILK_KERNELS_X86
  if (kernels == RowKernels::kBest && CpuHasAvx2()) {
    static constexpr BatchFn kGroupScale[kMaxBatchRows] = {RowsAvx2Batch<true, 1>, RowsAvx2Batch<true, 2>,
                                                           RowsAvx2Batch<true, 3>, RowsAvx2Batch<true, 4>};
    static constexpr BatchFn kBlockScale[kMaxBatchRows] = {RowsAvx2Batch<false, 1>, RowsAvx2Batch<false, 2>,
                                                           RowsAvx2Batch<false, 3>, RowsAvx2Batch<false, 4>};
    const BatchFn* table = s.block == kGroup ? kGroupScale : kBlockScale;
    return table[std::min<int64_t>(rows, kMaxBatchRows) - 1];
  }
#endif
  (void)s, (void)kernels, (void)rows;
  return nullptr;
}

// kPairs pairs of activation rows at once (1..kMaxPairs), from pair j0, against weight rows [r0, r1).
using PairsFn = void (*)(const Int4MatMulShape&, const QuantizedRows&, const PairedRows&, int64_t, const uint8_t*,
                         const float*, int64_t, int64_t, float*);
constexpr int kMaxPairs = 4;  // pairs of activation rows per pass over a tile (8 rows)

PairsFn PickPairs(const Int4MatMulShape& s, RowKernels kernels, int64_t pairs) {
#ifdef SILK_KERNELS_X86
  if (kernels == RowKernels::kBest && CpuHasAvx512Vnni()) {
    static constexpr PairsFn kGroupScale[kMaxPairs] = {RowsAvx512Pairs<true, 1>, RowsAvx512Pairs<true, 2>,
                                                       RowsAvx512Pairs<true, 3>, RowsAvx512Pairs<true, 4>};
    static constexpr PairsFn kBlockScale[kMaxPairs] = {RowsAvx512Pairs<false, 1>, RowsAvx512Pairs<false, 2>,
                                                       RowsAvx512Pairs<false, 3>, RowsAvx512Pairs<false, 4>};
    const PairsFn* table = s.block == kGroup ? kGroupScale : kBlockScale;
    return table[std::min<int64_t>(pairs, kMaxPairs) - 1];
  }
#endif
  (void)s, (void)kernels, (void)pairs;
  return nullptr;
}

// Pairs per pass over a weight tile: as many as keep their activations (256 bytes per pair per
// 64 weights) within a 48 KB L1 data cache, between 1 and kMaxPairs (measured, bench/int4_rows:
// at K 4,096, two pairs per pass give 8 rows 0.52 ms against 0.62 ms for one).
int64_t PairsPerPass(int64_t k) {
  const int64_t steps = std::max<int64_t>(1, (k + 2 * kGroup - 1) / (2 * kGroup));  // K below 64 too
  return std::clamp<int64_t>(int64_t{48 * 1024} / (steps * 256), 1, kMaxPairs);
}

struct Job {
  const Int4MatMulShape* shape;
  const QuantizedRows* rows;
  const uint8_t* packed;
  const float* scales;
  float* out;
  RowsFn fn;
  BatchFn batch[kMaxBatchRows];  // by rows - 1; null: one activation row at a time with fn
  const PairedRows* paired;      // with pair_fns: the 512-bit kernels instead of batch
  PairsFn pair_fns[kMaxPairs];   // by pairs - 1
};

// Weight rows [i * kRowsPerTask, ...) against every activation row: the rows' bytes are read
// from memory once and stay in cache for the other activation rows.
void RunTask(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const Int4MatMulShape& s = *job.shape;
  const int64_t r0 = static_cast<int64_t>(index) * kRowsPerTask, r1 = std::min(s.n, r0 + kRowsPerTask);
  if (job.paired) {
    const int64_t pairs = (s.m + 1) / 2, most = PairsPerPass(s.k), passes = (pairs + most - 1) / most;
    const int64_t per_pass = (pairs + passes - 1) / passes;  // even passes: 4 pairs at most 3 a pass go 2 + 2
    for (int64_t j = 0; j < pairs; j += per_pass)
      job.pair_fns[std::min(pairs - j, per_pass) - 1](s, *job.rows, *job.paired, j, job.packed, job.scales, r0, r1,
                                                      job.out);
    return;
  }
  if (!job.batch[0]) {
    for (int64_t m = 0; m < s.m; ++m) job.fn(s, (*job.rows)[m], job.packed, job.scales, r0, r1, job.out + m * s.n);
    return;
  }
  for (int64_t m = 0; m < s.m; m += kMaxBatchRows) {
    const int64_t rows = std::min<int64_t>(s.m - m, kMaxBatchRows);
    job.batch[rows - 1](s, &(*job.rows)[m], job.packed, job.scales, r0, r1, job.out + m * s.n);
  }
}

}  // namespace

bool Int4ShapeSupported(const Int4MatMulShape& s, const char** why) {
  const char* problem = nullptr;
  constexpr int64_t kLimit = int64_t{1} << 31;  // keeps every index product in range
  if (s.m < 0 || s.k <= 0 || s.n <= 0 || s.k >= kLimit || s.n >= kLimit)
    problem = "K and N must be in [1, 2^31)";
  else if (s.block != kGroup && (s.block <= 0 || s.block % (2 * kGroup) != 0))
    problem = "block_size must be 32 or a multiple of 64";
  else if (s.k % s.block != 0)
    problem = "K must be a multiple of block_size";
  if (why) *why = problem;
  return problem == nullptr;
}

void QuantizeInt4Activations(const float* a, int64_t k, int8_t* values, float* scales, RowKernels kernels) {
  const GroupValuesFn group_values = PickGroupValues(kernels);
  for (int64_t g = 0; g < k / kGroup; ++g) {
    alignas(32) int32_t v[kGroup];
    scales[g] = group_values(a + g * kGroup, v);
    for (int64_t i = 0; i < kGroup; ++i) values[g * kGroup + i] = static_cast<int8_t>(v[i]);
  }
}

void Int4MatMul(const Int4MatMulShape& s, const float* a, const uint8_t* packed, const float* scales, float* out,
                ParallelForFn parallel_for, void* parallel_context, RowKernels kernels) {
  if (s.m == 0) return;
  QuantizedRows rows(s.m, s.k);
  const GroupValuesFn group_values = PickGroupValues(kernels);
  for (int64_t m = 0; m < s.m; ++m) QuantizeRow(a + m * s.k, s.k, group_values, rows.row(m));
  Job job{&s, &rows, packed, scales, out, PickRows(s, kernels), {}, nullptr, {}};
  std::unique_ptr<PairedRows> paired;
  if (s.m > 1 && PickPairs(s, kernels, 1)) {  // the 512-bit kernels, two activation rows per register
    paired = std::make_unique<PairedRows>(rows, s.m, s.k);
    job.paired = paired.get();
    for (int64_t j = 1; j <= kMaxPairs; ++j) job.pair_fns[j - 1] = PickPairs(s, kernels, j);
  } else if (s.m > 1) {  // one row (a single sequence's step) keeps the one-row kernel
    for (int64_t r = 1; r <= kMaxBatchRows; ++r) job.batch[r - 1] = PickBatch(s, kernels, r);
  }
  RunTasks(parallel_for, parallel_context, RunTask, &job, static_cast<size_t>((s.n + kRowsPerTask - 1) / kRowsPerTask));
}

}  // namespace silk
