// model.json parsing and the compatibility checks of docs/model_contract.md.
#include "runtime/model_config.h"

#include <cstdint>

#include <nlohmann/json.hpp>

#include "io/file_bytes.h"
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

Status CheckEqual(const std::string& name, const char* what, int64_t got, int64_t want) {
  if (got == want) return Status::Ok();
  return Bad(name, std::string(what) + " is " + std::to_string(got) + ", this engine needs " + std::to_string(want));
}

}  // namespace

StatusOr<ModelConfig> ParseModelConfig(const std::string& json_text, const std::string& name) {
  Json j = Json::parse(json_text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return Status(StatusCode::kParseError, name + ": not a JSON object");
  ModelConfig c;
  std::string format, token_format;
  SILK_RETURN_IF_ERROR(GetString(j, "format", name, "", &format));
  SILK_RETURN_IF_ERROR(GetString(j, "token_format", name, "", &token_format));
  SILK_RETURN_IF_ERROR(GetString(j, "config", name, "", &c.config_name));
  if (format != "silk-model")
    return Bad(name, "\"format\" is not \"silk-model\" (not a Silk model folder?)");
  SILK_RETURN_IF_ERROR(GetInt(j, "model_version", name, &c.model_version));
  if (c.model_version != kSupportedModelVersion)
    return Bad(name, "model_version " + std::to_string(c.model_version) + " is not supported (this engine reads " +
                         std::to_string(kSupportedModelVersion) +
                         (c.model_version < kSupportedModelVersion ? "; re-export the checkpoint with `silk-export export`)"
                                                                   : "; a newer libsilk is needed)"));
  if (token_format != vocab::k_token_format)
    return Bad(name, std::string("token_format is not \"") + vocab::k_token_format + "\"");
  SILK_RETURN_IF_ERROR(GetInt(j, "token_format_version", name, &c.token_format_version));
  SILK_RETURN_IF_ERROR(
      CheckEqual(name, "token_format_version", c.token_format_version, vocab::k_token_format_version));

  auto v = j.find("vocab");
  if (v == j.end() || !v->is_object()) return Status(StatusCode::kParseError, name + ": missing object 'vocab'");
  int32_t fvs = 0;
  SILK_RETURN_IF_ERROR(GetInt(*v, "format_vocab_size", name + " vocab", &fvs));
  SILK_RETURN_IF_ERROR(GetInt(*v, "eos_id", name + " vocab", &c.eos_id));
  SILK_RETURN_IF_ERROR(GetInt(*v, "pad_id", name + " vocab", &c.pad_id));
  SILK_RETURN_IF_ERROR(GetInt(*v, "bos_id", name + " vocab", &c.bos_id));
  SILK_RETURN_IF_ERROR(GetInt(*v, "model_vocab_size", name + " vocab", &c.model_vocab_size));
  SILK_RETURN_IF_ERROR(GetInt(*v, "embedding_rows", name + " vocab", &c.embedding_rows));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.format_vocab_size", fvs, vocab::k_format_vocab_size));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.eos_id", c.eos_id, vocab::k_eos_id));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.pad_id", c.pad_id, vocab::k_pad_id));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.model_vocab_size", c.model_vocab_size, vocab::k_model_vocab_size));
  // BOS is the first id past the output vocabulary, an input-only embedding row.
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.bos_id", c.bos_id, vocab::k_model_vocab_size));
  SILK_RETURN_IF_ERROR(CheckEqual(name, "vocab.embedding_rows", c.embedding_rows, vocab::k_model_vocab_size + 1));

  auto d = j.find("dims");
  if (d == j.end() || !d->is_object()) return Status(StatusCode::kParseError, name + ": missing object 'dims'");
  const std::string dn = name + " dims";
  SILK_RETURN_IF_ERROR(GetInt(*d, "d_model", dn, &c.dims.d_model));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_layers", dn, &c.dims.n_layers));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_heads", dn, &c.dims.n_heads));
  SILK_RETURN_IF_ERROR(GetInt(*d, "head_dim", dn, &c.dims.head_dim));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_latents", dn, &c.dims.n_latents));
  SILK_RETURN_IF_ERROR(GetInt(*d, "n_points", dn, &c.dims.n_points));
  SILK_RETURN_IF_ERROR(GetInt(*d, "max_seq_len", dn, &c.dims.max_seq_len));
  const ModelDims& m = c.dims;
  if (m.d_model <= 0 || m.n_layers <= 0 || m.n_heads <= 0 || m.head_dim <= 0 || m.n_latents <= 0 ||
      m.n_points <= 0)
    return Status(StatusCode::kParseError, dn + ": every dimension must be positive");
  if (m.max_seq_len < kMinMeshTokens + 1)
    return Status(StatusCode::kParseError, dn + ": max_seq_len " + std::to_string(m.max_seq_len) +
                                               " leaves room for fewer ids than the smallest mesh (" +
                                               std::to_string(kMinMeshTokens) + " + BOS)");
  if (m.head_dim % 8 != 0 || int64_t{m.d_model} != int64_t{m.n_heads} * m.head_dim)
    return Bad(name, "dims.head_dim " + std::to_string(m.head_dim) +
                         " must be a multiple of 8 and d_model = n_heads * head_dim (docs/model_contract.md)");
  if (m.max_seq_len > vocab::k_max_seq_length + 1)
    return Bad(name, "dims.max_seq_len " + std::to_string(m.max_seq_len) + " exceeds the format's " +
                         std::to_string(vocab::k_max_seq_length) + " tokens + BOS");
  if (m.kv_row_floats() > (int64_t{1} << 26))
    return Status(StatusCode::kLimitExceeded, dn + ": implausibly large key/value row");

  auto b = j.find("normalize_bound");
  if (b != j.end()) {
    if (!b->is_number()) return Status(StatusCode::kParseError, name + ": normalize_bound is not a number");
    c.normalize_bound = b->get<double>();
    if (!(c.normalize_bound > 0 && c.normalize_bound <= 1))
      return Status(StatusCode::kParseError, name + ": normalize_bound must be in (0, 1]");
  }
  auto f = j.find("files");
  c.encoder_file = "encoder.onnx";
  c.decoder_file = "decoder.onnx";
  if (f != j.end()) {
    if (!f->is_object()) return Status(StatusCode::kParseError, name + ": 'files' is not an object");
    SILK_RETURN_IF_ERROR(GetString(*f, "encoder", name + " files", "encoder.onnx", &c.encoder_file));
    SILK_RETURN_IF_ERROR(GetString(*f, "decoder", name + " files", "decoder.onnx", &c.decoder_file));
    SILK_RETURN_IF_ERROR(GetString(*f, "decoder_int8", name + " files", "", &c.decoder_int8_file));
  }
  for (const std::string* s : {&c.encoder_file, &c.decoder_file, &c.decoder_int8_file})
    if (s->find('/') != std::string::npos || s->find('\\') != std::string::npos || *s == "..")
      return Status(StatusCode::kParseError, name + ": file names must be plain names inside the model folder");
  return c;
}

StatusOr<ModelConfig> LoadModelConfig(const std::string& dir) {
  const std::string path = dir + "/model.json";
  SILK_ASSIGN_OR_RETURN(std::string text, ReadFileBytes(path, uint64_t{1} << 20));
  SILK_ASSIGN_OR_RETURN(ModelConfig c, ParseModelConfig(text, path));
  c.dir = dir;
  return c;
}

}  // namespace silk
