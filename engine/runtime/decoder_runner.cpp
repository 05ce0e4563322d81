// SPDX-License-Identifier: MIT
// One decoder.onnx call per chunk of known tokens, with the per-layer cache blocks shared between
// past_* and present_*.
#include "runtime/decoder_runner.h"

#include <algorithm>
#include <array>

namespace silk {

KvShape ModelKvShape(const Model::Impl& model) { return KvShapeOf(model.config.dims, model.kv_precision); }

DecoderRunner::DecoderRunner(const Model::Impl& model, KvCache* cache, void* cross_kv, int64_t max_chunk)
    : model_(model),
      cache_(cache),
      cross_kv_(cross_kv),
      max_chunk_(std::max<int64_t>(1, max_chunk)),
      vocab_(model.config.model_vocab_size),
      in_names_(DecoderInputNames(model.config.dims.n_layers, model.rows_contract)),
      out_names_(DecoderOutputNames(model.config.dims.n_layers)) {
  for (const std::string& s : in_names_) in_ptrs_.push_back(s.c_str());
  for (const std::string& s : out_names_) out_ptrs_.push_back(s.c_str());
}

Status DecoderRunner::Feed(const int32_t* ids, int64_t n) {
  if (n <= 0) return InvalidArgument("decoder: nothing to feed");
  const ModelDims& d = model_.config.dims;
  const KvShape& s = cache_->shape();
  if (s.layers != d.n_layers || s.heads != d.n_heads || s.head_dim != d.head_dim || s.precision != model_.kv_precision)
    return InvalidArgument("decoder: the KV cache was not reserved for this model's shape");
  if (cache_->length() + n > cache_->capacity())
    return LimitExceeded("decoder: " + std::to_string(cache_->length() + n) + " positions exceed the cache of " +
                         std::to_string(cache_->capacity()));
  for (int64_t done = 0; done < n;) {
    const int64_t t = std::min(max_chunk_, n - done);
    SILK_RETURN_IF_ERROR(RunChunk(ids + done, t));
    done += t;
  }
  return Status::Ok();
}

Status DecoderRunner::RunChunk(const int32_t* ids, int64_t n) {
  StageInputs(ids, n);
  return OrtGuard("decoder", [&]() -> Status {
    // Values 0..3 change every call; the per-layer cache and cross views (and the present
    // outputs over the same blocks) are made once and reused.
    if (in_values_.empty() || views_of_ != cache_->block(0, 0) || views_capacity_ != cache_->capacity()) MakeViews();
    BindChunkInputs(n);
    RunInPlace(n);
    cache_->Extend(n);
    ++calls_;
    return Status::Ok();
  });
}

// The chunk's ids and positions (after the cached prefix), the attention lengths, and room for
// max_chunk rows of logits.
void DecoderRunner::StageInputs(const int32_t* ids, int64_t n) {
  const int64_t P = cache_->length();
  ids_.resize(n);
  positions_.resize(n);
  for (int64_t i = 0; i < n; ++i) {
    ids_[i] = ids[i];
    positions_[i] = P + i;
  }
  seqlens_k_ = static_cast<int32_t>(P + n - 1);
  total_ = static_cast<int32_t>(P + n);
  new_positions_ = static_cast<int32_t>(n);
  if (logits_.size() < static_cast<size_t>(max_chunk_ * vocab_)) logits_.resize(max_chunk_ * vocab_);
}

// Inputs after the per-call ones (per layer: past key and value, then the cross views) and the
// present outputs over the same cache blocks; the per-call inputs and output 0 are placeholders.
void DecoderRunner::MakeViews() {
  const Ort::MemoryInfo& mem = model_.cpu_memory;
  const ModelDims& d = model_.config.dims;
  const int64_t C = cache_->capacity();
  const int64_t L = d.n_layers, H = d.n_heads, D = d.head_dim, M = d.n_latents;
  const KvShape& ks = cache_->shape();
  const std::array<int64_t, 4> cache_shape = {1, H, C, ks.row_dims()};
  const std::array<int64_t, 4> cross_shape = {1, H, M, D};
  views_of_ = cache_->block(0, 0);  // a re-reserved cache gets fresh views
  views_capacity_ = C;
  in_values_.clear();
  out_values_.clear();
  for (size_t i = 0; i < PerCallInputs(); ++i) in_values_.emplace_back(nullptr);
  out_values_.emplace_back(nullptr);
  const int64_t row = ks.row_bytes();
  const auto type = KvOnnxType(ks.precision);
  for (int64_t l = 0; l < L; ++l)
    for (int kv = 0; kv < 2; ++kv) {
      void* past = cache_->block(l, kv);
      const size_t bytes = static_cast<size_t>(H * C * row);
      out_values_.push_back(Ort::Value::CreateTensor(mem, past, bytes, cache_shape.data(), 4, type));
      in_values_.push_back(Ort::Value::CreateTensor(mem, past, bytes, cache_shape.data(), 4, type));
    }
  const bool half = model_.cross_type == ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16;
  const size_t cross_bytes = static_cast<size_t>(H * M * D) * (half ? 2 : 4);  // one layer's keys or values
  unsigned char* cross = static_cast<unsigned char*>(cross_kv_);
  for (int64_t l = 0; l < L; ++l)
    for (int kv = 0; kv < 2; ++kv)
      in_values_.push_back(Ort::Value::CreateTensor(mem, cross + (l * 2 + kv) * cross_bytes, cross_bytes,
                                                    cross_shape.data(), 4, model_.cross_type));
}

// Inputs 0..3: ids, positions, seqlens_k, total length (remade every call); contract v4's
// new_positions (n) and cross_source (0: the one mesh) for its one row.
void DecoderRunner::BindChunkInputs(int64_t n) {
  const Ort::MemoryInfo& mem = model_.cpu_memory;
  const std::array<int64_t, 2> tok_shape = {1, n};
  const std::array<int64_t, 1> one = {1};
  in_values_[0] = Ort::Value::CreateTensor<int64_t>(mem, ids_.data(), n, tok_shape.data(), 2);
  in_values_[1] = Ort::Value::CreateTensor<int64_t>(mem, positions_.data(), n, tok_shape.data(), 2);
  in_values_[2] = Ort::Value::CreateTensor<int32_t>(mem, &seqlens_k_, 1, one.data(), 1);
  in_values_[3] = Ort::Value::CreateTensor<int32_t>(mem, &total_, 1, nullptr, 0);
  if (!model_.rows_contract) return;
  in_values_[4] = Ort::Value::CreateTensor<int32_t>(mem, &new_positions_, 1, one.data(), 1);
  in_values_[5] = Ort::Value::CreateTensor<int32_t>(mem, &cross_source_, 1, one.data(), 1);
}

// Logits into logits_, present_* written straight into the cache blocks.
void DecoderRunner::RunInPlace(int64_t n) {
  const std::array<int64_t, 3> logit_shape = {1, n, vocab_};
  out_values_[0] = Ort::Value::CreateTensor<float>(model_.cpu_memory, logits_.data(), static_cast<size_t>(n * vocab_),
                                                   logit_shape.data(), 3);
  model_.decoder->Run(Ort::RunOptions{nullptr}, in_ptrs_.data(), in_values_.data(), in_values_.size(), out_ptrs_.data(),
                      out_values_.data(), out_values_.size());
  last_logits_ = logits_.data() + (n - 1) * vocab_;
}

}  // namespace silk
