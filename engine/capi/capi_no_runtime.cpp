// SPDX-License-Identifier: MIT
// C API generation entry points of a libsilk built without onnxruntime: they exist (the ABI is
// the same) and answer SILK_ERR_UNSUPPORTED.
#if !defined(SILK_HAVE_RUNTIME)
#include "capi/capi_internal.h"

namespace {
constexpr const char* kNoRuntime = "this libsilk was built without onnxruntime (no generation)";
silk_status NoRuntime() { return silk::capi::SetError(SILK_ERR_UNSUPPORTED, kNoRuntime); }
}  // namespace

extern "C" {

int32_t silk_generation_available(void) { return 0; }
silk_status silk_param_range(const char*, double*, double*, int32_t*) { return NoRuntime(); }
silk_status silk_param_check(const char*, double) { return NoRuntime(); }
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
// C API 1.5: best of N's candidates.
silk_status silk_generator_candidate_count(silk_generator*, int32_t* n) {
  if (n) *n = 0;
  return NoRuntime();
}
silk_status silk_generator_get_candidate(silk_generator*, int32_t, silk_candidate_info*) { return NoRuntime(); }
silk_status silk_generator_get_candidate_mesh(silk_generator*, int32_t, silk_mesh** out) {
  if (out) *out = nullptr;
  return NoRuntime();
}

silk_status silk_batch_create(const silk_model*, const silk_batch_params*, silk_batch** out) {
  if (out) *out = nullptr;
  return NoRuntime();
}
void silk_batch_destroy(silk_batch*) {}
silk_status silk_batch_add(silk_batch*, const silk_generate_input*, const silk_generate_params*, int32_t* index) {
  if (index) *index = -1;
  return NoRuntime();
}
silk_status silk_batch_close(silk_batch*) { return NoRuntime(); }
silk_status silk_batch_next(silk_batch*, int32_t* index, silk_mesh** mesh, silk_tokens** tokens, silk_generate_stats*) {
  if (index) *index = -1;
  if (mesh) *mesh = nullptr;
  if (tokens) *tokens = nullptr;
  return NoRuntime();
}
silk_status silk_batch_counts(silk_batch*, int32_t*, int32_t*) { return NoRuntime(); }
void silk_batch_cancel(silk_batch*) {}

}  // extern "C"
#endif
