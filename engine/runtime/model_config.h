// ModelConfig: the model.json sidecar of a model folder (docs/model_contract.md), parsed and
// checked against the vocabulary this engine was built with, so a mismatched model is refused
// with a message instead of producing garbage.
#pragma once
#include <cstdint>
#include <string>

#include "core/status.h"

namespace silk {

// 2: per-layer head-major self-attention caches shared between past_* and present_*
// (GroupQueryAttention); 1 had one time-major past_kv tensor and is refused (re-export it).
inline constexpr int32_t kSupportedModelVersion = 2;

// The fewest ids a complete mesh takes (one triangle with its layer ends and EOS); a smaller
// max_tokens or max_seq_len - 1 can only end in an empty mesh and is refused up front.
inline constexpr int32_t kMinMeshTokens = 14;

struct ModelDims {
  int32_t d_model = 0, n_layers = 0, n_heads = 0, head_dim = 0, n_latents = 0;
  int32_t n_points = 4096;
  int32_t max_seq_len = 0;  // BOS + tokens incl. EOS
  // Floats of one time step of the self-attention cache: n_layers * 2 * n_heads * head_dim.
  int64_t kv_row_floats() const { return int64_t{n_layers} * 2 * n_heads * head_dim; }
  int64_t cross_kv_floats() const { return int64_t{n_layers} * 2 * n_heads * n_latents * head_dim; }
};

struct ModelConfig {
  std::string dir;  // folder holding model.json
  std::string config_name;
  int32_t model_version = 0, token_format_version = 0;
  int32_t bos_id = 0, eos_id = 0, pad_id = 0, model_vocab_size = 0, embedding_rows = 0;
  ModelDims dims;
  double normalize_bound = 0.95;
  std::string encoder_file, decoder_file, decoder_int8_file;  // relative to dir; int8 may be ""
};

// Parses `json_text` (name used in messages) and checks format, versions and vocabulary.
StatusOr<ModelConfig> ParseModelConfig(const std::string& json_text, const std::string& name);
// Reads <dir>/model.json.
StatusOr<ModelConfig> LoadModelConfig(const std::string& dir);

}  // namespace silk
