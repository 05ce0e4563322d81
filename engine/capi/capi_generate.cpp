// C API: model loading and generation (engine/runtime). Built into every libsilk; without
// onnxruntime the entry points exist and return SILK_ERR_UNSUPPORTED.
#include <chrono>
#include <cstring>
#include <memory>

#include "capi/capi_internal.h"

#if defined(SILK_HAVE_RUNTIME)
#include "runtime/generate_pipeline.h"
#include "runtime/model.h"

struct silk_model {
  std::unique_ptr<silk::Model> model;
};

struct silk_generator {
  explicit silk_generator(const silk::Model& m) : generator(m) {}
  const silk_model* owner = nullptr;
  silk::Generator generator;
};
#endif

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

namespace {

#if defined(SILK_HAVE_RUNTIME)
// Negative sampling fields take the model's defaults (model.json "sampling").
silk::GenerateOptions ToOptions(const silk_generate_params& p, const silk::ModelConfig& config) {
  silk::GenerateOptions o;
  o.sampling = config.sampling;
  o.sampling.seed = p.seed;
  if (p.temperature >= 0) o.sampling.temperature = p.temperature;
  if (p.top_k >= 0) o.sampling.top_k = p.top_k;
  if (p.top_p >= 0) o.sampling.top_p = p.top_p;
  if (p.top_p_temperature >= 0) o.sampling.top_p_temperature = p.top_p_temperature;
  o.max_tokens = p.max_tokens;
  o.max_faces = p.max_faces;
  o.holes = p.holes == SILK_HOLES_REPAIR ? silk::HolePolicy::kRepair
            : p.holes == SILK_HOLES_REPORT ? silk::HolePolicy::kReport : silk::HolePolicy::kOff;
  o.unconstrained = p.unconstrained != 0;
  return o;
}

silk::GenerateCallbacks ToCallbacks(const silk_generate_params& p) {
  silk::GenerateCallbacks cb;
  if (p.progress) {
    cb.progress = [fn = p.progress, user = p.user_data](const silk::GenerateProgress& g) {
      silk_generate_progress c{g.tokens, g.max_tokens, g.components, g.faces, g.seconds};
      fn(&c, user);
    };
  }
  if (p.cancel) cb.cancel = [fn = p.cancel, user = p.user_data]() { return fn(user) != 0; };
  return cb;
}

int32_t StopCode(const std::string& reason) {
  if (reason == "max_tokens") return SILK_STOP_MAX_TOKENS;
  if (reason == "max_faces") return SILK_STOP_MAX_FACES;
  if (reason == "grammar_dead_end") return SILK_STOP_GRAMMAR_DEAD_END;
  return SILK_STOP_EOS;
}

void FillStats(const silk::GenerationStats& s, silk_generate_stats* out) {
  std::memset(out, 0, sizeof(*out));
  out->tokens = s.tokens;
  out->forced_tokens = s.forced_tokens;
  out->sampled_tokens = s.sampled_tokens;
  out->model_calls = s.model_calls;
  out->stop_reason = StopCode(s.stop_reason);
  out->faces = s.faces;
  out->vertices = s.vertices;
  out->components = s.components;
  out->holes_found = s.holes_found;
  out->holes_repaired = s.holes_repaired;
  out->faces_added = s.faces_added;
  out->edge_manifold = s.edge_manifold;
  out->watertight = s.watertight;
  out->consistently_oriented = s.consistently_oriented;
  out->open_edges = s.open_edges;
  out->illegal_at = s.illegal_at;
  out->tokens_per_second = s.tokens_per_second;
  out->seconds_prepare = s.seconds.load_input;
  out->seconds_encoder = s.seconds.encoder;
  out->seconds_decoder = s.seconds.decoder;
  out->seconds_grammar = s.seconds.grammar;
  out->seconds_sampling = s.seconds.sampling;
  out->seconds_build_mesh = s.seconds.build_mesh;
  out->seconds_total = s.seconds.total;
  out->vertex_manifold = s.vertex_manifold;
  out->nonmanifold_vertices = s.nonmanifold_vertices;
  out->fan_gaps_closed = s.fan_gaps_closed;
  out->vertices_split = s.vertices_split;
}

silk_status RunGeneration(silk_generator* g, const silk::GenerationInput& input, const silk_generate_params* params,
                          silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  const silk_generate_params p = params ? *params : silk_generate_default_params();
  if (p.n_points < 0) return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generate: n_points is negative");
  if (p.preprocessing > SILK_PREPROCESS_OFFICIAL)
    return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generate: preprocessing is not a silk_preprocess_kind");
  if (p.raw_points && !input.point_cloud)
    return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generate: raw_points needs a point cloud");
  const silk::ModelConfig& config = g->owner->model->config();
  silk::PreprocessingParams prep = silk::ModelPreprocessing(config, p.n_points);
  if (p.preprocessing >= 0 && p.preprocessing != static_cast<int32_t>(prep.kind))
    prep = p.preprocessing == SILK_PREPROCESS_OFFICIAL ? silk::OfficialPreprocessing(prep.n_points)
                                                       : silk::SilkPreprocessing(prep.normalize_bound, prep.n_points);
  const auto t0 = std::chrono::steady_clock::now();
  auto r = silk::GenerateFromInput(&g->generator, config, input, ToOptions(p, config), ToCallbacks(p),
                                   p.raw_points ? nullptr : &prep);
  if (!r.ok()) return SetError(r.status());
  r->generation.stats.seconds.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  auto mesh = std::make_unique<silk_mesh>();
  mesh->mesh = std::move(r->output.mesh);
  mesh->triangle_component = std::move(r->output.triangle_component);
  std::unique_ptr<silk_tokens> tokens;
  if (out_tokens) {
    tokens = std::make_unique<silk_tokens>();
    tokens->ids = r->generation.tokens;
  }
  if (stats) FillStats(r->generation.stats, stats);
  *out_mesh = mesh.release();
  if (out_tokens) *out_tokens = tokens.release();
  return Ok();
}
#endif

constexpr const char* kNoRuntime = "this libsilk was built without onnxruntime (no generation)";

}  // namespace

extern "C" {

int32_t silk_generation_available(void) {
#if defined(SILK_HAVE_RUNTIME)
  return 1;
#else
  return 0;
#endif
}

silk_model_options silk_model_default_options(void) {
  silk_model_options o;
  o.threads = 0;
  o.decoder = SILK_DECODER_DEFAULT;
  return o;
}

silk_generate_params silk_generate_default_params(void) {
  silk_generate_params p;
  std::memset(&p, 0, sizeof(p));
  p.seed = 0;
  p.temperature = -1;  // the model's (model.json "sampling")
  p.top_k = -1;
  p.top_p = -1;
  p.top_p_temperature = -1;
  p.preprocessing = -1;  // the model's (model.json "preprocessing")
  p.holes = SILK_HOLES_OFF;
  return p;
}

silk_status silk_model_load(const char* dir, const silk_model_options* options, silk_model** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_model_load: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(dir, "silk_model_load: dir is NULL");
#if defined(SILK_HAVE_RUNTIME)
    const silk_model_options o = options ? *options : silk_model_default_options();
    SILK_CAPI_REQUIRE(o.threads >= 0, "silk_model_load: threads is negative");
    silk::ModelLoadOptions lo;
    lo.threads = o.threads;
    SILK_CAPI_REQUIRE(o.decoder >= SILK_DECODER_DEFAULT && o.decoder <= SILK_DECODER_INT4,
                      "silk_model_load: decoder is not a silk_decoder_precision");
    if (o.decoder == SILK_DECODER_INT8) lo.decoder = silk::DecoderPrecision::kInt8;
    if (o.decoder == SILK_DECODER_FP32) lo.decoder = silk::DecoderPrecision::kFp32;
    if (o.decoder == SILK_DECODER_INT4) lo.decoder = silk::DecoderPrecision::kInt4;
    auto m = silk::Model::Load(dir, lo);
    if (!m.ok()) return SetError(m.status());
    auto h = std::make_unique<silk_model>();
    h->model = std::move(*m);
    *out = h.release();
    return Ok();
#else
    (void)options;
    return SetError(SILK_ERR_UNSUPPORTED, kNoRuntime);
#endif
  });
}

void silk_model_destroy(silk_model* model) {
#if defined(SILK_HAVE_RUNTIME)
  delete model;
#else
  (void)model;
#endif
}

silk_status silk_model_get_info(const silk_model* model, silk_model_info* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(model && out, "silk_model_get_info: NULL argument");
#if defined(SILK_HAVE_RUNTIME)
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
#else
    return SetError(SILK_ERR_UNSUPPORTED, kNoRuntime);
#endif
  });
}

silk_status silk_model_get_preprocess_params(const silk_model* model, silk_preprocess_params* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(model && out, "silk_model_get_preprocess_params: NULL argument");
#if defined(SILK_HAVE_RUNTIME)
    *out = silk::capi::ToCPreprocess(model->model->config().preprocessing);
    return Ok();
#else
    return SetError(SILK_ERR_UNSUPPORTED, kNoRuntime);
#endif
  });
}

silk_status silk_generator_create(const silk_model* model, silk_generator** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_generator_create: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(model, "silk_generator_create: model is NULL");
#if defined(SILK_HAVE_RUNTIME)
    auto g = std::make_unique<silk_generator>(*model->model);
    g->owner = model;
    *out = g.release();
    return Ok();
#else
    return SetError(SILK_ERR_UNSUPPORTED, kNoRuntime);
#endif
  });
}

void silk_generator_destroy(silk_generator* generator) {
#if defined(SILK_HAVE_RUNTIME)
  delete generator;
#else
  (void)generator;
#endif
}

silk_status silk_generate(silk_generator* generator, const silk_mesh* mesh, const silk_generate_params* params,
                          silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_mesh, "silk_generate: out_mesh is NULL");
    *out_mesh = nullptr;
    if (out_tokens) *out_tokens = nullptr;
    SILK_CAPI_REQUIRE(generator && mesh, "silk_generate: generator or mesh is NULL");
#if defined(SILK_HAVE_RUNTIME)
    silk::GenerationInput input;
    input.mesh = mesh->mesh;
    return RunGeneration(generator, input, params, out_mesh, out_tokens, stats);
#else
    (void)params;
    (void)stats;
    return SetError(SILK_ERR_UNSUPPORTED, kNoRuntime);
#endif
  });
}

silk_status silk_generate_from_points(silk_generator* generator, const double* points, size_t n_points,
                                      const silk_generate_params* params, silk_mesh** out_mesh,
                                      silk_tokens** out_tokens, silk_generate_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_mesh, "silk_generate_from_points: out_mesh is NULL");
    *out_mesh = nullptr;
    if (out_tokens) *out_tokens = nullptr;
    SILK_CAPI_REQUIRE(generator && points && n_points > 0, "silk_generate_from_points: no generator or no points");
#if defined(SILK_HAVE_RUNTIME)
    silk::GenerationInput input;
    input.point_cloud = true;
    input.mesh.positions.resize(n_points);
    input.normals.resize(n_points);
    for (size_t i = 0; i < n_points; ++i)
      for (int a = 0; a < 3; ++a) {
        input.mesh.positions[i][a] = points[6 * i + a];
        input.normals[i][a] = points[6 * i + 3 + a];
      }
    return RunGeneration(generator, input, params, out_mesh, out_tokens, stats);
#else
    (void)params;
    (void)stats;
    return SetError(SILK_ERR_UNSUPPORTED, kNoRuntime);
#endif
  });
}

}  // extern "C"
