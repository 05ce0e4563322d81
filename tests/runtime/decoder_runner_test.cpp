// SPDX-License-Identifier: MIT
// The KV cache path: chunked feeding and one-at-a-time feeding must give the same cache contents
// and next-token logits, for every cache precision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "runtime/decoder_runner.h"
#include "runtime_test_util.h"

namespace silk {
namespace {

struct Fed {
  std::vector<float> logits, cache;
  int64_t calls = 0;
};

Fed FeedAll(const Model& model, const std::vector<int32_t>& ids, int64_t chunk) {
  auto cross = RunEncoder(model.impl(), testing::SamplePoints(model).data(), model.config().dims.n_points);
  EXPECT_TRUE(cross.ok());
  KvCache cache;
  EXPECT_TRUE(cache.Reserve(64, ModelKvShape(model.impl())).ok());
  DecoderRunner runner(model.impl(), &cache, cross->GetTensorMutableData<void>());
  for (size_t i = 0; i < ids.size(); i += chunk) {
    const int64_t n = std::min<int64_t>(chunk, ids.size() - i);
    Status s = runner.Feed(ids.data() + i, n);
    EXPECT_TRUE(s.ok()) << s.ToString();
  }
  Fed f;
  f.logits.assign(runner.last_logits(), runner.last_logits() + model.config().model_vocab_size);
  f.cache.resize(static_cast<size_t>(cache.length() * cache.shape().position_values()));
  cache.CopyTimeMajor(f.cache.data());
  f.calls = runner.calls();
  return f;
}

double MaxDiff(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, double(std::fabs(a[i] - b[i])));
  return d;
}

TEST(DecoderRunner, ChunkedEqualsStepwise) {
  auto model = testing::LoadTinyModel();
  ASSERT_TRUE(model);
  const std::vector<int32_t> ids = {10269, 0, 5835, 8758, 1, 6112, 9420, 220, 460, 5803, 8381, 352};
  const Fed step = FeedAll(*model, ids, 1);
  const Fed chunk = FeedAll(*model, ids, 5);
  const Fed whole = FeedAll(*model, ids, 12);
  EXPECT_EQ(step.calls, 12);
  EXPECT_EQ(chunk.calls, 3);
  EXPECT_EQ(whole.calls, 1);
  EXPECT_EQ(step.cache.size(), ids.size() * model->config().dims.kv_row_floats());
  EXPECT_LT(MaxDiff(step.logits, chunk.logits), 1e-4);
  EXPECT_LT(MaxDiff(step.logits, whole.logits), 1e-4);
  EXPECT_LT(MaxDiff(step.cache, whole.cache), 1e-4);
  // Positions matter: the logits after a different prefix differ clearly.
  std::vector<int32_t> other = ids;
  std::swap(other[2], other[5]);
  EXPECT_GT(MaxDiff(step.logits, FeedAll(*model, other, 1).logits), 1e-3);
}

// Tolerances of a cache variant against the fp32 cache on the tiny model.
struct VariantBounds {
  double chunked_logits;  // chunk of 12 against one at a time
  double cache_rel;       // max |cache - fp32 cache| / max |fp32 cache|
  double logits;          // max |logits - fp32 logits|
};

// A cache variant: chunked close to stepwise, the cache within its rounding of
// the fp32 run's (and not equal to it), the logits close, the greedy choice the same.
void ExpectVariantMatchesFp32(KvPrecision kv, int64_t row_bytes, const VariantBounds& bound) {
  auto model = testing::LoadTinyModel(1, kv);
  auto ref = testing::LoadTinyModel(1);
  ASSERT_TRUE(model && ref);
  EXPECT_EQ(ModelKvShape(model->impl()).row_bytes(), row_bytes);
  const std::vector<int32_t> ids = {10269, 0, 5835, 8758, 1, 6112, 9420, 220, 460, 5803, 8381, 352};
  const Fed step = FeedAll(*model, ids, 1);
  const Fed whole = FeedAll(*model, ids, 12);
  const Fed fp32 = FeedAll(*ref, ids, 1);
  EXPECT_LT(MaxDiff(step.logits, whole.logits), bound.chunked_logits);
  double scale = 0;
  for (float v : fp32.cache) scale = std::max(scale, double(std::fabs(v)));
  const double cache_diff = MaxDiff(step.cache, fp32.cache);
  EXPECT_GT(cache_diff, 0.0);  // it really is stored at the lower precision
  EXPECT_LT(cache_diff, scale * bound.cache_rel);
  EXPECT_LT(MaxDiff(step.logits, fp32.logits), bound.logits);
  const auto top = [](const std::vector<float>& v) { return std::max_element(v.begin(), v.end()) - v.begin(); };
  EXPECT_EQ(top(step.logits), top(fp32.logits));
  // A cache reserved for the fp32 rows is refused, not misread.
  auto cross = RunEncoder(model->impl(), testing::SamplePoints(*model).data(), model->config().dims.n_points);
  ASSERT_TRUE(cross.ok());
  KvCache wrong;
  ASSERT_TRUE(wrong.Reserve(4, ModelKvShape(ref->impl())).ok());
  DecoderRunner runner(model->impl(), &wrong, cross->GetTensorMutableData<void>());
  EXPECT_EQ(runner.Feed(ids.data(), 1).code(), StatusCode::kInvalidArgument);
}

// The fp16 self-K/V cache (decoder.kv16.onnx): float16 rounding (2^-11 relative).
TEST(DecoderRunner, Fp16CacheMatchesFp32) {
  auto dims = testing::LoadTinyModel(1)->config().dims;
  ExpectVariantMatchesFp32(KvPrecision::kFp16, 2 * dims.head_dim, {1e-2, 2e-3, 0.05});
}

// The int8 self-K/V cache (decoder.kv8.onnx, rows of int8 + a float32 scale): half a step is
// max|row| / 254; with the drift of earlier layers, within 2 % of the largest value.
TEST(DecoderRunner, Int8CacheMatchesFp32) {
  auto dims = testing::LoadTinyModel(1)->config().dims;
  ExpectVariantMatchesFp32(KvPrecision::kInt8, dims.head_dim + 4, {0.05, 0.02, 0.25});
}

TEST(DecoderRunner, RefusesOverflow) {
  auto model = testing::LoadTinyModel();
  ASSERT_TRUE(model);
  auto cross = RunEncoder(model->impl(), testing::SamplePoints(*model).data(), model->config().dims.n_points);
  ASSERT_TRUE(cross.ok());
  KvCache cache;
  ASSERT_TRUE(cache.Reserve(2, ModelKvShape(model->impl())).ok());
  DecoderRunner runner(model->impl(), &cache, cross->GetTensorMutableData<void>());
  const int32_t ids[3] = {10269, 0, 1};
  Status s = runner.Feed(ids, 3);
  EXPECT_EQ(s.code(), StatusCode::kLimitExceeded);
  EXPECT_EQ(cache.length(), 0);
}

// The silk-form cache variants take float16 cross K/V: RunEncoder gives the float32 encoder's
// output rounded to float16 (as onnxruntime rounds), in the contract's shape; fp32 stays float32.
TEST(Encoder, GivesFloat16CrossKvForTheSilkFormVariants) {
  auto ref = testing::LoadTinyModel(1);
  ASSERT_TRUE(ref);
  EXPECT_EQ(ref->impl().cross_type, ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT);
  const auto pts = testing::SamplePoints(*ref);
  auto full = RunEncoder(ref->impl(), pts.data(), ref->config().dims.n_points);
  ASSERT_TRUE(full.ok());
  for (KvPrecision kv : {KvPrecision::kFp16, KvPrecision::kInt8}) {
    auto model = testing::LoadTinyModel(1, kv);
    ASSERT_TRUE(model);
    EXPECT_EQ(model->impl().cross_type, ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16);
    auto half = RunEncoder(model->impl(), pts.data(), model->config().dims.n_points);
    ASSERT_TRUE(half.ok()) << half.status().ToString();
    const auto info = half->GetTensorTypeAndShapeInfo();
    ASSERT_EQ(info.GetElementType(), ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16);
    ASSERT_EQ(info.GetShape(), full->GetTensorTypeAndShapeInfo().GetShape());
    const float* f = full->GetTensorData<float>();
    const uint16_t* h = half->GetTensorData<uint16_t>();
    size_t differ = 0;
    for (size_t i = 0; i < info.GetElementCount(); ++i) differ += h[i] != Ort::Float16_t(f[i]).val;
    EXPECT_EQ(differ, 0u);
  }
}

TEST(Encoder, RejectsEmptyInputAndGivesContractShape) {
  auto model = testing::LoadTinyModel();
  ASSERT_TRUE(model);
  EXPECT_FALSE(RunEncoder(model->impl(), nullptr, 0).ok());
  const auto pts = testing::SamplePoints(*model);
  auto few = RunEncoder(model->impl(), pts.data(), 17);  // N is dynamic
  ASSERT_TRUE(few.ok()) << few.status().ToString();
  const ModelDims& d = model->config().dims;
  EXPECT_EQ(few->GetTensorTypeAndShapeInfo().GetShape(),
            (std::vector<int64_t>{d.n_layers, 2, d.n_heads, d.n_latents, d.head_dim}));
}

}  // namespace
}  // namespace silk
