// SPDX-License-Identifier: MIT
// ModelConfig: the model.json sidecar of a model folder (docs/model_contract.md), parsed and
// checked against the vocabulary this engine was built with, so a mismatched model is refused
// with a message instead of producing garbage.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/status.h"
#include "mesh/point_preprocessing.h"
#include "runtime/sampling/face_guide.h"
#include "runtime/sampling/generation_ranges.h"
#include "runtime/sampling/sampler.h"

namespace silk {

// 2: per-layer head-major self-attention caches shared between past_* and present_*
// (GroupQueryAttention); 1 had one time-major past_kv tensor and is refused (re-export it).
// 3: same graphs, plus arch, preprocessing, sampling, INT4 and external-data files in
// model.json (docs/model_contract.md); 2 still loads with the defaults of Silk's own model.
// 4: as 3, with the cache variants' decoders in contract v4 (R rows per call: new_positions and
// cross_source inputs); libsilk runs them with one row.
inline constexpr int32_t kOldestModelVersion = 2;
inline constexpr int32_t kSupportedModelVersion = 4;
inline constexpr int32_t kRowsModelVersion = 4;  // the first with decoder contract v4
// The report's one line on a folder older than kRowsModelVersion (how to get contract v4), else "".
std::string ModelVersionNote(int32_t model_version);

enum class ModelArch { kSilk, kOfficial };
enum class DecoderPrecision { kFp32, kInt8, kInt4 };
const char* DecoderPrecisionName(DecoderPrecision p);  // "fp32", "int8", "int4"
// Element type of the self-attention K/V cache (the decoder graph's past_*/present_*): each
// decoder file may have an fp16-cache and an int8-cache variant (model.json files.kv_fp16,
// files.kv_int8).
enum class KvPrecision { kFp32, kFp16, kInt8 };
const char* KvPrecisionName(KvPrecision p);  // "fp32", "fp16", "int8"
// Its model.json key, "kv_fp16" / "kv_int8" ("" for fp32, which is the decoder file itself).
const char* KvFilesKey(KvPrecision p);
// The silk-export command that adds that variant to a model folder, "kv16" / "kv8" ("" for fp32;
// export/silk_export/onnx/kv_precision.py KV_SUFFIXES, also the variant files' suffix).
const char* KvExportCommand(KvPrecision p);
// "fp32" / "fp16" / "int8" to the precision; false for anything else.
bool ParseKvPrecision(const std::string& name, KvPrecision* out);

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
  ModelArch arch = ModelArch::kSilk;
  ModelDims dims;
  PreprocessingParams preprocessing;  // v2: Silk's kind with the top-level normalize_bound
  SamplingParams sampling;            // defaults for silkgen / the C API (seed unused)
  // sampling.candidates: the best-of-N a caller gets when it leaves N to the model (1 when
  // absent; a small model can afford several, the release-size one cannot).
  int32_t candidates = 1;
  // sampling.rows: how many of best of N's candidates are decoded together, at most, when the
  // caller leaves it to the model (absent: unset, libsilk's kDefaultRows).
  std::optional<int32_t> rows;
  // sampling.face_guidance / sampling.face_tolerance: the face guidance a caller gets when it
  // leaves it to the model (absent: kDefaultFaceGuidance, kDefaultFaceTolerance).
  FaceGuidance face_guidance = kDefaultFaceGuidance;
  double face_tolerance = kDefaultFaceTolerance;
  // Relative to dir; int8/int4 may be "". external_data: files the ONNX graphs reference.
  std::string encoder_file, decoder_file, decoder_int8_file, decoder_int4_file;
  DecoderPrecision default_decoder = DecoderPrecision::kFp32;
  // files.kv_fp16 / files.kv_int8: the variant of each decoder with that cache ("" when absent),
  // indexed [KvPrecision][DecoderPrecision] (the fp32 row stays empty: that is the decoder file);
  // files.default_kv_precision (absent: fp32).
  std::string kv_files[3][3];
  KvPrecision default_kv = KvPrecision::kFp32;
  std::vector<std::string> external_data;
  std::string source_file, source_sha256, source_licence;  // "source" (optional)
  // The decoder file of a precision ("" when the model has none).
  const std::string& DecoderFile(DecoderPrecision p) const;
  // The decoder file of a precision with a cache precision ("" when the model has none).
  const std::string& DecoderFile(DecoderPrecision p, KvPrecision kv) const;
  // The model's KV precision for decoder p: default_kv when p has that variant, else fp32.
  KvPrecision DefaultKv(DecoderPrecision p) const;
};

// silkgen's sampling defaults before model.json carried them (v2 models keep them).
SamplingParams DefaultSamplingParams();

// Parses `json_text` (name used in messages) and checks format, versions and vocabulary.
StatusOr<ModelConfig> ParseModelConfig(const std::string& json_text, const std::string& name);
// Reads <dir>/model.json and checks that every file it names (external data included) exists.
StatusOr<ModelConfig> LoadModelConfig(const std::string& dir);

}  // namespace silk
