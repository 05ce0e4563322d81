// C API: model loading and information. The handle shares the Model with its generators.
#if defined(SILK_HAVE_RUNTIME)
#include <cstring>
#include <memory>

#include "capi/capi_generator.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

extern "C" {

int32_t silk_generation_available(void) { return 1; }

silk_model_options silk_model_default_options(void) {
  silk_model_options o;
  o.threads = 0;
  o.decoder = SILK_DECODER_DEFAULT;
  return o;
}

silk_status silk_model_load(const char* dir, const silk_model_options* options, silk_model** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_model_load: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(dir, "silk_model_load: dir is NULL");
    const silk_model_options o = options ? *options : silk_model_default_options();
    SILK_CAPI_CHECK("silk_model_load", silk::capi::CheckEnum("decoder", o.decoder, SILK_DECODER_DEFAULT, SILK_DECODER_INT4,
                                                             "silk_decoder_precision"));
    silk::ModelLoadOptions lo;
    lo.threads = o.threads;
    if (o.decoder == SILK_DECODER_INT8) lo.decoder = silk::DecoderPrecision::kInt8;
    if (o.decoder == SILK_DECODER_FP32) lo.decoder = silk::DecoderPrecision::kFp32;
    if (o.decoder == SILK_DECODER_INT4) lo.decoder = silk::DecoderPrecision::kInt4;
    auto m = silk::Model::Load(dir, lo);
    if (!m.ok()) return SetError(m.status());
    auto h = std::make_unique<silk_model>();
    h->model = std::shared_ptr<silk::Model>(std::move(*m));
    const int pool = h->model->threads();
    if (o.threads > 0 && o.threads != pool)
      silk::capi::Log(SILK_LOG_WARN, std::string(dir) + ": threads " + std::to_string(o.threads) +
                                         " ignored: the process's shared pool has " + std::to_string(pool));
    silk::capi::Log(SILK_LOG_INFO, std::string("loaded model ") + dir + " (" + h->model->config().config_name + ", " +
                                       std::to_string(pool) + " threads, " +
                                       silk::DecoderPrecisionName(h->model->precision()) + " decoder)");
    *out = h.release();
    return Ok();
  });
}

void silk_model_destroy(silk_model* model) { delete model; }

silk_status silk_model_get_info(const silk_model* model, silk_model_info* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(model && out, "silk_model_get_info: NULL argument");
    std::memset(out, 0, sizeof(*out));
    const silk::ModelConfig& c = model->model->config();
    std::strncpy(out->config, c.config_name.c_str(), sizeof(out->config) - 1);
    out->d_model = c.dims.d_model;
    out->n_layers = c.dims.n_layers;
    out->n_heads = c.dims.n_heads;
    out->head_dim = c.dims.head_dim;
    out->n_latents = c.dims.n_latents;
    out->n_points = c.dims.n_points;
    out->max_seq_len = c.dims.max_seq_len;
    out->threads = model->model->threads();
    const silk::DecoderPrecision d = model->model->precision();
    out->int8 = d == silk::DecoderPrecision::kInt8;
    out->decoder = d == silk::DecoderPrecision::kInt8 ? SILK_DECODER_INT8
                   : d == silk::DecoderPrecision::kInt4 ? SILK_DECODER_INT4 : SILK_DECODER_FP32;
    out->arch = c.arch == silk::ModelArch::kOfficial ? 1 : 0;
    out->encoder_points = static_cast<int32_t>(model->model->encoder_points());
    return Ok();
  });
}

silk_status silk_model_get_preprocess_params(const silk_model* model, silk_preprocess_params* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(model && out, "silk_model_get_preprocess_params: NULL argument");
    *out = silk::capi::ToCPreprocess(model->model->config().preprocessing);
    return Ok();
  });
}

}  // extern "C"
#endif
