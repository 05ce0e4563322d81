// SPDX-License-Identifier: MIT
// libFuzzer target: arbitrary bytes as a model.json sidecar (ParseModelConfig). A model folder
// comes from users, so a parsed config must be one the runtime can size buffers from: every
// dimension positive and plausible, plain file names, valid pre-processing and sampling
// defaults, a default decoder that names a file.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/model/model_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto c = silk::ParseModelConfig(std::string(reinterpret_cast<const char*>(data), size), "fuzz/model.json");
  if (!c.ok()) {
    if (c.status().message().empty()) __builtin_trap();
    return 0;
  }
  const silk::ModelDims& d = c->dims;
  if (d.d_model <= 0 || d.n_layers <= 0 || d.n_heads <= 0 || d.head_dim <= 0 || d.n_latents <= 0 || d.n_points <= 0)
    __builtin_trap();
  if (d.head_dim % 8 != 0 || d.kv_row_floats() > (int64_t{1} << 26)) __builtin_trap();
  if (c->arch == silk::ModelArch::kSilk && int64_t{d.d_model} != int64_t{d.n_heads} * d.head_dim) __builtin_trap();
  if (!ValidatePreprocessing(c->preprocessing).ok() || c->preprocessing.n_points != d.n_points) __builtin_trap();
  const silk::SamplingParams& s = c->sampling;
  if (!(s.temperature >= 0 && s.top_k >= 0 && s.top_p > 0 && s.top_p <= 1 && s.top_p_temperature >= 0))
    __builtin_trap();
  if (c->DecoderFile(c->default_decoder).empty()) __builtin_trap();
  std::vector<const std::string*> files = {&c->encoder_file, &c->decoder_file, &c->decoder_int8_file,
                                           &c->decoder_int4_file};
  for (const std::string& f : c->external_data) files.push_back(&f);
  for (const std::string* f : files)
    if (f->find('/') != std::string::npos || *f == "..") __builtin_trap();
  return 0;
}
