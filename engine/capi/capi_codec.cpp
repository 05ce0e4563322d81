// SPDX-License-Identifier: MIT
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

namespace {

// silk::EncodeStats -> silk_encode_stats (seconds: wall time since t0, normalisation included).
silk_encode_stats EncodeStatsOf(const silk::EncodeStats& s, std::chrono::steady_clock::time_point t0) {
  silk_encode_stats o = silk::capi::Blank<silk_encode_stats>();
  o.input_vertices = s.input_vertices;
  o.input_faces = s.input_faces;
  o.processed_vertices = s.processed_vertices;
  o.processed_faces = s.processed_faces;
  o.emitted_vertices = s.emitted_vertices;
  o.encodable_faces = s.encodable_faces;
  o.components_found = s.components_found;
  o.components_encoded = s.components_encoded;
  o.components_dropped_small = s.components_dropped_small;
  o.layers = s.layers;
  o.max_layer_size = s.max_layer_size;
  o.max_layer_count = s.max_layer_count;
  o.tokens = s.tokens;
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.merged_vertices = s.merged_vertices;
  o.dropped_degenerate_faces = s.dropped_degenerate_faces;
  o.dropped_duplicate_faces = s.dropped_duplicate_faces;
  o.nonmanifold_copies = s.nonmanifold_copies;
  o.flipped_faces = s.flipped_faces;
  o.seconds_quantize_cleanup = s.times.quantize_cleanup;
  o.seconds_nonmanifold = s.times.nonmanifold;
  o.seconds_orientation = s.times.orientation;
  o.seconds_components = s.times.components;
  o.seconds_layering = s.times.layering;
  o.seconds_codecs = s.times.codecs;
  o.seconds_packing = s.times.packing;
  return o;
}

}  // namespace

silk_status silk::capi::CheckEncodeParams(const char* function, const silk_encode_params* params) {
  SILK_CAPI_TRY(CheckParamsSize(function, "silk_encode_params", params, "silk_encode_default_params()"));
  const silk_encode_params p = ReadParams(params, silk_encode_default_params());
  const std::string fn = function;
  for (const Status& s :
       {CheckFlag("normalize", p.normalize), CheckFlag("nonmanifold_processing", p.nonmanifold_processing)})
    if (!s.ok()) return SetError(s.WithContext(fn + ": "));
  SILK_CAPI_REQUIRE(!p.normalize || (p.normalize_bound > 0 && p.normalize_bound <= 1),
                    fn + ": normalize_bound " + ValueText(p.normalize_bound) + " must lie in (0, 1]");
  return SILK_OK;
}

silk::StatusOr<silk::EncodeResult> silk::capi::EncodeWithParams(const silk_mesh& mesh,
                                                                const silk_encode_params* params) {
  const silk_encode_params p = ReadParams(params, silk_encode_default_params());
  silk::EncodeOptions opt;
  opt.nonmanifold_processing = p.nonmanifold_processing != 0;
  if (!p.normalize) return silk::EncodeMesh(mesh.mesh, opt);
  auto normalized = silk::NormalizeMesh(mesh.mesh, p.normalize_bound);
  if (!normalized.ok()) return normalized.status();
  return silk::EncodeMesh(*normalized, opt);
}

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

silk_status silk_tokens_copy(const silk_tokens* tokens, int32_t* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE(tokens, "silk_tokens_copy: tokens is NULL");
    if (silk_status c; !silk::capi::BeginCopy("silk_tokens_copy", out, capacity, tokens->ids.size(), out_count, &c))
      return c;
    std::copy(tokens->ids.begin(), tokens->ids.end(), out);
    return Ok();
  });
}

silk_encode_params silk_encode_default_params(void) {
  silk_encode_params p{};
  p.struct_size = sizeof(p);
  p.normalize = 1;
  p.normalize_bound = silk::kDefaultNormalizeBound;
  p.nonmanifold_processing = 1;
  return p;
}

silk_status silk_mesh_encode(const silk_mesh* mesh, const silk_encode_params* params, silk_tokens** out,
                             silk_encode_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(mesh && out, "silk_mesh_encode: mesh or out is NULL");
    *out = nullptr;
    SILK_CAPI_TRY(silk::capi::CheckEncodeParams("silk_mesh_encode", params));
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_mesh_encode", "silk_encode_stats", stats));
    const auto t0 = std::chrono::steady_clock::now();
    auto r = silk::capi::EncodeWithParams(*mesh, params);
    if (!r.ok()) return SetError(r.status());
    if (stats) silk::capi::StoreOut(stats, EncodeStatsOf(r->stats, t0));
    auto t = std::make_unique<silk_tokens>();
    t->ids = std::move(r->tokens);
    *out = t.release();
    return Ok();
  });
}

silk_decode_params silk_decode_default_params(void) {
  silk_decode_params p{};
  p.struct_size = sizeof(p);
  p.grid_coordinates = 0;
  p.split_nonmanifold_vertices = 0;
  return p;
}

silk_status silk_tokens_decode(const silk_tokens* tokens, const silk_decode_params* params, silk_mesh** out,
                               silk_decode_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(tokens && out, "silk_tokens_decode: tokens or out is NULL");
    *out = nullptr;
    SILK_CAPI_TRY(silk::capi::CheckParamsSize("silk_tokens_decode", "silk_decode_params", params,
                                              "silk_decode_default_params()"));
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_tokens_decode", "silk_decode_stats", stats));
    const silk_decode_params p = silk::capi::ReadParams(params, silk_decode_default_params());
    SILK_CAPI_CHECK("silk_tokens_decode", silk::capi::CheckFlag("grid_coordinates", p.grid_coordinates));
    SILK_CAPI_CHECK("silk_tokens_decode",
                    silk::capi::CheckFlag("split_nonmanifold_vertices", p.split_nonmanifold_vertices));
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
      if (p.grid_coordinates)
        positions.push_back({double(q.x), double(q.y), double(q.z)});
      else
        positions.push_back(silk::DequantizePosition(q));
    }
    auto m = silk::capi::MeshHandle(std::move(positions), *r);
    if (stats) {
      silk_decode_stats st = silk::capi::Blank<silk_decode_stats>();
      st.vertices = static_cast<int32_t>(r->positions.size());
      st.faces = static_cast<int32_t>(r->faces.size());
      st.components = r->components;
      st.vertices_split = split;
      silk::capi::StoreOut(stats, st);
    }
    *out = m.release();
    return Ok();
  });
}

}  // extern "C"
