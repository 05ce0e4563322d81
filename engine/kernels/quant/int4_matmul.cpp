// SPDX-License-Identifier: MIT
// Int4MatMul: each activation row is quantized once to int8 groups of 32 (scale max|a| / 127; the
// rows of a call on the caller's pool, a row a task), then every weight row is one pass of integer
// dot products over its packed nibbles, scaled per group, with the weight stream prefetched ahead;
// weight rows are spread over the pool. With
// AVX-512 VNNI, 16 groups at a time in group lanes (each group's dot product whole in one lane);
// with AVX2, 64 weights a step in eight lanes; else plain C++.
#include "kernels/quant/int4_matmul.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "kernels/cpu/cpu_features.h"
#include "kernels/cpu/vector_sums.h"

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

// A group's values (in [-127, 127]) as int8, its even elements to `even` and odd ones to `odd`;
// returns their sum.
using SplitGroupFn = int32_t (*)(const int32_t* values, int8_t* even, int8_t* odd);

int32_t SplitGroupScalar(const int32_t* values, int8_t* even, int8_t* odd) {
  int32_t sum = 0;
  for (int64_t i = 0; i < kGroup; ++i) {
    const int8_t v = static_cast<int8_t>(values[i]);
    int8_t* half = i % 2 ? odd : even;  // (as an lvalue, GCC 12's -O0 UBSan build computed a wild address)
    half[i / 2] = v;
    sum += v;
  }
  return sum;
}

// How a call quantizes its activation rows (the vectorized or the plain functions: the same values).
struct GroupQuantizer {
  GroupValuesFn values;
  SplitGroupFn split;
};

void QuantizeRow(const float* a, int64_t k, const GroupQuantizer& quantizer, QuantizedRow* q) {
  const int64_t groups = k / kGroup;
  for (int64_t g = 0; g < groups; ++g) {
    alignas(32) int32_t values[kGroup];
    const float scale = quantizer.values(a + g * kGroup, values);
    const int32_t sum = quantizer.split(values, q->even + g * 16, q->odd + g * 16);
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

// Group lanes: a block of 16 groups (512 weights, 256 packed bytes) of a weight row as four
// 512-bit registers transposed so that each int32 lane holds one group: lane 4c + j is group
// 4j + c of the block (GroupOfLane), and register k holds its packed bytes 4k..4k + 3, whose low
// nibbles meet the group's even elements 8k, 8k + 2, 8k + 4, 8k + 6 and high nibbles the odd ones.
// Eight vpdpbusd then give each lane its group's whole integer dot product, so the float work
// (convert, scale, accumulate) is done once per group and row instead of once per eight weights.
constexpr int64_t kLaneGroups = 16;
constexpr int64_t GroupOfLane(int64_t lane) { return 4 * (lane % 4) + lane / 4; }

// The activation rows of a call laid out for the group lanes: per row and block of 16 groups,
// the bytes that meet the low nibbles of register k (lo[k]: 64 bytes), those that meet the high
// ones (hi[k]), the lanes' zero-point offsets (-8 * sum of the group's values) and scales; groups
// past K are zeros. 64-byte aligned, 640 bytes per row and block.
class GroupLaneRows {
 public:
  static constexpr int64_t kBlockBytes = 640;
  GroupLaneRows(int64_t m, int64_t k)
      : blocks_((k / kGroup + kLaneGroups - 1) / kLaneGroups),
        groups_(k / kGroup),
        bytes_(static_cast<size_t>(m * blocks_ * kBlockBytes + 64)) {
    base_ = bytes_.data() + (64 - reinterpret_cast<uintptr_t>(bytes_.data()) % 64) % 64;
  }
  // Row r's blocks from its quantized values (rows are independent: filled in parallel).
  void Fill(const QuantizedRow& q, int64_t r) {
    for (int64_t b = 0; b < blocks_; ++b) {
      unsigned char* block = Block(r, b);
      for (int64_t lane = 0; lane < kLaneGroups; ++lane) {
        const int64_t g = b * kLaneGroups + GroupOfLane(lane);
        if (g >= groups_) continue;
        for (int kk = 0; kk < 4; ++kk) {
          std::memcpy(block + kk * 64 + lane * 4, q.even + g * 16 + 4 * kk, 4);
          std::memcpy(block + 256 + kk * 64 + lane * 4, q.odd + g * 16 + 4 * kk, 4);
        }
        std::memcpy(block + 512 + lane * 4, q.offset + g * 4, 4);
        std::memcpy(block + 576 + lane * 4, q.scale + g, 4);
      }
    }
  }
  // Row r's block b: lo[4][64], hi[4][64], offsets[16] (int32), scales[16] (float).
  const unsigned char* Block(int64_t r, int64_t b) const { return base_ + (r * blocks_ + b) * kBlockBytes; }
  int64_t blocks() const { return blocks_; }

 private:
  unsigned char* Block(int64_t r, int64_t b) { return base_ + (r * blocks_ + b) * kBlockBytes; }
  int64_t blocks_, groups_;
  std::vector<unsigned char> bytes_;  // zeros where no group is
  unsigned char* base_;
};

// Per block of 16 groups of a weight row: where its scales start among the row's scales, how many
// there are, and which of them each lane takes (scale index = group * 32 / block).
struct LaneScales {
  std::vector<int64_t> first, count;
  std::vector<int32_t> pick;  // [blocks][16]: the lane's scale, counted from `first`

  LaneScales(const Int4MatMulShape& s, int64_t blocks) : first(blocks), count(blocks), pick(blocks * kLaneGroups) {
    const int64_t groups = s.k / kGroup;
    for (int64_t b = 0; b < blocks; ++b) {
      const int64_t g0 = b * kLaneGroups, g1 = std::min(groups, g0 + kLaneGroups);
      first[b] = g0 * kGroup / s.block;
      count[b] = (g1 - 1) * kGroup / s.block - first[b] + 1;
      for (int64_t lane = 0; lane < kLaneGroups; ++lane) {
        const int64_t g = g0 + GroupOfLane(lane);  // a lane past K takes a zero (count < 16 there)
        pick[b * kLaneGroups + lane] = static_cast<int32_t>(g < groups ? g * kGroup / s.block - first[b] : 15);
      }
    }
  }
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

// SplitGroupScalar's bytes and sum: the 32 values packed to int8 in order (no value saturates),
// then the even bytes of each 128-bit lane gathered before the odd ones.
SILK_AVX2 int32_t SplitGroupAvx2(const int32_t* values, int8_t* even, int8_t* odd) {
  const __m256i* v = reinterpret_cast<const __m256i*>(values);
  const __m256i a = _mm256_load_si256(v), b = _mm256_load_si256(v + 1), c = _mm256_load_si256(v + 2),
                d = _mm256_load_si256(v + 3);
  const __m256i sums = _mm256_add_epi32(_mm256_add_epi32(a, b), _mm256_add_epi32(c, d));
  __m128i t = _mm_add_epi32(_mm256_castsi256_si128(sums), _mm256_extracti128_si256(sums, 1));
  t = _mm_add_epi32(t, _mm_shuffle_epi32(t, 0x4e));
  t = _mm_add_epi32(t, _mm_shuffle_epi32(t, 0xb1));
  // packs interleave the 128-bit lanes: dwords a0-3 b0-3 c0-3 d0-3 | a4-7 b4-7 c4-7 d4-7, put back in order
  __m256i x = _mm256_packs_epi16(_mm256_packs_epi32(a, b), _mm256_packs_epi32(c, d));
  x = _mm256_permutevar8x32_epi32(x, _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7));
  const __m256i evens_first = _mm256_setr_epi8(0, 2, 4, 6, 8, 10, 12, 14, 1, 3, 5, 7, 9, 11, 13, 15, 0, 2, 4, 6, 8, 10,
                                               12, 14, 1, 3, 5, 7, 9, 11, 13, 15);
  x = _mm256_permute4x64_epi64(_mm256_shuffle_epi8(x, evens_first), _MM_SHUFFLE(3, 1, 2, 0));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(even), _mm256_castsi256_si128(x));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(odd), _mm256_extracti128_si256(x, 1));
  return _mm_cvtsi128_si32(t);
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
  float sum = Sum8(acc);
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

// Block b of a weight row (256 packed bytes from w; fewer past K, read masked) transposed into
// group lanes: lo[k] and hi[k] its nibbles as GroupLaneRows' lo[k] and hi[k] expect them.
SILK_AVX512 inline void LaneNibbles(const uint8_t* w, int64_t bytes, __m512i* lo, __m512i* hi) {
  __m512i x[4];
  if (bytes >= 256) {
#pragma GCC unroll 4
    for (int j = 0; j < 4; ++j) x[j] = _mm512_loadu_si512(w + 64 * j);
  } else {  // the last block of a row whose groups are not a multiple of 16
    for (int j = 0; j < 4; ++j) {
      const int64_t n = std::clamp<int64_t>(bytes - 64 * j, 0, 64);
      x[j] = _mm512_maskz_loadu_epi8(n == 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1, w + 64 * j);
    }
  }
  // a 4 x 4 transpose of the dwords of each 128-bit lane: register k, lane 4c + j = x[j]'s lane c, dword k
  const __m512i t0 = _mm512_unpacklo_epi32(x[0], x[1]), t1 = _mm512_unpackhi_epi32(x[0], x[1]);
  const __m512i t2 = _mm512_unpacklo_epi32(x[2], x[3]), t3 = _mm512_unpackhi_epi32(x[2], x[3]);
  const __m512i k[4] = {_mm512_unpacklo_epi64(t0, t2), _mm512_unpackhi_epi64(t0, t2), _mm512_unpacklo_epi64(t1, t3),
                        _mm512_unpackhi_epi64(t1, t3)};
  const __m512i low4 = _mm512_set1_epi8(0x0f);
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j)
    lo[j] = _mm512_and_si512(k[j], low4), hi[j] = _mm512_and_si512(_mm512_srli_epi16(k[j], 4), low4);
}

// Activation rows [m0, m0 + kRows) against weight rows [r0, r1) in group lanes: per block, the
// eight dot products of each lane's group (zero point included) converted once, times the weight
// and activation scales, accumulated per lane; the 16 lanes summed at the end in a fixed order.
// Each row's arithmetic depends on that row alone, so a row is the same bits in any batch.
template <int kRows>
SILK_AVX512 void GroupLanesAvx512(const Int4MatMulShape& s, const GroupLaneRows& a, const LaneScales& ls, int64_t m0,
                                  const uint8_t* packed, const float* scales, int64_t r0, int64_t r1, float* out) {
  const int64_t blocks = a.blocks(), row_bytes = s.k / 2, row_scales = s.k / s.block;
  for (int64_t r = r0; r < r1; ++r) {
    const uint8_t* w = packed + r * row_bytes;
    const float* ws = scales + r * row_scales;
    __m512 acc[kRows];  // (the loops over it are unrolled, so it stays in registers)
#pragma GCC unroll 8
    for (int i = 0; i < kRows; ++i) acc[i] = _mm512_setzero_ps();
    for (int64_t b = 0; b < blocks; ++b) {
#pragma GCC unroll 4
      for (int line = 0; line < 4; ++line)
        _mm_prefetch(reinterpret_cast<const char*>(w + b * 256 + kPrefetchBytes + 64 * line), _MM_HINT_T0);
      __m512i lo[4], hi[4];
      LaneNibbles(w + b * 256, row_bytes - b * 256, lo, hi);
      const __mmask16 have = static_cast<__mmask16>((1u << ls.count[b]) - 1);  // count: 1..16
      const __m512 held = _mm512_maskz_loadu_ps(have, ws + ls.first[b]);
      const __m512 wscale = _mm512_permutexvar_ps(_mm512_loadu_si512(&ls.pick[b * kLaneGroups]), held);
#pragma GCC unroll 8
      for (int i = 0; i < kRows; ++i) {
        const unsigned char* x = a.Block(m0 + i, b);
        __m512i dot = _mm512_load_si512(x + 512);
#pragma GCC unroll 4
        for (int k = 0; k < 4; ++k) {
          dot = _mm512_dpbusd_epi32(dot, lo[k], _mm512_load_si512(x + 64 * k));
          dot = _mm512_dpbusd_epi32(dot, hi[k], _mm512_load_si512(x + 256 + 64 * k));
        }
        const __m512 lane = _mm512_mul_ps(wscale, _mm512_load_ps(reinterpret_cast<const float*>(x + 576)));
        acc[i] = _mm512_fmadd_ps(_mm512_cvtepi32_ps(dot), lane, acc[i]);
      }
    }
#pragma GCC unroll 8
    for (int i = 0; i < kRows; ++i) out[(m0 + i) * s.n + r] = SumHalves(acc[i]);
  }
}
SILK_AVX512_CODE_END
#endif

GroupQuantizer PickQuantizer(RowKernels kernels) {
#ifdef SILK_KERNELS_X86
  if (kernels != RowKernels::kScalar && CpuHasAvx2()) return {GroupValuesAvx2, SplitGroupAvx2};
#endif
  (void)kernels;
  return {GroupValuesScalar, SplitGroupScalar};
}

using RowsFn = void (*)(const Int4MatMulShape&, const QuantizedRow&, const uint8_t*, const float*, int64_t, int64_t,
                        float*);

RowsFn PickRows(const Int4MatMulShape& s, RowKernels kernels) {
#ifdef SILK_KERNELS_X86
  if (kernels != RowKernels::kScalar && CpuHasAvx2()) return s.block == kGroup ? RowsAvx2<true> : RowsAvx2<false>;
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
  if (kernels != RowKernels::kScalar && CpuHasAvx2()) {
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

// kRows activation rows at once (1..kMaxLaneRows) in group lanes, from row m0.
using LanesFn = void (*)(const Int4MatMulShape&, const GroupLaneRows&, const LaneScales&, int64_t, const uint8_t*,
                         const float*, int64_t, int64_t, float*);
constexpr int kMaxLaneRows = 8;  // activation rows per pass over a tile (measured: 8 rows 0.21 ms, 2 x 4 0.27 ms)

LanesFn PickLanes(RowKernels kernels, int64_t rows) {
#ifdef SILK_KERNELS_X86
  if (kernels == RowKernels::kBest && CpuHasAvx512Vnni()) {
    static constexpr LanesFn kByRows[kMaxLaneRows] = {GroupLanesAvx512<1>, GroupLanesAvx512<2>, GroupLanesAvx512<3>,
                                                      GroupLanesAvx512<4>, GroupLanesAvx512<5>, GroupLanesAvx512<6>,
                                                      GroupLanesAvx512<7>, GroupLanesAvx512<8>};
    return kByRows[std::min<int64_t>(rows, kMaxLaneRows) - 1];
  }
#endif
  (void)kernels, (void)rows;
  return nullptr;
}

struct Job {
  const Int4MatMulShape* shape;
  const QuantizedRows* rows;
  const uint8_t* packed;
  const float* scales;
  float* out;
  RowsFn fn;
  BatchFn batch[kMaxBatchRows];  // by rows - 1; null: one activation row at a time with fn
  const GroupLaneRows* lanes;    // with lane_fns: the group-lane kernels instead of fn and batch
  const LaneScales* lane_scales;
  LanesFn lane_fns[kMaxLaneRows];  // by rows - 1
};

// Weight rows [i * kRowsPerTask, ...) against every activation row: the rows' bytes are read
// from memory once and stay in cache for the other activation rows.
void RunTask(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const Int4MatMulShape& s = *job.shape;
  const int64_t r0 = static_cast<int64_t>(index) * kRowsPerTask, r1 = std::min(s.n, r0 + kRowsPerTask);
  if (job.lanes) {
    for (int64_t m = 0; m < s.m; m += kMaxLaneRows) {
      const int64_t rows = std::min<int64_t>(s.m - m, kMaxLaneRows);
      job.lane_fns[rows - 1](s, *job.lanes, *job.lane_scales, m, job.packed, job.scales, r0, r1, job.out);
    }
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

// Activation row `index`: its int8 groups, and its group-lane blocks when the call uses them.
struct PrepareJob {
  const Int4MatMulShape* shape;
  const float* a;
  GroupQuantizer quantizer;
  QuantizedRows* rows;
  GroupLaneRows* lanes;  // null: no group lanes
};

void PrepareRow(void* state, size_t index) {
  const PrepareJob& job = *static_cast<const PrepareJob*>(state);
  const int64_t m = static_cast<int64_t>(index), k = job.shape->k;
  QuantizeRow(job.a + m * k, k, job.quantizer, job.rows->row(m));
  if (job.lanes) job.lanes->Fill((*job.rows)[m], m);
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
  const GroupValuesFn group_values = PickQuantizer(kernels).values;
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
  Job job{&s, &rows, packed, scales, out, PickRows(s, kernels), {}, nullptr, nullptr, {}};
  std::unique_ptr<GroupLaneRows> lanes;
  std::unique_ptr<LaneScales> lane_scales;
  if (PickLanes(kernels, 1)) {  // one row and many alike: a row's bits do not depend on the batch
    lanes = std::make_unique<GroupLaneRows>(s.m, s.k);
    lane_scales = std::make_unique<LaneScales>(s, lanes->blocks());
    job.lanes = lanes.get(), job.lane_scales = lane_scales.get();
    for (int64_t r = 1; r <= kMaxLaneRows; ++r) job.lane_fns[r - 1] = PickLanes(kernels, r);
  } else if (s.m > 1) {  // one row (a single sequence's step) keeps the one-row kernel
    for (int64_t r = 1; r <= kMaxBatchRows; ++r) job.batch[r - 1] = PickBatch(s, kernels, r);
  }
  // The activation rows quantized (and laid out in group lanes) on the pool, a row a task: with
  // 8 rows this was a tenth of a release decoder call on one thread while the others waited.
  PrepareJob prepare{&s, a, PickQuantizer(kernels), &rows, lanes.get()};
  RunTasks(parallel_for, parallel_context, PrepareRow, &prepare, static_cast<size_t>(s.m));
  RunTasks(parallel_for, parallel_context, RunTask, &job, static_cast<size_t>((s.n + kRowsPerTask - 1) / kRowsPerTask));
}

}  // namespace silk
