// SPDX-License-Identifier: MIT
// The row primitives of CachedAttention (dot products with cached keys, the softmax's
// exponentials, the weighted sum of cached values, storing new rows) for one cache element type:
// AVX-512 or AVX2/FMA/F16C versions where the CPU has them (the same bits), plain C++ otherwise,
// chosen once per call.
// `rows` are consecutive cache rows of CacheRowBytes(element, d) bytes each.
#pragma once
#include <cstdint>

#include "kernels/attention/cached_attention.h"

namespace silk {

struct AttentionRows {
  bool vectorized = false;
  // Row of `d` floats into the cache's element type (float16: round to nearest even; int8:
  // scale = max|x| / 127, int8[i] = x[i] / scale rounded to nearest even, in [-127, 127]).
  void (*store)(const float* src, void* row, int64_t d) = nullptr;
  // out[j] = scale * q . rows[j] for the n consecutive rows of d values (int8 rows: with q
  // rounded to int16 steps of max|q| / 32767 and the sum exact in integers; docs/model_contract.md).
  void (*dots)(const float* q, const void* rows, int64_t n, int64_t d, float scale, float* out) = nullptr;
  // x[j] = exp(x[j] - top) (every x[j] <= top); returns their sum.
  float (*exp_shifted)(float* x, int64_t n, float top) = nullptr;
  // out[i] += factor * sum_j w[j] * rows[j][i].
  void (*weighted_sum)(const float* w, const void* rows, int64_t n, int64_t d, float factor, float* out) = nullptr;
  // Several queries over the same rows (cross attention: the candidates of one mesh read its K/V),
  // each exactly as dots / weighted_sum would give it alone, the rows widened once for all of them;
  // nullptr where the element type or head size has no such version (DotsOfMany and
  // WeightedSumsOfMany then call the one-query primitives in turn).
  void (*dots_many)(const float* const* q, int64_t queries, const void* rows, int64_t n, int64_t d, float scale,
                    float* const* out) = nullptr;
  void (*weighted_sum_many)(const float* const* w, int64_t queries, const void* rows, int64_t n, int64_t d,
                            const float* factor, float* const* out) = nullptr;

  void DotsOfMany(const float* const* q, int64_t queries, const void* rows, int64_t n, int64_t d, float scale,
                  float* const* out) const;
  void WeightedSumsOfMany(const float* const* w, int64_t queries, const void* rows, int64_t n, int64_t d,
                          const float* factor, float* const* out) const;
};

AttentionRows AttentionRowsFor(CacheElement element, int64_t head_dim, RowKernels kernels);

}  // namespace silk
