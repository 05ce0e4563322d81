// DecoderRunner: feeds known tokens to decoder.onnx and keeps the KV cache. In kInPlace mode
// past_kv is a tensor over the cache prefix and new_kv is bound as an output at offset P
// (no copy, no allocation per step); kCopy is the naive baseline (fresh past_kv copy, ORT-
// allocated outputs copied back) kept for the measurement in docs/runtime.md.
#pragma once
#include <cstdint>
#include <vector>

#include "runtime/kv_cache.h"
#include "runtime/model_impl.h"

namespace silk {

enum class KvMode { kInPlace, kCopy };

class DecoderRunner {
 public:
  // `cross_kv` ([L, 2, H, M, D] floats from the encoder) must outlive the runner. `max_chunk` bounds the tokens per decoder call (the
  // logits buffer holds max_chunk rows).
  DecoderRunner(const Model::Impl& model, KvCache* cache, float* cross_kv, KvMode mode = KvMode::kInPlace,
                int64_t max_chunk = 256);

  // Feeds n ids at positions cache.length() .. +n-1 (BOS first, at position 0), in chunks.
  // Afterwards last_logits() holds the next-token logits after the last id.
  Status Feed(const int32_t* ids, int64_t n);
  const float* last_logits() const { return last_logits_; }
  int64_t calls() const { return calls_; }

 private:
  Status RunChunk(const int32_t* ids, int64_t n);

  const Model::Impl& model_;
  KvCache* cache_;
  float* cross_kv_;
  KvMode mode_;
  int64_t max_chunk_;
  int64_t vocab_;
  std::vector<int64_t> ids_, positions_;
  std::vector<float> logits_;     // [max_chunk, V] (kInPlace: the bound output)
  const float* last_logits_ = nullptr;
  int64_t calls_ = 0;
};

}  // namespace silk
