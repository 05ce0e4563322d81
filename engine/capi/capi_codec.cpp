// C API: token sequences, encode (mesh -> tokens) and decode (tokens -> mesh).
#include <algorithm>
#include <chrono>
#include <memory>

#include "capi/capi_internal.h"
#include "io/files/atomic_file.h"
#include "io/tokens/token_text.h"
#include "mesh/vertex_fans.h"
#include "mesh/normalize.h"
#include "tokenizer/cleanup/quantize.h"
#include "tokenizer/tokenizer.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

extern "C" {

silk_status silk_tokens_create(const int32_t* ids, size_t count, silk_tokens** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_tokens_create: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(ids || count == 0, "silk_tokens_create: ids is NULL");
    auto t = std::make_unique<silk_tokens>();
    t->ids.assign(ids, ids + count);
    *out = t.release();
    return Ok();
  });
}

silk_status silk_tokens_load(const char* path, silk_tokens** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out && path, "silk_tokens_load: NULL argument");
    *out = nullptr;
    auto r = silk::ReadTokenText(path);
    if (!r.ok()) return SetError(r.status());
    auto t = std::make_unique<silk_tokens>();
    t->ids = std::move(*r);
    *out = t.release();
    return Ok();
  });
}

silk_status silk_tokens_save(const silk_tokens* tokens, const char* path) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(tokens && path, "silk_tokens_save: NULL argument");
    return SetError(silk::WriteFileAtomically(path, silk::FormatTokenText(tokens->ids)));
  });
}

void silk_tokens_destroy(silk_tokens* tokens) { delete tokens; }
size_t silk_tokens_count(const silk_tokens* tokens) { return tokens ? tokens->ids.size() : 0; }

silk_status silk_tokens_copy(const silk_tokens* tokens, int32_t* out, size_t capacity) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(tokens, "silk_tokens_copy: tokens is NULL");
    if (silk_status c = silk::capi::CheckCopy("silk_tokens_copy", out, capacity, tokens->ids.size()); c != SILK_OK)
      return c;
    std::copy(tokens->ids.begin(), tokens->ids.end(), out);
    return Ok();
  });
}

silk_encode_params silk_encode_default_params(void) {
  silk_encode_params p{};
  p.normalize = 1;
  p.normalize_bound = silk::kDefaultNormalizeBound;
  p.nonmanifold_processing = 1;
  return p;
}

silk_status silk_encode(const silk_mesh* mesh, const silk_encode_params* params, silk_tokens** out,
                        silk_encode_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(mesh && out, "silk_encode: mesh or out is NULL");
    *out = nullptr;
    const silk_encode_params p = params ? *params : silk_encode_default_params();
    SILK_CAPI_CHECK("silk_encode", silk::capi::CheckFlag("normalize", p.normalize));
    SILK_CAPI_CHECK("silk_encode", silk::capi::CheckFlag("nonmanifold_processing", p.nonmanifold_processing));
    SILK_CAPI_REQUIRE(!p.normalize || (p.normalize_bound > 0 && p.normalize_bound <= 1),
                      "silk_encode: normalize_bound " + silk::capi::ValueText(p.normalize_bound) + " must lie in (0, 1]");
    const auto t0 = std::chrono::steady_clock::now();
    silk::IoMesh normalized;
    if (p.normalize) {
      auto n = silk::NormalizeMesh(mesh->mesh, p.normalize_bound);
      if (!n.ok()) return SetError(n.status());
      normalized = std::move(*n);
    }
    silk::EncodeOptions opt;
    opt.nonmanifold_processing = p.nonmanifold_processing != 0;
    auto r = silk::EncodeMesh(p.normalize ? normalized : mesh->mesh, opt);
    if (!r.ok()) return SetError(r.status());
    if (stats) {
      const silk::EncodeStats& s = r->stats;
      *stats = silk_encode_stats{};
      stats->input_vertices = s.input_vertices;
      stats->input_faces = s.input_faces;
      stats->processed_vertices = s.processed_vertices;
      stats->processed_faces = s.processed_faces;
      stats->emitted_vertices = s.emitted_vertices;
      stats->encodable_faces = s.encodable_faces;
      stats->components_found = s.components_found;
      stats->components_encoded = s.components_encoded;
      stats->components_dropped_small = s.components_dropped_small;
      stats->layers = s.layers;
      stats->max_layer_size = s.max_layer_size;
      stats->max_layer_count = s.max_layer_count;
      stats->tokens = s.tokens;
      stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      stats->merged_vertices = s.merged_vertices;
      stats->dropped_degenerate_faces = s.dropped_degenerate_faces;
      stats->dropped_duplicate_faces = s.dropped_duplicate_faces;
      stats->nonmanifold_copies = s.nonmanifold_copies;
      stats->flipped_faces = s.flipped_faces;
      stats->seconds_quantize_cleanup = s.times.quantize_cleanup;
      stats->seconds_nonmanifold = s.times.nonmanifold;
      stats->seconds_orientation = s.times.orientation;
      stats->seconds_components = s.times.components;
      stats->seconds_layering = s.times.layering;
      stats->seconds_codecs = s.times.codecs;
      stats->seconds_packing = s.times.packing;
    }
    auto t = std::make_unique<silk_tokens>();
    t->ids = std::move(r->tokens);
    *out = t.release();
    return Ok();
  });
}

silk_decode_params silk_decode_default_params(void) {
  silk_decode_params p{};
  p.grid_coordinates = 0;
  p.split_nonmanifold_vertices = 0;
  return p;
}

silk_status silk_decode(const silk_tokens* tokens, const silk_decode_params* params, silk_mesh** out) {
  return silk_decode_with_stats(tokens, params, out, nullptr);
}

silk_status silk_decode_with_stats(const silk_tokens* tokens, const silk_decode_params* params, silk_mesh** out,
                                   silk_decode_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(tokens && out, "silk_decode: tokens or out is NULL");
    *out = nullptr;
    const silk_decode_params p = params ? *params : silk_decode_default_params();
    SILK_CAPI_CHECK("silk_decode", silk::capi::CheckFlag("grid_coordinates", p.grid_coordinates));
    SILK_CAPI_CHECK("silk_decode", silk::capi::CheckFlag("split_nonmanifold_vertices", p.split_nonmanifold_vertices));
    auto r = silk::DecodeTokens(tokens->ids);
    if (!r.ok()) return SetError(r.status());
    int32_t split = 0;
    if (p.split_nonmanifold_vertices) {
      std::vector<int32_t> copy_of;  // the copies keep their source's position
      split = silk::SplitNonManifoldFans(&r->faces, static_cast<int32_t>(r->positions.size()), &copy_of);
      for (int32_t v : copy_of) r->positions.push_back(r->positions[v]);
    }
    std::vector<std::array<double, 3>> positions;
    for (const silk::QVec& q : r->positions) {
      if (p.grid_coordinates) positions.push_back({double(q.x), double(q.y), double(q.z)});
      else
        positions.push_back(silk::DequantizePosition(q));
    }
    auto m = silk::capi::MeshHandle(std::move(positions), *r);
    if (stats) {
      stats->vertices = static_cast<int32_t>(r->positions.size());
      stats->faces = static_cast<int32_t>(r->faces.size());
      stats->components = r->components;
      stats->vertices_split = split;
    }
    *out = m.release();
    return Ok();
  });
}

}  // extern "C"
