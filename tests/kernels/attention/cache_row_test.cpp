// SPDX-License-Identifier: MIT
// The one KV row layout (kernels/attention/cache_row.h) as the model contract writes it: sizes per
// element type, and rows read back as floats (float16 against onnxruntime's own conversion, int8
// as value x the trailing scale).
#include "kernels/attention/cache_row.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include <onnxruntime_cxx_api.h>

namespace silk {
namespace {

TEST(CacheRow, SizesFollowTheContract) {
  EXPECT_EQ(CacheRowBytes(CacheElement::kFloat32, 64), 256u);
  EXPECT_EQ(CacheRowBytes(CacheElement::kFloat16, 64), 128u);
  EXPECT_EQ(CacheRowBytes(CacheElement::kInt8, 64), 68u);  // 64 values + a float32 scale
  EXPECT_EQ(CacheRowElements(CacheElement::kInt8, 64), 68);
  EXPECT_EQ(CacheRowElements(CacheElement::kFloat16, 64), 64);
}

TEST(CacheRow, RowsReadBackAsFloats) {
  const float values[4] = {1.5f, -0.25f, 3.0f, 0.0f};
  std::vector<unsigned char> row(CacheRowBytes(CacheElement::kFloat16, 4));
  for (int i = 0; i < 4; ++i) {
    const uint16_t bits = Ort::Float16_t(values[i]).val;
    std::memcpy(row.data() + 2 * i, &bits, 2);
  }
  float out[4];
  CacheRowToFloats(CacheElement::kFloat16, row.data(), 4, out);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(out[i], values[i]);

  const int8_t q[4] = {127, -64, 1, 0};
  const float scale = 0.5f;
  std::vector<unsigned char> int8_row(CacheRowBytes(CacheElement::kInt8, 4));
  std::memcpy(int8_row.data(), q, 4);
  std::memcpy(int8_row.data() + 4, &scale, 4);
  CacheRowToFloats(CacheElement::kInt8, int8_row.data(), 4, out);
  const float expected[4] = {63.5f, -32.0f, 0.5f, 0.0f};
  for (int i = 0; i < 4; ++i) EXPECT_EQ(out[i], expected[i]);

  std::vector<unsigned char> f32_row(CacheRowBytes(CacheElement::kFloat32, 4));
  std::memcpy(f32_row.data(), values, sizeof values);
  CacheRowToFloats(CacheElement::kFloat32, f32_row.data(), 4, out);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(out[i], values[i]);
}

}  // namespace
}  // namespace silk
