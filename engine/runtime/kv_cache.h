// SPDX-License-Identifier: MIT
// KvCache: one pre-allocated self-attention cache for a whole generation, one head-major block
// [H, capacity, row] per layer and K/V (docs/model_contract.md), with rows as the decoder graph's
// past_*/present_* have them (KV precision): D float32, D float16, or D int8 + a float32 scale.
// decoder.onnx reads the prefix of each block in place and writes a chunk's new rows at P, so a
// step copies nothing.
#pragma once
#include <cstdint>
#include <memory>

#include "core/status.h"
#include "kernels/attention/cache_row.h"
#include "runtime/model/model_config.h"

namespace silk {

// The kernels' element type of a KV precision's cache rows.
inline CacheElement CacheElementOf(KvPrecision precision) {
  return precision == KvPrecision::kInt8   ? CacheElement::kInt8
         : precision == KvPrecision::kFp16 ? CacheElement::kFloat16
                                           : CacheElement::kFloat32;
}

struct KvShape {
  int64_t layers = 0, heads = 0, head_dim = 0;
  KvPrecision precision = KvPrecision::kFp32;
  // The kernels' row layout (kernels/attention/cache_row.h): the cache tensors' last dimension
  // (D, or D + 4 for int8 rows: D values, then the scale's bytes) and a row's bytes.
  CacheElement element() const { return CacheElementOf(precision); }
  int64_t row_dims() const { return CacheRowElements(element(), head_dim); }
  int64_t row_bytes() const { return static_cast<int64_t>(CacheRowBytes(element(), head_dim)); }
  int64_t position_bytes() const { return layers * 2 * heads * row_bytes(); }  // K+V of one position
  int64_t position_values() const { return layers * 2 * heads * head_dim; }    // as floats (CopyTimeMajor)
};

// The cache shape of a model's dims with a KV precision.
inline KvShape KvShapeOf(const ModelDims& d, KvPrecision precision) {
  return KvShape{d.n_layers, d.n_heads, d.head_dim, precision};
}

class KvCache {
 public:
  // Room for `capacity` positions (reuses the buffer when it is already big enough).
  Status Reserve(int64_t capacity, const KvShape& shape);
  void Clear() { length_ = 0; }

  int64_t capacity() const { return capacity_; }
  const KvShape& shape() const { return shape_; }
  int64_t length() const { return length_; }  // positions filled
  // The block of layer `layer`, keys (kv 0) or values (kv 1): [H, capacity] rows of
  // shape().row_bytes() bytes each.
  void* block(int64_t layer, int kv) { return data_.get() + (layer * 2 + kv) * block_bytes(); }
  const void* block(int64_t layer, int kv) const { return data_.get() + (layer * 2 + kv) * block_bytes(); }
  int64_t block_bytes() const { return shape_.heads * capacity_ * shape_.row_bytes(); }
  void Extend(int64_t n) { length_ += n; }
  // Forgets positions from n on (rewinding a generation; the rows are simply overwritten).
  void Truncate(int64_t n) {
    if (n >= 0 && n < length_) length_ = n;
  }
  // Copies positions [0, length) out as time-major float32 [length, L, 2, H, D] (tests,
  // diagnostics; float16 rows are widened exactly, int8 rows dequantized: value x scale).
  void CopyTimeMajor(float* out) const;
  int64_t bytes() const { return allocated_; }

 private:
  // Left uninitialised: pages are only touched (and counted in RSS) as positions fill.
  std::unique_ptr<unsigned char[]> data_;
  int64_t allocated_ = 0;  // bytes
  int64_t capacity_ = 0, length_ = 0;
  KvShape shape_;
};

}  // namespace silk
