// SPDX-License-Identifier: MIT
// The runtime's KV cache shape uses the kernels' row layout (kernels/attention/cache_row.h) for
// every KV precision: the bytes the cache allocates are the bytes the ai.silk kernels read.
#include "runtime/kv_cache.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

namespace silk {
namespace {

TEST(KvShape, RowsAreTheKernelsRows) {
  const KvPrecision precisions[] = {KvPrecision::kFp32, KvPrecision::kFp16, KvPrecision::kInt8};
  const int64_t expected_bytes[] = {4 * 24, 2 * 24, 24 + 4};
  for (int i = 0; i < 3; ++i) {
    const KvShape shape{2, 3, 24, precisions[i]};
    EXPECT_EQ(shape.row_bytes(), expected_bytes[i]);
    EXPECT_EQ(shape.row_dims(), precisions[i] == KvPrecision::kInt8 ? 28 : 24);
    EXPECT_EQ(shape.position_bytes(), 2 * 2 * 3 * expected_bytes[i]);
  }
}

TEST(KvShape, CopyTimeMajorReadsInt8RowsThroughTheLayout) {
  KvCache cache;
  const KvShape shape{1, 1, 2, KvPrecision::kInt8};
  ASSERT_TRUE(cache.Reserve(1, shape).ok());
  auto* row = static_cast<unsigned char*>(cache.block(0, 0));
  const int8_t q[2] = {10, -20};
  const float scale = 0.25f;
  std::memcpy(row, q, 2);
  std::memcpy(row + 2, &scale, 4);
  auto* value_row = static_cast<unsigned char*>(cache.block(0, 1));
  std::memcpy(value_row, q, 2);
  std::memcpy(value_row + 2, &scale, 4);
  cache.Extend(1);
  float out[4];
  cache.CopyTimeMajor(out);
  EXPECT_EQ(out[0], 2.5f);
  EXPECT_EQ(out[1], -5.0f);
  EXPECT_EQ(out[2], 2.5f);
}

}  // namespace
}  // namespace silk
