// SPDX-License-Identifier: MIT
// HalfMatMul: each float16 weight row is read once per call and dotted with every activation row
// (AVX2 + F16C: four accumulators, the stream prefetched ahead; plain C++ otherwise), rows spread
// over the caller's pool in blocks.
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
  for (int64_t r = r0; r < r1; ++r)
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
