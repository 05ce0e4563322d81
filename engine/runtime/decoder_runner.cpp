// One decoder.onnx call per chunk of known tokens, with the per-layer cache blocks shared between
// past_* and present_* (or copied, in the baseline mode).
#include "runtime/decoder_runner.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace silk {

KvShape ModelKvShape(const ModelDims& dims) { return KvShape{dims.n_layers, dims.n_heads, dims.head_dim}; }

DecoderRunner::DecoderRunner(const Model::Impl& model, KvCache* cache, float* cross_kv, KvMode mode,
                             int64_t max_chunk)
    : model_(model), cache_(cache), cross_kv_(cross_kv), mode_(mode), max_chunk_(std::max<int64_t>(1, max_chunk)),
      vocab_(model.config.model_vocab_size),
      in_names_(DecoderInputNames(model.config.dims.n_layers)),
      out_names_(DecoderOutputNames(model.config.dims.n_layers)) {
  for (const std::string& s : in_names_) in_ptrs_.push_back(s.c_str());
  for (const std::string& s : out_names_) out_ptrs_.push_back(s.c_str());
}

Status DecoderRunner::Feed(const int32_t* ids, int64_t n) {
  if (n <= 0) return InvalidArgument("decoder: nothing to feed");
  const ModelDims& d = model_.config.dims;
  const KvShape& s = cache_->shape();
  if (s.layers != d.n_layers || s.heads != d.n_heads || s.head_dim != d.head_dim)
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
  const int64_t P = cache_->length(), C = cache_->capacity();
  const ModelDims& d = model_.config.dims;
  const int64_t L = d.n_layers, H = d.n_heads, D = d.head_dim, M = d.n_latents;
  ids_.resize(n);
  positions_.resize(n);
  for (int64_t i = 0; i < n; ++i) {
    ids_[i] = ids[i];
    positions_[i] = P + i;
  }
  int32_t seqlens_k = static_cast<int32_t>(P + n - 1), total = static_cast<int32_t>(P + n);
  if (logits_.size() < static_cast<size_t>(max_chunk_ * vocab_)) logits_.resize(max_chunk_ * vocab_);
  return OrtGuard("decoder", [&]() -> Status {
    const Ort::MemoryInfo& mem = model_.cpu_memory;
    const std::array<int64_t, 2> tok_shape = {1, n};
    const std::array<int64_t, 1> one = {1};
    const std::array<int64_t, 4> cache_shape = {1, H, mode_ == KvMode::kInPlace ? C : P, D};
    const std::array<int64_t, 4> cross_shape = {1, H, M, D};
    const std::array<int64_t, 3> logit_shape = {1, n, vocab_};
    std::vector<Ort::Value> inputs;
    inputs.reserve(in_names_.size());
    inputs.push_back(Ort::Value::CreateTensor<int64_t>(mem, ids_.data(), n, tok_shape.data(), 2));
    inputs.push_back(Ort::Value::CreateTensor<int64_t>(mem, positions_.data(), n, tok_shape.data(), 2));
    inputs.push_back(Ort::Value::CreateTensor<int32_t>(mem, &seqlens_k, 1, one.data(), 1));
    inputs.push_back(Ort::Value::CreateTensor<int32_t>(mem, &total, 1, nullptr, 0));
    std::vector<std::vector<float>> compact;  // kCopy: fresh prefix copies, [H, P, D] each
    for (int64_t l = 0; l < L; ++l)
      for (int kv = 0; kv < 2; ++kv) {
        float* past = cache_->block(l, kv);
        size_t count = static_cast<size_t>(H * C * D);
        if (mode_ == KvMode::kCopy) {
          compact.emplace_back(static_cast<size_t>(std::max<int64_t>(1, H * P * D)));
          for (int64_t h = 0; h < H; ++h)
            std::memcpy(compact.back().data() + h * P * D, past + h * C * D, static_cast<size_t>(P * D) * sizeof(float));
          past = compact.back().data();
          count = static_cast<size_t>(H * P * D);
        }
        inputs.push_back(Ort::Value::CreateTensor<float>(mem, past, count, cache_shape.data(), 4));
      }
    for (int64_t l = 0; l < L; ++l)
      for (int kv = 0; kv < 2; ++kv)
        inputs.push_back(Ort::Value::CreateTensor<float>(mem, cross_kv_ + (l * 2 + kv) * H * M * D,
                                                         static_cast<size_t>(H * M * D), cross_shape.data(), 4));
    if (mode_ == KvMode::kInPlace) {
      std::vector<Ort::Value> outputs;
      outputs.reserve(out_names_.size());
      outputs.push_back(Ort::Value::CreateTensor<float>(mem, logits_.data(), static_cast<size_t>(n * vocab_),
                                                        logit_shape.data(), 3));
      for (int64_t l = 0; l < L; ++l)
        for (int kv = 0; kv < 2; ++kv)
          outputs.push_back(Ort::Value::CreateTensor<float>(mem, cache_->block(l, kv), static_cast<size_t>(H * C * D),
                                                            cache_shape.data(), 4));
      model_.decoder->Run(Ort::RunOptions{nullptr}, in_ptrs_.data(), inputs.data(), inputs.size(), out_ptrs_.data(),
                          outputs.data(), outputs.size());
      last_logits_ = logits_.data() + (n - 1) * vocab_;
    } else {
      auto outs = model_.decoder->Run(Ort::RunOptions{nullptr}, in_ptrs_.data(), inputs.data(), inputs.size(),
                                      out_ptrs_.data(), out_ptrs_.size());
      for (int64_t l = 0; l < L; ++l)
        for (int kv = 0; kv < 2; ++kv) {
          const Ort::Value& present = outs[1 + l * 2 + kv];
          const std::vector<int64_t> shape = present.GetTensorTypeAndShapeInfo().GetShape();
          if (shape != std::vector<int64_t>{1, H, P + n, D})
            return InternalError("decoder: " + out_names_[1 + l * 2 + kv] + " has an unexpected shape");
          const float* src = present.GetTensorData<float>();
          for (int64_t h = 0; h < H; ++h)
            std::memcpy(cache_->block(l, kv) + (h * C + P) * D, src + (h * (P + n) + P) * D,
                        static_cast<size_t>(n * D) * sizeof(float));
        }
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
