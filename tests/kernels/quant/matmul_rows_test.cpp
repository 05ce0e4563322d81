// SPDX-License-Identifier: MIT
// Int4MatMul and HalfMatMul over a batch of activation rows (decoder contract v4: R sequences, or
// a chunk of positions, in one call that reads each weight once): every row's outputs must be
// bit for bit those of the same row multiplied alone, whatever the batch size, shape, block size
// and row kernels.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "kernels/quant/half_matmul.h"
#include "kernels/quant/int4_matmul.h"

namespace silk {
namespace {

void Backwards(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = count; i-- > 0;) work(state, i);
}

std::vector<float> Normal(size_t n, uint32_t seed, float sigma) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, sigma);
  std::vector<float> v(n);
  for (float& x : v) x = normal(rng);
  return v;
}

// The rows of `batch` ([rows, n]) bit for bit against `alone(r)` ([n]).
template <typename Alone>
void ExpectRowsAsAlone(const std::vector<float>& batch, int64_t rows, int64_t n, Alone alone, const char* what) {
  for (int64_t r = 0; r < rows; ++r) {
    const std::vector<float> one = alone(r);
    EXPECT_EQ(std::memcmp(batch.data() + r * n, one.data(), static_cast<size_t>(n) * 4), 0)
        << what << ": row " << r << " of " << rows << " differs from that row alone";
  }
}

TEST(MatMulRows, Int4EveryRowOfABatchIsBitIdenticalToItAlone) {
  struct Shape {
    int64_t k, n, block;
  };
  // block 32 (one scale per group), 64, 128 and 192 (one per block; 192: blocks of 16 group lanes
  // whose scales start mid-block), K = 32 mod 64 (the odd last group), group counts that are not a
  // multiple of 16 (the group lanes' masked last block: K 96, 4160, 32), N not a multiple of the
  // 256-row tile; 9 rows take two passes of the group-lane kernel.
  for (const Shape& sh :
       {Shape{1024, 300, 32}, Shape{256, 513, 64}, Shape{96, 40, 32}, Shape{384, 77, 128}, Shape{2048, 70, 32},
        Shape{4160, 9, 64}, Shape{32, 33, 32}, Shape{768, 20, 192}, Shape{64, 16, 32}, Shape{64, 16, 64}})
    for (int64_t rows : {2, 3, 4, 5, 8, 9})
      for (RowKernels kernels : {RowKernels::kBest, RowKernels::kAvx2, RowKernels::kScalar}) {
        std::mt19937 rng(static_cast<uint32_t>(sh.k + sh.n + rows));
        std::vector<uint8_t> packed(static_cast<size_t>(sh.n * sh.k / 2));
        for (uint8_t& b : packed) b = static_cast<uint8_t>(rng());
        std::vector<float> scales = Normal(static_cast<size_t>(sh.n * sh.k / sh.block), 5, 0.02f);
        const std::vector<float> a = Normal(static_cast<size_t>(rows * sh.k), static_cast<uint32_t>(rows), 2.0f);
        std::vector<float> out(static_cast<size_t>(rows * sh.n), NAN);
        Int4MatMul({rows, sh.k, sh.n, sh.block}, a.data(), packed.data(), scales.data(), out.data(), Backwards, nullptr,
                   kernels);
        ExpectRowsAsAlone(
            out, rows, sh.n,
            [&](int64_t r) {
              std::vector<float> one(static_cast<size_t>(sh.n), NAN);
              Int4MatMul({1, sh.k, sh.n, sh.block}, a.data() + r * sh.k, packed.data(), scales.data(), one.data(),
                         Backwards, nullptr, kernels);
              return one;
            },
            kernels == RowKernels::kBest   ? "Int4MatMul (best rows)"
            : kernels == RowKernels::kAvx2 ? "Int4MatMul (AVX2 rows)"
                                           : "Int4MatMul (scalar rows)");
      }
}

TEST(MatMulRows, HalfEveryRowOfABatchIsBitIdenticalToItAlone) {
  for (int64_t k : {1024, 40, 16})
    for (int64_t rows : {2, 5, 8})
      for (RowKernels kernels : {RowKernels::kBest, RowKernels::kAvx2, RowKernels::kScalar}) {
        const int64_t n = 300;
        std::vector<uint16_t> w(static_cast<size_t>(n * k));
        std::mt19937 rng(3);
        for (uint16_t& h : w) h = static_cast<uint16_t>(0x3000 + rng() % 0x1000) | (rng() % 2 ? 0x8000 : 0);
        const std::vector<float> a = Normal(static_cast<size_t>(rows * k), 9, 1.0f);
        std::vector<float> out(static_cast<size_t>(rows * n), NAN);
        HalfMatMul({rows, k, n}, a.data(), w.data(), out.data(), Backwards, nullptr, kernels);
        ExpectRowsAsAlone(
            out, rows, n,
            [&](int64_t r) {
              std::vector<float> one(static_cast<size_t>(n), NAN);
              HalfMatMul({1, k, n}, a.data() + r * k, w.data(), one.data(), Backwards, nullptr, kernels);
              return one;
            },
            "HalfMatMul");
      }
}

}  // namespace
}  // namespace silk
