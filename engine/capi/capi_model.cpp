// SPDX-License-Identifier: MIT
// C API: model loading and information. The handle shares the Model with its generators.
#if defined(SILK_HAVE_RUNTIME)
#include <cstring>
#include <memory>

#include "capi/capi_generator.h"
#include "io/files/model_folders.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

extern "C" {

int32_t silk_generation_available(void) { return 1; }

silk_status silk_model_load(const char* dir, const silk_model_params* params, silk_model** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_model_load: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(dir, "silk_model_load: dir is NULL");
    SILK_CAPI_TRY(
        silk::capi::CheckParamsSize("silk_model_load", "silk_model_params", params, "silk_model_default_params()"));
    const silk_model_params o = silk::capi::ReadParams(params, silk_model_default_params());
    SILK_CAPI_CHECK("silk_model_load", silk::capi::CheckEnum("decoder", o.decoder, SILK_DECODER_DEFAULT,
                                                             SILK_DECODER_INT4, "silk_decoder_precision"));
    SILK_CAPI_CHECK("silk_model_load", silk::capi::CheckEnum("kv_precision", o.kv_precision, SILK_KV_DEFAULT,
                                                             SILK_KV_INT8, "silk_kv_precision"));
    silk::ModelLoadOptions lo;
    lo.threads = o.threads;
    if (o.decoder == SILK_DECODER_INT8) lo.decoder = silk::DecoderPrecision::kInt8;
    if (o.decoder == SILK_DECODER_FP32) lo.decoder = silk::DecoderPrecision::kFp32;
    if (o.decoder == SILK_DECODER_INT4) lo.decoder = silk::DecoderPrecision::kInt4;
    if (o.kv_precision == SILK_KV_FP32) lo.kv = silk::KvPrecision::kFp32;
    if (o.kv_precision == SILK_KV_FP16) lo.kv = silk::KvPrecision::kFp16;
    if (o.kv_precision == SILK_KV_INT8) lo.kv = silk::KvPrecision::kInt8;
    auto found = silk::ResolveModelDir(dir);  // a path, a model name, or "" for the bundled model
    if (!found.ok()) return SetError(found.status().WithContext("silk_model_load: "));
    const std::string& folder = *found;
    auto m = silk::Model::Load(folder, lo);
    if (!m.ok()) return SetError(m.status());
    auto h = std::make_unique<silk_model>();
    h->model = std::shared_ptr<silk::Model>(std::move(*m));
    const int pool = h->model->threads();
    if (o.threads > 0 && o.threads != pool)
      silk::capi::Log(SILK_LOG_WARN, folder + ": threads " + std::to_string(o.threads) +
                                         " ignored: the process's shared pool has " + std::to_string(pool));
    silk::capi::Log(SILK_LOG_INFO, std::string("loaded model ") + folder + " (" + h->model->config().config_name +
                                       ", " + std::to_string(pool) + " threads, " +
                                       silk::DecoderPrecisionName(h->model->precision()) + " decoder, " +
                                       silk::KvPrecisionName(h->model->kv_precision()) + " KV cache)");
    *out = h.release();
    return Ok();
  });
}

void silk_model_destroy(silk_model* model) { delete model; }

silk_status silk_model_get_info(const silk_model* model, silk_model_info* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(model && out, "silk_model_get_info: NULL argument");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_model_get_info", "silk_model_info", out));
    silk_model_info info = silk::capi::Blank<silk_model_info>();
    silk_model_info* o = &info;
    const silk::ModelConfig& c = model->model->config();
    std::strncpy(o->config, c.config_name.c_str(), sizeof(o->config) - 1);
    o->d_model = c.dims.d_model;
    o->n_layers = c.dims.n_layers;
    o->n_heads = c.dims.n_heads;
    o->head_dim = c.dims.head_dim;
    o->n_latents = c.dims.n_latents;
    o->default_points = c.dims.n_points;
    o->max_seq_len = c.dims.max_seq_len;
    o->threads = model->model->threads();
    const silk::DecoderPrecision d = model->model->precision();
    o->int8 = d == silk::DecoderPrecision::kInt8;
    o->decoder = d == silk::DecoderPrecision::kInt8   ? SILK_DECODER_INT8
                 : d == silk::DecoderPrecision::kInt4 ? SILK_DECODER_INT4
                                                      : SILK_DECODER_FP32;
    o->arch = c.arch == silk::ModelArch::kOfficial ? SILK_ARCH_OFFICIAL : SILK_ARCH_SILK;
    o->encoder_points = static_cast<int32_t>(model->model->encoder_points());
    const silk::KvPrecision kv = model->model->kv_precision();
    o->kv_precision = kv == silk::KvPrecision::kFp16   ? SILK_KV_FP16
                      : kv == silk::KvPrecision::kInt8 ? SILK_KV_INT8
                                                       : SILK_KV_FP32;
    silk::capi::StoreOut(out, info);
    return Ok();
  });
}

silk_status silk_model_get_preprocess_params(const silk_model* model, silk_preprocess_params* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(model && out, "silk_model_get_preprocess_params: NULL argument");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_model_get_preprocess_params", "silk_preprocess_params", out));
    silk::capi::StoreOut(out, silk::capi::ToCPreprocess(model->model->config().preprocessing));
    return Ok();
  });
}

}  // extern "C"
#endif
