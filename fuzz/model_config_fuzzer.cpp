// libFuzzer target: arbitrary bytes as a model.json sidecar (ParseModelConfig). A model folder
// comes from users, so a parsed config must be one the runtime can size buffers from: every
// dimension positive and plausible, plain file names, a normalise bound in (0, 1].
#include <cstddef>
#include <cstdint>
#include <string>

#include "runtime/model_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto c = silk::ParseModelConfig(std::string(reinterpret_cast<const char*>(data), size), "fuzz/model.json");
  if (!c.ok()) {
    if (c.status().message().empty()) __builtin_trap();
    return 0;
  }
  const silk::ModelDims& d = c->dims;
  if (d.d_model <= 0 || d.n_layers <= 0 || d.n_heads <= 0 || d.head_dim <= 0 || d.n_latents <= 0 || d.n_points <= 0)
    __builtin_trap();
  if (d.head_dim % 8 != 0 || int64_t{d.d_model} != int64_t{d.n_heads} * d.head_dim || d.kv_row_floats() > (int64_t{1} << 26))
    __builtin_trap();
  if (!(c->normalize_bound > 0 && c->normalize_bound <= 1)) __builtin_trap();
  for (const std::string* f : {&c->encoder_file, &c->decoder_file, &c->decoder_int8_file})
    if (f->find('/') != std::string::npos || *f == "..") __builtin_trap();
  return 0;
}
