// SPDX-License-Identifier: MIT
// C API: the default model and generation params, written once for the builds with and without
// onnxruntime (a build without generation hands out the same defaults, then refuses the calls),
// with the 1.0 layouts earlier callers still bind to.
#include <cstring>

#include "capi/capi_internal.h"

namespace silk::capi {

// silk_model_default_params as libsilk 1.0 exported it (its struct ended before kv_precision): a
// caller built against 1.0 receives the 1.0 size by value, so it must keep getting that layout.
// On ELF it stays bound as silk_model_default_params@SILK_1.0 (engine/libsilk.map), the current
// one is @@SILK_1.1; elsewhere (no symbol versions) only the current one exists.
struct ModelParams10 {
  uint32_t struct_size;
  int32_t threads, decoder;
};
static_assert(sizeof(ModelParams10) == kSize10<silk_model_params>, "the 1.0 layout of silk_model_params");

// silk_generate_default_params as an earlier libsilk exported it: the current defaults cut to
// that release's size, struct_size included. The struct is returned in memory the caller provides
// (larger than 16 bytes), so bytes of the old size and alignment are that layout exactly.
template <size_t kSize>
struct alignas(silk_generate_params) GenerateParamsCut {
  unsigned char bytes[kSize];
};
template <size_t kSize>
GenerateParamsCut<kSize> CutGenerateDefaults() {
  silk_generate_params p = silk_generate_default_params();
  p.struct_size = static_cast<uint32_t>(kSize);
  GenerateParamsCut<kSize> old;
  std::memcpy(old.bytes, &p, kSize);
  return old;
}
// 1.0-1.2 (the struct ended before face_guidance, which 1.3 appended), bound as
// silk_generate_default_params@SILK_1.0; 1.3-1.4 (it ended before rows, which 1.5 appended),
// bound as @SILK_1.3. The current one is @@SILK_1.5.
using GenerateParams10 = GenerateParamsCut<kSize10<silk_generate_params>>;
using GenerateParams13 = GenerateParamsCut<kSize13<silk_generate_params>>;
static_assert(sizeof(GenerateParams13) == kSize13<silk_generate_params>, "the 1.3 layout of silk_generate_params");

}  // namespace silk::capi

extern "C" {

silk_model_params silk_model_default_params(void) {
  silk_model_params o;
  o.struct_size = sizeof(o);
  o.threads = 0;
  o.decoder = SILK_DECODER_DEFAULT;
  o.kv_precision = SILK_KV_DEFAULT;
  return o;
}

silk_batch_params silk_batch_default_params(void) {
  silk_batch_params p;
  std::memset(&p, 0, sizeof(p));
  p.struct_size = sizeof(p);
  p.parallel = 1;
  p.rows = SILK_MODEL_VALUE;
  return p;
}

silk_generate_params silk_generate_default_params(void) {
  silk_generate_params p;
  std::memset(&p, 0, sizeof(p));
  p.struct_size = sizeof(p);
  p.seed = 0;
  p.temperature = SILK_MODEL_VALUE;  // the model's (model.json "sampling")
  p.top_k = SILK_MODEL_VALUE;
  p.top_p = SILK_MODEL_VALUE;
  p.top_p_temperature = SILK_MODEL_VALUE;
  p.preprocessing = SILK_MODEL_VALUE;  // the model's (model.json "preprocessing")
  p.holes = SILK_HOLES_OFF;
  p.surface_tolerance = SILK_DEFAULT_SURFACE_TOLERANCE;
  p.candidates = SILK_MODEL_VALUE;
  p.orient = SILK_DEFAULT_ORIENT;
  p.face_guidance = SILK_MODEL_VALUE;  // the model's (model.json "sampling"), else libsilk's
  p.face_tolerance = SILK_MODEL_VALUE;
  p.rows = SILK_MODEL_VALUE;  // the model's (model.json "sampling.rows"), else libsilk's
  return p;
}

#if defined(__ELF__)
__attribute__((visibility("default"))) silk::capi::ModelParams10 capi_model_default_params_1_0(void) {
  return {sizeof(silk::capi::ModelParams10), 0, SILK_DECODER_DEFAULT};
}
__asm__(".symver capi_model_default_params_1_0,silk_model_default_params@SILK_1.0");

__attribute__((visibility("default"))) silk::capi::GenerateParams10 capi_generate_default_params_1_0(void) {
  return silk::capi::CutGenerateDefaults<sizeof(silk::capi::GenerateParams10)>();
}
__asm__(".symver capi_generate_default_params_1_0,silk_generate_default_params@SILK_1.0");

__attribute__((visibility("default"))) silk::capi::GenerateParams13 capi_generate_default_params_1_3(void) {
  return silk::capi::CutGenerateDefaults<sizeof(silk::capi::GenerateParams13)>();
}
__asm__(".symver capi_generate_default_params_1_3,silk_generate_default_params@SILK_1.3");
#endif

}  // extern "C"
