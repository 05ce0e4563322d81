// One decoder.onnx call per chunk of known tokens, with the cache bound in place (or copied,
// in the baseline mode).
#include "runtime/decoder_runner.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace silk {

DecoderRunner::DecoderRunner(const Model::Impl& model, KvCache* cache, float* cross_kv, KvMode mode,
                             int64_t max_chunk)
    : model_(model), cache_(cache), cross_kv_(cross_kv), mode_(mode), max_chunk_(std::max<int64_t>(1, max_chunk)),
      vocab_(model.config.model_vocab_size) {}

Status DecoderRunner::Feed(const int32_t* ids, int64_t n) {
  if (n <= 0) return InvalidArgument("decoder: nothing to feed");
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
  const int64_t P = cache_->length();
  const ModelDims& d = model_.config.dims;
  const int64_t row = cache_->row_floats();
  ids_.resize(n);
  positions_.resize(n);
  for (int64_t i = 0; i < n; ++i) {
    ids_[i] = ids[i];
    positions_[i] = P + i;
  }
  if (logits_.size() < static_cast<size_t>(max_chunk_ * vocab_)) logits_.resize(max_chunk_ * vocab_);
  return OrtGuard("decoder", [&]() -> Status {
    const Ort::MemoryInfo& mem = model_.cpu_memory;
    const std::array<int64_t, 2> tok_shape = {1, n};
    const std::array<int64_t, 5> past_shape = {P, d.n_layers, 2, d.n_heads, d.head_dim};
    const std::array<int64_t, 5> new_shape = {n, d.n_layers, 2, d.n_heads, d.head_dim};
    const std::array<int64_t, 3> logit_shape = {1, n, vocab_};
    const std::array<int64_t, 5> cross_shape = {d.n_layers, 2, d.n_heads, d.n_latents, d.head_dim};
    float* past_data = cache_->row(0);
    std::vector<float> past_copy;
    if (mode_ == KvMode::kCopy) {  // baseline: a freshly allocated copy of the prefix each call
      past_copy.assign(cache_->data(), cache_->data() + P * row);
      if (!past_copy.empty()) past_data = past_copy.data();
    }
    Ort::Value inputs[4] = {
        Ort::Value::CreateTensor<int64_t>(mem, ids_.data(), n, tok_shape.data(), tok_shape.size()),
        Ort::Value::CreateTensor<int64_t>(mem, positions_.data(), n, tok_shape.data(), tok_shape.size()),
        Ort::Value::CreateTensor<float>(mem, past_data, static_cast<size_t>(P * row), past_shape.data(),
                                        past_shape.size()),
        Ort::Value::CreateTensor<float>(mem, cross_kv_, static_cast<size_t>(d.cross_kv_floats()), cross_shape.data(),
                                        cross_shape.size())};
    static const char* in_names[] = {"input_ids", "positions", "past_kv", "cross_kv"};
    static const char* out_names[] = {"logits", "new_kv"};
    if (mode_ == KvMode::kInPlace) {
      Ort::Value outputs[2] = {
          Ort::Value::CreateTensor<float>(mem, logits_.data(), static_cast<size_t>(n * vocab_), logit_shape.data(),
                                          logit_shape.size()),
          Ort::Value::CreateTensor<float>(mem, cache_->row(P), static_cast<size_t>(n * row), new_shape.data(),
                                          new_shape.size())};
      model_.decoder->Run(Ort::RunOptions{nullptr}, in_names, inputs, 4, out_names, outputs, 2);
      last_logits_ = logits_.data() + (n - 1) * vocab_;
    } else {
      auto outs = model_.decoder->Run(Ort::RunOptions{nullptr}, in_names, inputs, 4, out_names, 2);
      std::memcpy(cache_->row(P), outs[1].GetTensorData<float>(), static_cast<size_t>(n * row) * sizeof(float));
      std::memcpy(logits_.data(), outs[0].GetTensorData<float>() + (n - 1) * vocab_,
                  static_cast<size_t>(vocab_) * sizeof(float));
      last_logits_ = logits_.data();
    }
    cache_->Extend(n);
    ++calls_;
    return Status::Ok();
  });
}

}  // namespace silk
