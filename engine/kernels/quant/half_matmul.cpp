// SPDX-License-Identifier: MIT
// HalfMatMul: each float16 weight row is read once per call and dotted with every activation row
// (AVX2 + F16C: four accumulators, the stream prefetched ahead, eight weight rows reduced together
// and, for many activation rows, converted once; plain C++ otherwise), rows spread over the
// caller's pool in blocks.
#include "kernels/quant/half_matmul.h"

#include <algorithm>

#include "kernels/cpu/float16.h"

#if (defined(__x86_64__) || defined(_M_X64)) && (defined(__GNUC__) || defined(__clang__))
#define SILK_HALF_AVX2 1
#include <immintrin.h>
#endif

namespace silk {

namespace {

constexpr int64_t kRowsPerTask = 256;  // weight rows per unit of parallel work

float RowScalar(const float* a, const uint16_t* w, int64_t k) {
  float acc = 0.0f;
  for (int64_t i = 0; i < k; ++i) acc += a[i] * HalfToFloat(w[i]);
  return acc;
}

#if SILK_HALF_AVX2
#define SILK_AVX2 __attribute__((target("avx2,fma,f16c")))

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
  __m128 h = _mm_add_ps(_mm256_castps256_ps128(s), _mm256_extractf128_ps(s, 1));
  h = _mm_add_ps(h, _mm_movehl_ps(h, h));
  return _mm_cvtss_f32(_mm_add_ss(h, _mm_movehdup_ps(h))) + RowScalar(a + i, w + i, k - i);
}

// Eight weight rows at once against each activation row: every output keeps RowAvx2's arithmetic
// (the same four accumulators over the same 32-wide steps, the same horizontal sum, the tail
// added last), so a product is bit for bit the same whichever path computes it; the eight
// horizontal sums are done together (a 4x4 transpose per half) and stored as one vector, and with
// several activation rows the eight weight rows are converted to float32 once for all of them.
constexpr int64_t kBlockRows = 8;
constexpr int64_t kConvertedMax = 1024;  // K up to which a block's weights are converted once

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

// Weight rows [r0, r0 + 8) against every activation row; `wf` holds 8 x kConvertedMax floats.
template <bool kConverted>
SILK_AVX2 void BlockAvx2(int64_t m_rows, int64_t k, int64_t n, const float* a, const uint16_t* w, float* out,
                         float* wf) {
  const int64_t steps = k / 32, body = steps * 32;
  if (kConverted)
    for (int64_t j = 0; j < kBlockRows; ++j)
      for (int64_t i = 0; i < body; i += 8) _mm256_storeu_ps(wf + j * body + i, Half8(w + j * k + i));
  for (int64_t m = 0; m < m_rows; ++m) {
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

bool CpuHasAvx2() {
  static const bool has =
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("f16c");
  return has;
}
#endif

using RowFn = float (*)(const float*, const uint16_t*, int64_t);

RowFn PickRow(RowKernels kernels) {
#if SILK_HALF_AVX2
  if (kernels == RowKernels::kBest && CpuHasAvx2()) return RowAvx2;
#endif
  (void)kernels;
  return RowScalar;
}

struct Job {
  const HalfMatMulShape* shape;
  const float* a;
  const uint16_t* w;
  float* out;
  RowFn row;
};

// Weight rows [index * kRowsPerTask, ...) against every activation row (each weight row is read
// from memory once; the other activation rows find it in cache).
void RunTask(void* state, size_t index) {
  const Job& job = *static_cast<const Job*>(state);
  const HalfMatMulShape& s = *job.shape;
  const int64_t r0 = static_cast<int64_t>(index) * kRowsPerTask, r1 = std::min(s.n, r0 + kRowsPerTask);
  int64_t r = r0;
#if SILK_HALF_AVX2
  if (job.row == RowAvx2) {
    alignas(32) float wf[kBlockRows * kConvertedMax];
    const bool convert = s.m > 1 && s.k <= kConvertedMax;
    for (; r + kBlockRows <= r1; r += kBlockRows) {
      const uint16_t* w = job.w + r * s.k;
      if (convert)
        BlockAvx2<true>(s.m, s.k, s.n, job.a, w, job.out + r, wf);
      else
        BlockAvx2<false>(s.m, s.k, s.n, job.a, w, job.out + r, wf);
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
  Job job{&s, a, w, out, PickRow(kernels)};
  RunTasks(parallel_for, parallel_context, RunTask, &job, static_cast<size_t>((s.n + kRowsPerTask - 1) / kRowsPerTask));
}

}  // namespace silk
