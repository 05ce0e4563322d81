// SPDX-License-Identifier: MIT
// C API generation entry points of a libsilk built without onnxruntime: they exist (the ABI is
// the same) and answer SILK_ERR_UNSUPPORTED.
#if !defined(SILK_HAVE_RUNTIME)
#include <cstring>

#include "capi/capi_internal.h"

namespace {
constexpr const char* kNoRuntime = "this libsilk was built without onnxruntime (no generation)";
silk_status NoRuntime() { return silk::capi::SetError(SILK_ERR_UNSUPPORTED, kNoRuntime); }
}  // namespace

extern "C" {

int32_t silk_generation_available(void) { return 0; }
silk_model_params silk_model_default_params(void) {
  return silk_model_params{sizeof(silk_model_params), 0, SILK_DECODER_DEFAULT, SILK_KV_DEFAULT};
}
SILK_CAPI_MODEL_PARAMS_1_0
silk_generate_params silk_generate_default_params(void) {
  silk_generate_params p;
  std::memset(&p, 0, sizeof(p));
  p.struct_size = sizeof(p);
  p.temperature = SILK_MODEL_VALUE;
  p.top_k = SILK_MODEL_VALUE;
  p.top_p = SILK_MODEL_VALUE;
  p.top_p_temperature = SILK_MODEL_VALUE;
  p.preprocessing = SILK_MODEL_VALUE;
  p.surface_tolerance = SILK_DEFAULT_SURFACE_TOLERANCE;
  p.candidates = SILK_MODEL_VALUE;
  p.orient = SILK_DEFAULT_ORIENT;
  p.face_guidance = SILK_MODEL_VALUE;  // the model's (model.json "sampling"), else libsilk's
  p.face_tolerance = SILK_MODEL_VALUE;
  return p;
}
SILK_CAPI_GENERATE_PARAMS_1_0
silk_status silk_model_load(const char*, const silk_model_params*, silk_model** out) {
  if (out) *out = nullptr;
  return NoRuntime();
}
void silk_model_destroy(silk_model*) {}
silk_status silk_model_get_info(const silk_model*, silk_model_info*) { return NoRuntime(); }
silk_status silk_model_get_preprocess_params(const silk_model*, silk_preprocess_params*) { return NoRuntime(); }
silk_status silk_generator_create(const silk_model*, silk_generator** out) {
  if (out) *out = nullptr;
  return NoRuntime();
}
void silk_generator_destroy(silk_generator*) {}
silk_status silk_generator_start(silk_generator*, const silk_generate_input*, const silk_generate_params*) {
  return NoRuntime();
}
silk_status silk_generator_advance(silk_generator*, int32_t, int32_t, int32_t* done) {
  if (done) *done = 0;
  return NoRuntime();
}
void silk_generator_cancel(silk_generator*) {}
silk_status silk_generator_get_tokens(silk_generator*, silk_tokens** out) {
  if (out) *out = nullptr;
  return NoRuntime();
}
silk_status silk_generator_get_mesh(silk_generator*, silk_mesh** out) {
  if (out) *out = nullptr;
  return NoRuntime();
}
silk_status silk_generator_get_stats(silk_generator*, silk_generate_stats*) { return NoRuntime(); }
silk_status silk_generator_finish(silk_generator*, silk_mesh** m, silk_tokens**, silk_generate_stats*) {
  if (m) *m = nullptr;
  return NoRuntime();
}
silk_status silk_generator_report(silk_generator*, int32_t, silk_report** out) {
  if (out) *out = nullptr;
  return NoRuntime();
}
silk_status silk_generator_copy_points(silk_generator*, double*, size_t, size_t* out_count) {
  if (out_count) *out_count = 0;
  return NoRuntime();
}
silk_status silk_generator_run(silk_generator*, const silk_generate_input*, const silk_generate_params*, silk_mesh** m,
                               silk_tokens** t, silk_generate_stats*) {
  if (m) *m = nullptr;
  if (t) *t = nullptr;
  return NoRuntime();
}

}  // extern "C"
#endif
