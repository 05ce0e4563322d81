// SPDX-License-Identifier: MIT
// C API: seeded random legal token streams drawn from the grammar's masks, and their meshes
// (property tests, fuzzing seeds, demos of what the grammar allows).
#include <memory>
#include <random>

#include "capi/capi_internal.h"
#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "decoder/random_walk.h"
#include "tokenizer/cleanup/quantize.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

extern "C" {

silk_random_walk_params silk_random_walk_default_params(void) {
  const silk::RandomWalkOptions o;
  silk_random_walk_params p;
  p.struct_size = sizeof(p);
  p.seed = 1;
  p.max_components = o.max_components;
  p.max_layers = o.max_layers;
  p.max_layer_size = o.max_layer_size;
  return p;
}

silk_status silk_tokens_random_walk(const silk_random_walk_params* params, silk_tokens** out_tokens,
                                    silk_mesh** out_mesh) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_tokens, "silk_tokens_random_walk: out_tokens is NULL");
    *out_tokens = nullptr;
    if (out_mesh) *out_mesh = nullptr;
    SILK_CAPI_TRY(silk::capi::CheckParamsSize("silk_tokens_random_walk", "silk_random_walk_params", params,
                                              "silk_random_walk_default_params()"));
    const silk_random_walk_params p = silk::capi::ReadParams(params, silk_random_walk_default_params());
    SILK_CAPI_REQUIRE(p.max_components >= 1 && p.max_components <= 1000,
                      "silk_tokens_random_walk: max_components must be in [1, 1000]");
    SILK_CAPI_REQUIRE(p.max_layers >= 0 && p.max_layers <= 199,
                      "silk_tokens_random_walk: max_layers must be in [0, 199]");
    SILK_CAPI_REQUIRE(p.max_layer_size >= 0 && p.max_layer_size <= 200,
                      "silk_tokens_random_walk: max_layer_size must be in [0, 200]");
    silk::RandomWalkOptions wo;
    wo.max_components = p.max_components;
    wo.max_layers = p.max_layers;
    wo.max_layer_size = p.max_layer_size;
    std::mt19937_64 rng(p.seed);
    silk::Grammar g;
    auto t = std::make_unique<silk_tokens>();
    t->ids = silk::RandomLegalWalk(&g, &rng, wo);
    std::unique_ptr<silk_mesh> m;
    if (out_mesh) {
      auto mesh = silk::BuildMeshSoFar(g, silk::MeshBuildOptions{}, nullptr);
      if (!mesh.ok()) return SetError(mesh.status());
      m = silk::capi::MeshHandle(silk::DequantizePositions(mesh->positions), *mesh);
    }
    *out_tokens = t.release();
    if (out_mesh) *out_mesh = m.release();
    return Ok();
  });
}

}  // extern "C"
