// SPDX-License-Identifier: MIT
// model.json parsing and the compatibility checks of docs/model_contract.md.
#include "runtime/model/model_config.h"

#include <cmath>
#include <cstdint>
#include <utility>

#include <nlohmann/json.hpp>

#include "io/files/file_bytes.h"
#include "io/files/file_system.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

using Json = nlohmann::json;

Status Bad(const std::string& name, const std::string& what) {
  return Status(StatusCode::kUnsupported, name + ": " + what);
}

// Reads an integer field, failing with a message naming it.
Status GetInt(const Json& obj, const char* key, const std::string& where, int32_t* out) {
  auto it = obj.find(key);
  if (it == obj.end() || !it->is_number_integer())
    return Status(StatusCode::kParseError, where + ": missing integer field '" + key + "'");
  const bool in_range = it->is_number_unsigned() ? it->get<uint64_t>() <= uint64_t{INT32_MAX}
                                                 : it->get<int64_t>() >= INT32_MIN && it->get<int64_t>() <= INT32_MAX;
  if (!in_range) return Status(StatusCode::kParseError, where + ": integer field '" + key + "' is out of range");
  *out = static_cast<int32_t>(it->get<int64_t>());
  return Status::Ok();
}

// Reads an optional string field (`fallback` when absent); any other type is an error (never
// an exception: this parser sees user files).
Status GetString(const Json& obj, const char* key, const std::string& where, const std::string& fallback,
                 std::string* out) {
  auto it = obj.find(key);
  if (it == obj.end()) {
    *out = fallback;
    return Status::Ok();
  }
  if (!it->is_string()) return Status(StatusCode::kParseError, where + ": field '" + key + "' is not a string");
  *out = it->get<std::string>();
  return Status::Ok();
}

// Reads an optional number field into *out (left unchanged when absent).
Status GetDouble(const Json& obj, const char* key, const std::string& where, double* out) {
  auto it = obj.find(key);
  if (it == obj.end()) return Status::Ok();
  if (!it->is_number()) return Status(StatusCode::kParseError, where + ": field '" + key + "' is not a number");
  *out = it->get<double>();
  if (!std::isfinite(*out)) return Status(StatusCode::kParseError, where + ": field '" + key + "' is not finite");
  return Status::Ok();
}

// Reads an optional integer field into *out (left unchanged when absent).
Status GetOptionalInt(const Json& obj, const char* key, const std::string& where, int32_t* out) {
  return obj.contains(key) ? GetInt(obj, key, where, out) : Status::Ok();
}

Status GetBool(const Json& obj, const char* key, const std::string& where, bool* out) {
  auto it = obj.find(key);
  if (it == obj.end()) return Status::Ok();
  if (!it->is_boolean()) return Status(StatusCode::kParseError, where + ": field '" + key + "' is not true/false");
  *out = it->get<bool>();
  return Status::Ok();
}

// The optional object `key`: nullptr when absent, an error when it is not an object.
Status GetObject(const Json& j, const char* key, const std::string& name, const Json** out) {
  *out = nullptr;
  auto it = j.find(key);
  if (it == j.end()) return Status::Ok();
  if (!it->is_object()) return Status(StatusCode::kParseError, name + ": '" + key + "' is not an object");
  *out = &*it;
  return Status::Ok();
}

Status CheckEqual(const std::string& name, const char* what, int64_t got, int64_t want) {
  if (got == want) return Status::Ok();
  return Bad(name, std::string(what) + " is " + std::to_string(got) + ", this engine needs " + std::to_string(want));
}

bool PlainName(const std::string& s) {
  return !s.empty() && s.find('/') == std::string::npos && s.find('\\') == std::string::npos && s != "." && s != "..";
}

Status ParseHeader(const Json& j, const std::string& name, ModelConfig* c) {
  std::string format, token_format, arch;
  SILK_RETURN_IF_ERROR(GetString(j, "format", name, "", &format));
  SILK_RETURN_IF_ERROR(GetString(j, "token_format", name, "", &token_format));
  SILK_RETURN_IF_ERROR(GetString(j, "config", name, "", &c->config_name));
  if (format != "silk-model") return Bad(name, "\"format\" is not \"silk-model\" (not a Silk model folder?)");
  SILK_RETURN_IF_ERROR(GetInt(j, "model_version", name, &c->model_version));
  if (c->model_version < kOldestModelVersion || c->model_version > kSupportedModelVersion)
    return Bad(name,
               "model_version " + std::to_string(c->model_version) + " is not supported (this engine reads " +
                   std::to_string(kOldestModelVersion) + " to " + std::to_string(kSupportedModelVersion) +
                   (c->model_version < kOldestModelVersion ? "; re-export the checkpoint with `silk-export export`)"
                                                           : "; a newer libsilk is needed)"));
  if (token_format != vocab::k_token_format)
    return Bad(name, std::string("token_format is not \"") + vocab::k_token_format + "\"");
  SILK_RETURN_IF_ERROR(GetInt(j, "token_format_version", name, &c->token_format_version));
  SILK_RETURN_IF_ERROR(
      CheckEqual(name, "token_format_version", c->token_format_version, vocab::k_token_format_version));
  SILK_RETURN_IF_ERROR(GetString(j, "arch", name, c->model_version >= 3 ? "" : "silk", &arch));
  if (arch == "silk")
    c->arch = ModelArch::kSilk;
  else if (arch == "official")
    c->arch = ModelArch::kOfficial;
  else
    return Bad(name, "arch \"" + arch + "\" is neither \"silk\" nor \"official\"");
  return Status::Ok();
}

Status ParseVocab(const Json& j, const std::string& name, ModelConfig* c) {
  auto v = j.find("vocab");
  if (v == j.end() || !v->is_object()) return Status(StatusCode::kParseError, name + ": missing object 'vocab'");
  int32_t fvs = 0;
  SILK_RETURN_IF_ERROR(GetInt(*v, "format_vocab_size", name + " vocab", &fvs));
  SILK_RETURN_IF_ERROR(GetInt(*v, "eos_id", name + " vocab", &c->eos_id));
  SILK_RETURN_IF_ERROR(GetInt(*v, "pad_id", name + " vocab", &c->pad_id));
  SILK_RETURN_IF_ERROR(GetInt(*v, "bos_id", name + " vocab", &c->bos_id));
  SILK_RETURN_IF_ERROR(GetInt(*v, "model_vocab_size", name + " vocab", &c->model_vocab_size));
  SILK_RETURN_IF_ERROR(GetInt(*v, "embedding_rows", name + " vocab", &c->embedding_rows));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.format_vocab_size", fvs, vocab::k_format_vocab_size));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.eos_id", c->eos_id, vocab::k_eos_id));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.pad_id", c->pad_id, vocab::k_pad_id));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.model_vocab_size", c->model_vocab_size, vocab::k_model_vocab_size));
  // BOS is the first id past the output vocabulary, an input-only embedding row.
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.bos_id", c->bos_id, vocab::k_model_vocab_size));
  return CheckEqual(name, "vocab.embedding_rows", c->embedding_rows, vocab::k_model_vocab_size + 1);
}

Status ParseDims(const Json& j, const std::string& name, ModelDims* m) {
  auto d = j.find("dims");
  if (d == j.end() || !d->is_object()) return Status(StatusCode::kParseError, name + ": missing object 'dims'");
  const std::string dn = name + " dims";
  SILK_RETURN_IF_ERROR(GetInt(*d, "d_model", dn, &m->d_model));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_layers", dn, &m->n_layers));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_heads", dn, &m->n_heads));
  SILK_RETURN_IF_ERROR(GetInt(*d, "head_dim", dn, &m->head_dim));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_latents", dn, &m->n_latents));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_points", dn, &m->n_points));
  SILK_RETURN_IF_ERROR(GetInt(*d, "max_seq_len", dn, &m->max_seq_len));
  if (m->d_model <= 0 || m->n_layers <= 0 || m->n_heads <= 0 || m->head_dim <= 0 || m->n_latents <= 0 ||
      m->n_points <= 0)
    return Status(StatusCode::kParseError, dn + ": every dimension must be positive");
  if (m->max_seq_len < kMinMeshTokens + 1)
    return Status(StatusCode::kParseError, dn + ": max_seq_len " + std::to_string(m->max_seq_len) +
                                               " leaves room for fewer ids than the smallest mesh (" +
                                               std::to_string(kMinMeshTokens) + " + BOS)");
  if (m->head_dim % 8 != 0)
    return Bad(name,
               "dims.head_dim " + std::to_string(m->head_dim) + " must be a multiple of 8 (docs/model_contract.md)");
  if (m->max_seq_len > vocab::k_max_seq_length + 1)
    return Bad(name, "dims.max_seq_len " + std::to_string(m->max_seq_len) + " exceeds the format's " +
                         std::to_string(vocab::k_max_seq_length) + " tokens + BOS");
  if (m->kv_row_floats() > (int64_t{1} << 26) || m->n_latents > (1 << 16) || m->n_points > (1 << 20))
    return Status(StatusCode::kLimitExceeded, dn + ": implausibly large key/value row, n_latents or n_points");
  return Status::Ok();
}

// "preprocessing" (v3; absent: the arch's own) or, in v2, Silk's kind with "normalize_bound".
Status ParsePreprocessing(const Json& j, const std::string& name, ModelConfig* c) {
  double bound = kDefaultNormalizeBound;
  SILK_RETURN_IF_ERROR(GetDouble(j, "normalize_bound", name, &bound));
  if (!(bound > 0 && bound <= 1)) return Status(StatusCode::kParseError, name + ": normalize_bound must be in (0, 1]");
  const Json* pp = nullptr;
  SILK_RETURN_IF_ERROR(GetObject(j, "preprocessing", name, &pp));
  PreprocessingParams& p = c->preprocessing;
  p = c->arch == ModelArch::kOfficial ? OfficialPreprocessing(c->dims.n_points)
                                      : SilkPreprocessing(bound, c->dims.n_points);
  if (!pp) return Status::Ok();
  const std::string where = name + " preprocessing";
  std::string kind;
  SILK_RETURN_IF_ERROR(GetString(*pp, "kind", where, PreprocessingKindName(p.kind), &kind));
  if (kind == "official")
    p = OfficialPreprocessing(c->dims.n_points);
  else if (kind == "silk")
    p = SilkPreprocessing(bound, c->dims.n_points);
  else
    return Bad(name, "preprocessing.kind \"" + kind + "\" is neither \"silk\" nor \"official\"");
  SILK_RETURN_IF_ERROR(GetDouble(*pp, "normalize_bound", where, &p.normalize_bound));
  SILK_RETURN_IF_ERROR(GetDouble(*pp, "merge_distance_fraction", where, &p.merge_distance_fraction));
  SILK_RETURN_IF_ERROR(GetOptionalInt(*pp, "surface_samples", where, &p.surface_samples));
  SILK_RETURN_IF_ERROR(GetBool(*pp, "round_float16", where, &p.round_float16));
  SILK_RETURN_IF_ERROR(GetOptionalInt(*pp, "n_points", where, &p.n_points));
  Status s = ValidatePreprocessing(p);
  if (!s.ok()) return Status(StatusCode::kParseError, name + ": " + s.message());
  if (p.n_points != c->dims.n_points)
    return Bad(name, "preprocessing.n_points " + std::to_string(p.n_points) + " differs from dims.n_points " +
                         std::to_string(c->dims.n_points));
  return Status::Ok();
}

// A model.json "sampling" value by the generation settings' one range table: a parse error
// "model.json: sampling.temperature 150 is not in [0, 100] (0 = greedy)".
Status SamplingSetting(const std::string& name, const SettingRange& range, double value) {
  const Status s = CheckSetting(range, value);
  return s.ok() ? s : Status(StatusCode::kParseError, name + ": sampling." + s.message());
}

Status ParseSampling(const Json& j, const std::string& name, ModelConfig* c) {
  SamplingParams* sp = &c->sampling;
  int32_t* candidates = &c->candidates;
  *sp = DefaultSamplingParams();
  *candidates = 1;
  c->rows.reset();
  const Json* o = nullptr;
  SILK_RETURN_IF_ERROR(GetObject(j, "sampling", name, &o));
  if (!o) return Status::Ok();
  const std::string where = name + " sampling";
  SILK_RETURN_IF_ERROR(GetDouble(*o, "temperature", where, &sp->temperature));
  SILK_RETURN_IF_ERROR(GetOptionalInt(*o, "top_k", where, &sp->top_k));
  SILK_RETURN_IF_ERROR(GetDouble(*o, "top_p", where, &sp->top_p));
  SILK_RETURN_IF_ERROR(GetDouble(*o, "top_p_temperature", where, &sp->top_p_temperature));
  SILK_RETURN_IF_ERROR(GetOptionalInt(*o, "candidates", where, candidates));
  if (o->contains("rows")) {
    int32_t rows = 0;
    SILK_RETURN_IF_ERROR(GetInt(*o, "rows", where, &rows));
    SILK_RETURN_IF_ERROR(SamplingSetting(name, ranges::kRows, rows));
    c->rows = rows;
  }
  for (const auto& [range, value] : {std::pair{ranges::kCandidates, double(*candidates)},
                                     {ranges::kTemperature, sp->temperature},
                                     {ranges::kTopK, double(sp->top_k)},
                                     {ranges::kTopP, sp->top_p},
                                     {ranges::kTopPTemperature, sp->top_p_temperature}})
    SILK_RETURN_IF_ERROR(SamplingSetting(name, range, value));
  return Status::Ok();
}

// sampling.face_guidance ("off", "hard", "soft") and sampling.face_tolerance (cells): the model's
// own face guidance (runtime/sampling/face_guide.h); absent: libsilk's measured defaults.
Status ParseFaceGuidance(const Json& j, const std::string& name, ModelConfig* c) {
  c->face_guidance = kDefaultFaceGuidance;
  c->face_tolerance = kDefaultFaceTolerance;
  const Json* o = nullptr;
  SILK_RETURN_IF_ERROR(GetObject(j, "sampling", name, &o));
  if (!o) return Status::Ok();
  const std::string where = name + " sampling";
  std::string mode;
  SILK_RETURN_IF_ERROR(GetString(*o, "face_guidance", where, FaceGuidanceName(c->face_guidance), &mode));
  if (!ParseFaceGuidanceName(mode, &c->face_guidance))
    return Status(StatusCode::kParseError, name + ": sampling.face_guidance \"" + mode + "\" is not off, hard or soft");
  SILK_RETURN_IF_ERROR(GetDouble(*o, "face_tolerance", where, &c->face_tolerance));
  return SamplingSetting(name, ranges::kFaceTolerance, c->face_tolerance);
}

// files.kv_fp16 / files.kv_int8 {"decoder": ..., "decoder_int8": ..., "decoder_int4": ...}: each
// the variant of the decoder of the same key, which must be given.
Status ParseKvVariant(const Json& f, const std::string& name, KvPrecision kv, ModelConfig* c) {
  const Json* obj = nullptr;
  const std::string key = KvFilesKey(kv);
  SILK_RETURN_IF_ERROR(GetObject(f, key.c_str(), name + " files", &obj));
  const char* keys[3] = {"decoder", "decoder_int8", "decoder_int4"};
  const DecoderPrecision precisions[3] = {DecoderPrecision::kFp32, DecoderPrecision::kInt8, DecoderPrecision::kInt4};
  for (int i = 0; obj && i < 3; ++i) {
    std::string& file = c->kv_files[static_cast<int>(kv)][static_cast<int>(precisions[i])];
    SILK_RETURN_IF_ERROR(GetString(*obj, keys[i], name + " files." + key, "", &file));
    if (file.empty()) continue;
    if (!PlainName(file))
      return Status(StatusCode::kParseError,
                    name + ": file names must be plain names inside the model folder ('" + file + "')");
    if (c->DecoderFile(precisions[i]).empty())
      return Bad(name, "files." + key + "." + keys[i] + " is given, but files." + keys[i] + " is not");
  }
  return Status::Ok();
}

// The variants, then files.default_kv_precision, which needs a variant of the default decoder.
Status ParseKvFiles(const Json& f, const std::string& name, ModelConfig* c) {
  for (KvPrecision kv : {KvPrecision::kFp16, KvPrecision::kInt8}) SILK_RETURN_IF_ERROR(ParseKvVariant(f, name, kv, c));
  std::string def;
  SILK_RETURN_IF_ERROR(GetString(f, "default_kv_precision", name + " files", "fp32", &def));
  if (!ParseKvPrecision(def, &c->default_kv))
    return Bad(name, "files.default_kv_precision \"" + def + "\" is not one of \"fp32\", \"fp16\", \"int8\"");
  if (c->default_kv != KvPrecision::kFp32 && c->DecoderFile(c->default_decoder, c->default_kv).empty())
    return Bad(name, "files.default_kv_precision is \"" + def + "\", but the default decoder has no files." +
                         KvFilesKey(c->default_kv) + " variant");
  return Status::Ok();
}

Status ParseFiles(const Json& j, const std::string& name, ModelConfig* c) {
  const Json* f = nullptr;
  SILK_RETURN_IF_ERROR(GetObject(j, "files", name, &f));
  c->encoder_file = "encoder.onnx";
  c->decoder_file = "decoder.onnx";
  if (!f) return Status::Ok();
  const std::string where = name + " files";
  std::string def;
  SILK_RETURN_IF_ERROR(GetString(*f, "encoder", where, "encoder.onnx", &c->encoder_file));
  SILK_RETURN_IF_ERROR(GetString(*f, "decoder", where, "decoder.onnx", &c->decoder_file));
  SILK_RETURN_IF_ERROR(GetString(*f, "decoder_int8", where, "", &c->decoder_int8_file));
  SILK_RETURN_IF_ERROR(GetString(*f, "decoder_int4", where, "", &c->decoder_int4_file));
  SILK_RETURN_IF_ERROR(GetString(*f, "default_decoder", where, "decoder", &def));
  auto ext = f->find("external_data");
  if (ext != f->end()) {
    if (!ext->is_array() || ext->size() > 256)
      return Status(StatusCode::kParseError, name + ": files.external_data is not an array of at most 256 names");
    for (const Json& e : *ext) {
      if (!e.is_string()) return Status(StatusCode::kParseError, name + ": files.external_data holds a non-string");
      c->external_data.push_back(e.get<std::string>());
    }
  }
  std::vector<const std::string*> names = {&c->encoder_file, &c->decoder_file};
  for (const std::string* s : {&c->decoder_int8_file, &c->decoder_int4_file})
    if (!s->empty()) names.push_back(s);
  for (const std::string& s : c->external_data) names.push_back(&s);
  for (const std::string* s : names)
    if (!PlainName(*s))
      return Status(StatusCode::kParseError,
                    name + ": file names must be plain names inside the model folder ('" + *s + "')");
  if (def == "decoder")
    c->default_decoder = DecoderPrecision::kFp32;
  else if (def == "decoder_int8")
    c->default_decoder = DecoderPrecision::kInt8;
  else if (def == "decoder_int4")
    c->default_decoder = DecoderPrecision::kInt4;
  else
    return Bad(name, "files.default_decoder \"" + def + "\" is not decoder, decoder_int8 or decoder_int4");
  if (c->DecoderFile(c->default_decoder).empty())
    return Bad(name, "files.default_decoder is \"" + def + "\", but files." + def + " is not given");
  return ParseKvFiles(*f, name, c);
}

Status ParseSource(const Json& j, const std::string& name, ModelConfig* c) {
  const Json* s = nullptr;
  SILK_RETURN_IF_ERROR(GetObject(j, "source", name, &s));
  if (!s) return Status::Ok();
  const std::string where = name + " source";
  SILK_RETURN_IF_ERROR(GetString(*s, "file", where, "", &c->source_file));
  SILK_RETURN_IF_ERROR(GetString(*s, "sha256", where, "", &c->source_sha256));
  return GetString(*s, "licence", where, "", &c->source_licence);
}

}  // namespace

const char* DecoderPrecisionName(DecoderPrecision p) {
  return p == DecoderPrecision::kInt8 ? "int8" : p == DecoderPrecision::kInt4 ? "int4" : "fp32";
}

const std::string& ModelConfig::DecoderFile(DecoderPrecision p) const {
  return p == DecoderPrecision::kInt8   ? decoder_int8_file
         : p == DecoderPrecision::kInt4 ? decoder_int4_file
                                        : decoder_file;
}

const char* KvPrecisionName(KvPrecision p) {
  return p == KvPrecision::kFp16 ? "fp16" : p == KvPrecision::kInt8 ? "int8" : "fp32";
}

const char* KvFilesKey(KvPrecision p) {
  return p == KvPrecision::kFp16 ? "kv_fp16" : p == KvPrecision::kInt8 ? "kv_int8" : "";
}

const char* KvExportCommand(KvPrecision p) {
  return p == KvPrecision::kFp16 ? "kv16" : p == KvPrecision::kInt8 ? "kv8" : "";
}

bool ParseKvPrecision(const std::string& name, KvPrecision* out) {
  for (KvPrecision p : {KvPrecision::kFp32, KvPrecision::kFp16, KvPrecision::kInt8})
    if (name == KvPrecisionName(p)) {
      *out = p;
      return true;
    }
  return false;
}

const std::string& ModelConfig::DecoderFile(DecoderPrecision p, KvPrecision kv) const {
  return kv == KvPrecision::kFp32 ? DecoderFile(p) : kv_files[static_cast<int>(kv)][static_cast<int>(p)];
}

KvPrecision ModelConfig::DefaultKv(DecoderPrecision p) const {
  return DecoderFile(p, default_kv).empty() ? KvPrecision::kFp32 : default_kv;
}

SamplingParams DefaultSamplingParams() {
  SamplingParams p;
  p.temperature = 0.5;
  p.top_k = 50;
  p.top_p = 1.0;
  p.top_p_temperature = 0;
  return p;
}

StatusOr<ModelConfig> ParseModelConfig(const std::string& json_text, const std::string& name) {
  Json j = Json::parse(json_text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return Status(StatusCode::kParseError, name + ": not a JSON object");
  ModelConfig c;
  SILK_RETURN_IF_ERROR(ParseHeader(j, name, &c));
  SILK_RETURN_IF_ERROR(ParseVocab(j, name, &c));
  SILK_RETURN_IF_ERROR(ParseDims(j, name, &c.dims));
  // Silk's own network has d_model = n_heads * head_dim; the official one's attention is wider.
  if (c.arch == ModelArch::kSilk && int64_t{c.dims.d_model} != int64_t{c.dims.n_heads} * c.dims.head_dim)
    return Bad(name, "dims.d_model must be n_heads * head_dim for arch \"silk\" (docs/model_contract.md)");
  SILK_RETURN_IF_ERROR(ParsePreprocessing(j, name, &c));
  SILK_RETURN_IF_ERROR(ParseSampling(j, name, &c));
  SILK_RETURN_IF_ERROR(ParseFaceGuidance(j, name, &c));
  SILK_RETURN_IF_ERROR(ParseFiles(j, name, &c));
  SILK_RETURN_IF_ERROR(ParseSource(j, name, &c));
  return c;
}

std::string ModelVersionNote(int32_t model_version) {
  if (model_version >= kRowsModelVersion) return "";
  return "model_version " + std::to_string(model_version) +
         ": decoder contract v3 (one row per call); `silk-export export` (or `silk-export import-official`) "
         "re-exports it as model_version 4 (R rows per call)";
}

StatusOr<ModelConfig> LoadModelConfig(const std::string& dir) {
  const std::string path = dir + "/model.json";
  SILK_ASSIGN_OR_RETURN(std::string text, ReadFileBytes(path, uint64_t{1} << 20));
  SILK_ASSIGN_OR_RETURN(ModelConfig c, ParseModelConfig(text, path));
  c.dir = dir;
  for (const std::string& f : c.external_data)
    if (!IsRegularFile(dir + "/" + f))
      return IoError(dir + "/" + f + ": missing (files.external_data in model.json names it)");
  return c;
}

}  // namespace silk
