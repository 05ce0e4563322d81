// SPDX-License-Identifier: MIT
// Model: a loaded model folder (model.json + encoder/decoder ONNX sessions). Immutable after
// Load and safe to share between threads; each concurrent generation needs its own Generator.
// onnxruntime stays out of this header (Impl in runtime/model/model_impl.h).
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "core/status.h"
#include "runtime/model/model_config.h"

namespace silk {

struct ModelLoadOptions {
  int threads = 0;  // intra-op threads of the process's shared pool (sized by the first
                    // model loaded); 0 = physical cores; ranges::Threads() bounds it
  // Decoder precision; unset = model.json's files.default_decoder. Error if the file is absent.
  std::optional<DecoderPrecision> decoder;
  // Self-K/V cache precision; unset = the model's (files.default_kv_precision when the chosen
  // decoder has that variant, else fp32). Error if the decoder has no variant of that precision.
  std::optional<KvPrecision> kv;
  bool allow_spinning = true;  // worker threads spin between ops (faster, burns CPU while idle)
};

class Model {
 public:
  struct Impl;
  static StatusOr<std::unique_ptr<Model>> Load(const std::string& dir, const ModelLoadOptions& options = {});
  ~Model();
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  const ModelConfig& config() const;
  int threads() const;                 // threads of the shared pool
  DecoderPrecision precision() const;  // the decoder in use
  KvPrecision kv_precision() const;    // its self-K/V cache's element type
  // The encoder graph's fixed point count (input "points" dimension 1); -1 when dynamic.
  int64_t encoder_points() const;
  Impl& impl() const { return *impl_; }

 private:
  explicit Model(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace silk
