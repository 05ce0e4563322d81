// SPDX-License-Identifier: MIT
// Matrix product with float16 weights: the decoder's logits head (d_model x 10,269 in the release
// network: 42 MB read in float32 on every call, the largest weight left unquantized because the
// logits decide the sampled id). Stored as float16 it reads half the bytes; products and sums
// stay float32. The ai.silk HalfMatMul op (docs/model_contract.md) computes it.
#pragma once
#include <cstdint>

#include "kernels/cpu/cpu_kernels.h"

namespace silk {

// out[m, n] = sum_k a[m, k] * w[n, k] with w float16 [n, k] (one row per output column).
struct HalfMatMulShape {
  int64_t m = 0;  // rows of activations
  int64_t k = 0;  // inner dimension
  int64_t n = 0;  // output columns (weight rows)
};

// Whether the shape is one this kernel computes (K and N in [1, 2^31), M >= 0); if not, why.
bool HalfShapeSupported(const HalfMatMulShape& shape, const char** why);

// The product above; `a` is [m, k] float32, `w` [n, k] float16 bits, `out` [m, n] float32.
void HalfMatMul(const HalfMatMulShape& shape, const float* a, const uint16_t* w, float* out, ParallelForFn parallel_for,
                void* parallel_context, RowKernels kernels = RowKernels::kBest);

}  // namespace silk
