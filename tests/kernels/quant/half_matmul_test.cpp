// SPDX-License-Identifier: MIT
// HalfMatMul (kernels/quant), the kernel behind the ai.silk op of the fp16/int8-cache decoders'
// logits head: against the product of the float16 weights (widened by onnxruntime's own
// conversion) in double precision, vectorized rows against scalar ones, every row-block split
// and tail length, non-finite inputs propagated.
#include "kernels/quant/half_matmul.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <onnxruntime_cxx_api.h>

namespace silk {
namespace {

struct Case {
  int64_t m, k, n;
};

void Serial(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = 0; i < count; ++i) work(state, i);
}
void Backwards(void*, void (*work)(void*, size_t), void* state, size_t count) {
  for (size_t i = count; i-- > 0;) work(state, i);
}

struct Operands {
  std::vector<float> a;
  std::vector<uint16_t> w;  // float16 bits, [n, k]
};

Operands Random(const Case& c, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  Operands o;
  for (int64_t i = 0; i < c.m * c.k; ++i) o.a.push_back(normal(rng));
  for (int64_t i = 0; i < c.n * c.k; ++i) o.w.push_back(Ort::Float16_t(0.05f * normal(rng)).val);
  return o;
}

std::vector<float> Multiply(const Case& c, const Operands& o, RowKernels kernels, ParallelForFn pool = Serial) {
  std::vector<float> out(static_cast<size_t>(c.m * c.n), std::numeric_limits<float>::quiet_NaN());
  HalfMatMul(HalfMatMulShape{c.m, c.k, c.n}, o.a.data(), o.w.data(), out.data(), pool, nullptr, kernels);
  return out;
}

// Each output within float32 summation error of the exact product: |error| <= k * 2^-23 * sum|a w|.
void ExpectExact(const Case& c, const Operands& o, const std::vector<float>& out) {
  for (int64_t m = 0; m < c.m; ++m)
    for (int64_t n = 0; n < c.n; ++n) {
      double exact = 0, magnitude = 0;
      for (int64_t i = 0; i < c.k; ++i) {
        const double p = double(o.a[m * c.k + i]) * Ort::Float16_t::FromBits(o.w[n * c.k + i]).ToFloat();
        exact += p, magnitude += std::fabs(p);
      }
      ASSERT_NEAR(out[m * c.n + n], exact, c.k * std::ldexp(magnitude, -23) + 1e-30) << "m " << m << " n " << n;
    }
}

const Case kCases[] = {{1, 1024, 600}, {3, 96, 513}, {2, 37, 5}, {1, 8, 1}, {4, 64, 257}};

TEST(HalfMatMul, MatchesTheFloat16WeightsProductWithEveryRowKernel) {
  for (const Case& c : kCases) {
    const Operands o = Random(c, static_cast<uint32_t>(c.k * 31 + c.n));
    for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) ExpectExact(c, o, Multiply(c, o, k));
  }
}

TEST(HalfMatMul, OrderOfParallelWorkIsIrrelevant) {
  const Case c{2, 1024, 1000};
  const Operands o = Random(c, 5);
  EXPECT_EQ(Multiply(c, o, RowKernels::kBest, Serial), Multiply(c, o, RowKernels::kBest, Backwards));
}

// Weight rows go eight at a time (one vector of horizontal sums; converted to float32 once for
// many activation rows up to K 1,024) and the rest one by one: every output must be bit for bit
// the one-row path's (a product of one weight row alone), so no model's logits move with N or M.
TEST(HalfMatMul, EightRowBlocksGiveEachOutputTheOneRowValue) {
  for (const Case& c : {Case{1, 1024, 19}, Case{5, 96, 17}, Case{3, 1056, 16}, Case{2, 37, 8}, Case{8, 1000, 24},
                        Case{8, 96, 41}, Case{4, 16, 9}, Case{7, 1024, 16}}) {
    const Operands o = Random(c, static_cast<uint32_t>(c.k + c.m));
    const std::vector<float> all = Multiply(c, o, RowKernels::kBest);
    for (int64_t n = 0; n < c.n; ++n) {
      const Case one{c.m, c.k, 1};
      Operands row{o.a, std::vector<uint16_t>(o.w.begin() + n * c.k, o.w.begin() + (n + 1) * c.k)};
      const std::vector<float> alone = Multiply(one, row, RowKernels::kBest);
      for (int64_t m = 0; m < c.m; ++m)
        ASSERT_EQ(0, std::memcmp(&all[static_cast<size_t>(m * c.n + n)], &alone[static_cast<size_t>(m)], 4))
            << "m " << m << " n " << n << " of " << c.m << "x" << c.k << "x" << c.n;
    }
  }
}

TEST(HalfMatMul, NonFiniteInputsPropagate) {
  const Case c{1, 64, 3};
  Operands o = Random(c, 9);
  o.a[5] = std::numeric_limits<float>::infinity();
  o.w[2 * 64 + 7] = Ort::Float16_t(std::numeric_limits<float>::quiet_NaN()).val;
  for (RowKernels k : {RowKernels::kBest, RowKernels::kScalar}) {
    const std::vector<float> out = Multiply(c, o, k);
    EXPECT_TRUE(std::isnan(out[2])) << "a NaN weight makes its column NaN";
    EXPECT_TRUE(std::isinf(out[0]) || std::isnan(out[0]));
  }
}

TEST(HalfMatMul, RefusesShapesOutOfRange) {
  const char* why = nullptr;
  EXPECT_FALSE(HalfShapeSupported(HalfMatMulShape{1, 0, 5}, &why));
  EXPECT_NE(why, nullptr);
  EXPECT_FALSE(HalfShapeSupported(HalfMatMulShape{1, 8, int64_t{1} << 31}, &why));
  EXPECT_TRUE(HalfShapeSupported(HalfMatMulShape{0, 8, 5}, &why));
  EXPECT_EQ(why, nullptr);
  std::vector<float> out(5, 1.0f);
  HalfMatMul(HalfMatMulShape{0, 8, 5}, nullptr, nullptr, out.data(), Serial,
             nullptr);  // no rows: nothing read or written
  EXPECT_EQ(out, std::vector<float>(5, 1.0f));
}

}  // namespace
}  // namespace silk
