// SPDX-License-Identifier: MIT
// Matrix product with 4-bit weights, the decoder's largest cost per id: onnxruntime 1.22's
// MatMulNBits streams the release network's INT4 weights at about two thirds of this machine's
// read bandwidth for one row of activations; this kernel (the ai.silk Int4MatMul op,
// docs/model_contract.md) reads each weight byte once, at memory speed, with the same weights.
#pragma once
#include <cstddef>
#include <cstdint>

#include "kernels/cpu/cpu_kernels.h"

namespace silk {

// Activations are quantized to int8 in groups of this many (onnxruntime's accuracy level 4 does
// the same per weight block; a group never spans two weight blocks).
constexpr int64_t kInt4ActivationGroup = 32;

// out[m, n] = sum_k a[m, k] * w[n, k], with w[n, k] = (q[n, k] - 8) * scales[n, k / block]:
// MatMulNBits' layout for bits 4 without zero points. q is packed [n, k / block, block / 2]
// bytes, element 2i of a block in the low nibble of byte i and 2i + 1 in the high one.
struct Int4MatMulShape {
  int64_t m = 0;       // rows of activations (each batch row's new positions)
  int64_t k = 0;       // inner dimension, a multiple of block
  int64_t n = 0;       // output columns (weight rows)
  int64_t block = 32;  // weights per scale: 32 or a multiple of 64
};

// Whether the shape is one this kernel computes; if not, why (for the op's error message).
bool Int4ShapeSupported(const Int4MatMulShape& shape, const char** why);

// Activation row `a` (k values, a multiple of kInt4ActivationGroup) as Int4MatMul quantizes it:
// values[i] = nearest even of a[i] * 127 / max|group|, clamped to [-127, 127], NaN -> 0, and
// scales[g] = max|group g| / 127 (NaN ignored). kBest and kScalar give the same bytes.
void QuantizeInt4Activations(const float* a, int64_t k, int8_t* values, float* scales,
                             RowKernels kernels = RowKernels::kBest);

// The product above; `a` is [m, k] float32, `out` [m, n]. The caller checked the shape.
void Int4MatMul(const Int4MatMulShape& shape, const float* a, const uint8_t* packed, const float* scales, float* out,
                ParallelForFn parallel_for, void* parallel_context, RowKernels kernels = RowKernels::kBest);

}  // namespace silk
