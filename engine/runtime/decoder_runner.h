// SPDX-License-Identifier: MIT
// DecoderRunner: feeds known tokens to decoder.onnx and keeps the KV cache. Each layer's
// past_key/past_value is a tensor over its whole cache block and present_* is bound to the same
// memory, so the attention reads the prefix in place and writes only the new rows (no copy, no
// allocation per step).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/kv_cache.h"
#include "runtime/model/model_impl.h"

namespace silk {

// The most known ids one decoder call takes per sequence (longer runs go in chunks of this many);
// DecoderRunner and RowsDecoder alike, so a row is fed exactly as it is alone.
inline constexpr int64_t kDecoderChunk = 256;

class DecoderRunner {
 public:
  // `cross_kv` ([L, 2, H, M, D] of the model's cross_type, from RunEncoder) must outlive the
  // runner; each layer's cross_key/cross_value input is a view into it. The cache must have been reserved with the
  // model's KvShape. `max_chunk` bounds the tokens per decoder call (the logits buffer holds
  // max_chunk rows).
  DecoderRunner(const Model::Impl& model, KvCache* cache, void* cross_kv, int64_t max_chunk = kDecoderChunk);

  // Feeds n ids at positions cache.length() .. +n-1 (BOS first, at position 0), in chunks.
  // Afterwards last_logits() holds the next-token logits after the last id.
  Status Feed(const int32_t* ids, int64_t n);
  const float* last_logits() const { return last_logits_; }
  int64_t calls() const { return calls_; }

 private:
  Status RunChunk(const int32_t* ids, int64_t n);
  // RunChunk's phases: stage the chunk, (re)make the cache views, bind the per-call inputs, run.
  void StageInputs(const int32_t* ids, int64_t n);
  void MakeViews();
  void BindChunkInputs(int64_t n);
  void RunInPlace(int64_t n);
  size_t PerCallInputs() const { return model_.rows_contract ? 6 : 4; }

  const Model::Impl& model_;
  KvCache* cache_;
  void* cross_kv_;
  int64_t max_chunk_;
  int64_t vocab_;
  std::vector<std::string> in_names_, out_names_;
  std::vector<const char*> in_ptrs_, out_ptrs_;
  std::vector<int64_t> ids_, positions_;
  int32_t seqlens_k_ = 0, total_ = 0, new_positions_ = 0, cross_source_ = 0;
  // Tensors over ids_/positions_/seqlens_k_/total_ (and new_positions_/cross_source_; remade per call), then the
  // per-layer cache and cross views; out: logits, then the present views over the same cache blocks. The views are
  // built once (again if the cache is re-reserved); the cross buffer must stay where it is for the runner's life.
  std::vector<Ort::Value> in_values_, out_values_;
  const void* views_of_ = nullptr;
  int64_t views_capacity_ = 0;
  std::vector<float> logits_;  // [max_chunk, V], the bound output
  const float* last_logits_ = nullptr;
  int64_t calls_ = 0;
};

// The loaded model's cache shape (layers, heads, head width, element size of its KV precision).
KvShape ModelKvShape(const Model::Impl& model);

}  // namespace silk
