// SPDX-License-Identifier: MIT
// HalfMatMul: each float16 weight row is read once per call and dotted with every activation row
// (AVX2 + F16C: four accumulators, the stream prefetched ahead, eight weight rows reduced together
// and, for many activation rows, converted once, two rows per register with AVX-512; plain C++
// otherwise), rows spread over the caller's pool in blocks.
#include "kernels/quant/half_matmul.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "kernels/cpu/cpu_features.h"
#include "kernels/cpu/float16.h"
#include "kernels/cpu/vector_sums.h"

namespace silk {

namespace {

constexpr int64_t kRowsPerTask = 256;  // weight rows per unit of parallel work

float RowScalar(const float* a, const uint16_t* w, int64_t k) {
  float acc = 0.0f;
  for (int64_t i = 0; i < k; ++i) acc += a[i] * HalfToFloat(w[i]);
  return acc;
}

#ifdef SILK_KERNELS_X86
#define SILK_AVX2 SILK_TARGET_AVX2

constexpr int64_t kPrefetchBytes = 2048;  // ahead in the weight stream

SILK_AVX2 inline __m256 Half8(const uint16_t* p) {
  return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}

// Four independent accumulators over 32 elements per step; the tail (k % 32) in plain C++.
SILK_AVX2 float RowAvx2(const float* a, const uint16_t* w, int64_t k) {
  __m256 acc[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
  int64_t i = 0;
  for (; i + 32 <= k; i += 32) {
    _mm_prefetch(reinterpret_cast<const char*>(w + i) + kPrefetchBytes, _MM_HINT_T0);
    for (int j = 0; j < 4; ++j) acc[j] = _mm256_fmadd_ps(_mm256_loadu_ps(a + i + 8 * j), Half8(w + i + 8 * j), acc[j]);
  }
  const __m256 s = _mm256_add_ps(_mm256_add_ps(acc[0], acc[1]), _mm256_add_ps(acc[2], acc[3]));
  return Sum8(s) + RowScalar(a + i, w + i, k - i);
}

// Eight weight rows at once against each activation row: every output keeps RowAvx2's arithmetic
// (the same four accumulators over the same 32-wide steps, the same horizontal sum, the tail
// added last), so a product is bit for bit the same whichever path computes it; the eight
// horizontal sums are done together (a 4x4 transpose per half) and stored as one vector, and with
// several activation rows the eight weight rows are converted to float32 once for all of them.
constexpr int64_t kBlockRows = 8;
constexpr int64_t kConvertedMax = 1024;  // K up to which a block's weights are converted once

// Whether a call converts each block of weight rows to float32 once for all its activation rows.
bool ConvertsOnce(const HalfMatMulShape& s) { return s.m > 1 && s.k <= kConvertedMax; }

// (acc0 + acc1) + (acc2 + acc3) of RowAvx2 over `steps` steps of 32, weights as float32 or float16.
template <bool kConverted>
SILK_AVX2 inline __m256 StepSums(const float* a, const float* wf, const uint16_t* w, int64_t steps) {
  __m256 acc[4] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
  for (int64_t t = 0, i = 0; t < steps; ++t, i += 32) {
    if (!kConverted) _mm_prefetch(reinterpret_cast<const char*>(w + i) + kPrefetchBytes, _MM_HINT_T0);
    for (int j = 0; j < 4; ++j) {
      const __m256 wv = kConverted ? _mm256_loadu_ps(wf + i + 8 * j) : Half8(w + i + 8 * j);
      acc[j] = _mm256_fmadd_ps(_mm256_loadu_ps(a + i + 8 * j), wv, acc[j]);
    }
  }
  return _mm256_add_ps(_mm256_add_ps(acc[0], acc[1]), _mm256_add_ps(acc[2], acc[3]));
}

// Output j of eight: RowAvx2's reduction of s[j], h_l = s_l + s_(l+4), then (h0 + h2) + (h1 + h3).
SILK_AVX2 inline __m256 Reduce8(const __m256* s) {
  __m256 h[4];  // h[j] = [h of output j | h of output j + 4]
  for (int j = 0; j < 4; ++j)
    h[j] = _mm256_add_ps(_mm256_permute2f128_ps(s[j], s[j + 4], 0x20), _mm256_permute2f128_ps(s[j], s[j + 4], 0x31));
  const __m256 t0 = _mm256_unpacklo_ps(h[0], h[1]), t1 = _mm256_unpackhi_ps(h[0], h[1]);
  const __m256 t2 = _mm256_unpacklo_ps(h[2], h[3]), t3 = _mm256_unpackhi_ps(h[2], h[3]);
  const __m256 c0 = _mm256_shuffle_ps(t0, t2, 0x44), c1 = _mm256_shuffle_ps(t0, t2, 0xEE);
  const __m256 c2 = _mm256_shuffle_ps(t1, t3, 0x44), c3 = _mm256_shuffle_ps(t1, t3, 0xEE);
  return _mm256_add_ps(_mm256_add_ps(c0, c2), _mm256_add_ps(c1, c3));
}

// The eight weight rows of a block as float32 (`wf`: 8 x the 32-wide body of K), converted once for
// every activation row of the call.
SILK_AVX2 void ConvertBlock(int64_t k, const uint16_t* w, float* wf) {
  const int64_t body = k / 32 * 32;
  for (int64_t j = 0; j < kBlockRows; ++j)
    for (int64_t i = 0; i < body; i += 8) _mm256_storeu_ps(wf + j * body + i, Half8(w + j * k + i));
}

// Weight rows [r0, r0 + 8) against activation rows [m0, m_rows); `wf`: the block converted by
// ConvertBlock when kConverted.
template <bool kConverted>
SILK_AVX2 void BlockAvx2(int64_t m0, int64_t m_rows, int64_t k, int64_t n, const float* a, const uint16_t* w,
                         float* out, const float* wf) {
  const int64_t steps = k / 32, body = steps * 32;
  for (int64_t m = m0; m < m_rows; ++m) {
    const float* am = a + m * k;
    __m256 sums[kBlockRows];
    alignas(32) float tail[kBlockRows];
    for (int64_t j = 0; j < kBlockRows; ++j) {
      sums[j] = StepSums<kConverted>(am, wf + j * body, w + j * k, steps);
      tail[j] = RowScalar(am + body, w + j * k + body, k - body);
    }
    _mm256_storeu_ps(out + m * n, _mm256_add_ps(Reduce8(sums), _mm256_load_ps(tail)));
  }
}

// Two activation rows per 512-bit register (row 2i in the low half, 2i + 1 in the high one),
// each half doing BlockAvx2's float operations in BlockAvx2's order, so each output is still bit
// for bit its one-row value; the ports do twice the products per instruction, and a step's four
// activation vectors stay in registers for four weight rows (one weight load per fma).
#define SILK_AVX512 SILK_TARGET_AVX512
SILK_AVX512_CODE_BEGIN

// The call's activation rows two by two, 8 floats of row 2i then the same 8 of row 2i + 1, over
// the 32-wide body of K (64-byte aligned); an odd last row is left to BlockAvx2.
class PairedActivations {
 public:
  PairedActivations(const float* a, int64_t m, int64_t k)
      : chunks_(k / 32 * 4), pairs_(m / 2), data_(static_cast<size_t>(pairs_ * chunks_ * 16 + 16)) {
    data0_ = data_.data() + (64 - reinterpret_cast<uintptr_t>(data_.data()) % 64) % 64 / 4;
    for (int64_t p = 0; p < pairs_; ++p)
      for (int64_t c = 0; c < chunks_; ++c)
        for (int h = 0; h < 2; ++h)
          std::copy_n(a + (2 * p + h) * k + c * 8, 8, data0_ + (p * chunks_ + c) * 16 + 8 * h);
  }
  const float* Pair(int64_t p) const { return data0_ + p * chunks_ * 16; }
  int64_t pairs() const { return pairs_; }

 private:
  int64_t chunks_, pairs_;
  std::vector<float> data_;  // 16 floats over, for the alignment
  float* data0_;
};

// StepSums<true> of four weight rows [j0, j0 + 4) of a converted block against one pair: s[j].
SILK_AVX512 inline void PairStepSums4(const float* pa, const float* wf, int64_t body, int64_t j0, __m512* s) {
  // (every loop below is unrolled, so the sixteen accumulators stay in registers)
  __m512 acc[4][4];
#pragma GCC unroll 16
  for (int v = 0; v < 16; ++v) acc[v / 4][v % 4] = _mm512_setzero_ps();
  for (int64_t i = 0; i < body; i += 32) {
    __m512 a[4];
#pragma GCC unroll 4
    for (int c = 0; c < 4; ++c) a[c] = _mm512_load_ps(pa + (i / 8 + c) * 16);
#pragma GCC unroll 16
    for (int v = 0; v < 16; ++v) {
      const int j = v / 4, c = v % 4;
      const __m512 wv = _mm512_broadcast_f32x8(_mm256_loadu_ps(wf + (j0 + j) * body + i + 8 * c));
      acc[j][c] = _mm512_fmadd_ps(a[c], wv, acc[j][c]);
    }
  }
#pragma GCC unroll 4
  for (int j = 0; j < 4; ++j)
    s[j0 + j] = _mm512_add_ps(_mm512_add_ps(acc[j][0], acc[j][1]), _mm512_add_ps(acc[j][2], acc[j][3]));
}

// Reduce8 in each half: the low half gives row 2i's eight outputs, the high half row 2i + 1's.
SILK_AVX512 inline __m512 Reduce8Pair(const __m512* s) {
  const __m512i lo = _mm512_set_epi32(27, 26, 25, 24, 11, 10, 9, 8, 19, 18, 17, 16, 3, 2, 1, 0);
  const __m512i hi = _mm512_set_epi32(31, 30, 29, 28, 15, 14, 13, 12, 23, 22, 21, 20, 7, 6, 5, 4);
  __m512 h[4];
  for (int j = 0; j < 4; ++j)
    h[j] = _mm512_add_ps(_mm512_permutex2var_ps(s[j], lo, s[j + 4]), _mm512_permutex2var_ps(s[j], hi, s[j + 4]));
  const __m512 t0 = _mm512_unpacklo_ps(h[0], h[1]), t1 = _mm512_unpackhi_ps(h[0], h[1]);
  const __m512 t2 = _mm512_unpacklo_ps(h[2], h[3]), t3 = _mm512_unpackhi_ps(h[2], h[3]);
  const __m512 c0 = _mm512_shuffle_ps(t0, t2, 0x44), c1 = _mm512_shuffle_ps(t0, t2, 0xEE);
  const __m512 c2 = _mm512_shuffle_ps(t1, t3, 0x44), c3 = _mm512_shuffle_ps(t1, t3, 0xEE);
  return _mm512_add_ps(_mm512_add_ps(c0, c2), _mm512_add_ps(c1, c3));
}

// A converted block of weight rows (w, as float32 in wf) against every pair of activation rows.
SILK_AVX512 void BlockPairs(const PairedActivations& pairs, int64_t k, int64_t n, const float* a, const uint16_t* w,
                            float* out, const float* wf) {
  const int64_t body = k / 32 * 32;
  for (int64_t p = 0; p < pairs.pairs(); ++p) {
    __m512 sums[kBlockRows];
    PairStepSums4(pairs.Pair(p), wf, body, 0, sums);
    PairStepSums4(pairs.Pair(p), wf, body, 4, sums);
    alignas(64) float tail[2 * kBlockRows] = {};
    if (body < k)
      for (int h = 0; h < 2; ++h)
        for (int64_t j = 0; j < kBlockRows; ++j)
          tail[h * kBlockRows + j] = RowScalar(a + (2 * p + h) * k + body, w + j * k + body, k - body);
    const __m512 both = _mm512_add_ps(Reduce8Pair(sums), _mm512_load_ps(tail));
    _mm256_storeu_ps(out + 2 * p * n, _mm512_castps512_ps256(both));
    _mm256_storeu_ps(out + (2 * p + 1) * n, _mm512_extractf32x8_ps(both, 1));
  }
}
SILK_AVX512_CODE_END
#endif

using RowFn = float (*)(const float*, const uint16_t*, int64_t);

RowFn PickRow(RowKernels kernels) {
#ifdef SILK_KERNELS_X86
  if (kernels != RowKernels::kScalar && CpuHasAvx2()) return RowAvx2;
#endif
  (void)kernels;
  return RowScalar;
}

class PairedActivations;  // (defined with the AVX-512 kernels)

struct Job {
  const HalfMatMulShape* shape;
  const float* a;
  const uint16_t* w;
  float* out;
  RowFn row;
  const PairedActivations* pairs;  // where the 512-bit kernel runs, else null
};

// Weight rows [index * kRowsPerTask, ...) against every activation row (each weight row is read
// from memory once; the other activation rows find it in cache).
void RunTask(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const HalfMatMulShape& s = *job.shape;
  const int64_t r0 = static_cast<int64_t>(index) * kRowsPerTask, r1 = std::min(s.n, r0 + kRowsPerTask);
  int64_t r = r0;
#ifdef SILK_KERNELS_X86
  if (job.row == RowAvx2) {
    alignas(32) float wf[kBlockRows * kConvertedMax];
    const bool convert = ConvertsOnce(s);
    const PairedActivations* pairs = job.pairs;
    for (; r + kBlockRows <= r1; r += kBlockRows) {
      const uint16_t* w = job.w + r * s.k;
      if (!convert) {
        BlockAvx2<false>(0, s.m, s.k, s.n, job.a, w, job.out + r, wf);
        continue;
      }
      ConvertBlock(s.k, w, wf);
      if (pairs) BlockPairs(*pairs, s.k, s.n, job.a, w, job.out + r, wf);
      BlockAvx2<true>(pairs ? 2 * pairs->pairs() : 0, s.m, s.k, s.n, job.a, w, job.out + r, wf);
    }
  }
#endif
  for (; r < r1; ++r)
    for (int64_t m = 0; m < s.m; ++m) job.out[m * s.n + r] = job.row(job.a + m * s.k, job.w + r * s.k, s.k);
}

}  // namespace

bool HalfShapeSupported(const HalfMatMulShape& s, const char** why) {
  constexpr int64_t kLimit = int64_t{1} << 31;  // keeps every index product in range
  const char* problem =
      s.m < 0 || s.k <= 0 || s.n <= 0 || s.k >= kLimit || s.n >= kLimit ? "K and N must be in [1, 2^31)" : nullptr;
  if (why) *why = problem;
  return problem == nullptr;
}

void HalfMatMul(const HalfMatMulShape& s, const float* a, const uint16_t* w, float* out, ParallelForFn parallel_for,
                void* parallel_context, RowKernels kernels) {
  if (s.m == 0) return;
  Job job{&s, a, w, out, PickRow(kernels), nullptr};
#ifdef SILK_KERNELS_X86
  std::unique_ptr<PairedActivations> pairs;
  if (kernels == RowKernels::kBest && job.row == RowAvx2 && ConvertsOnce(s) && CpuHasAvx512()) {
    pairs = std::make_unique<PairedActivations>(a, s.m, s.k);
    job.pairs = pairs.get();
  }
#endif
  RunTasks(parallel_for, parallel_context, RunTask, &job, static_cast<size_t>((s.n + kRowsPerTask - 1) / kRowsPerTask));
}

}  // namespace silk
