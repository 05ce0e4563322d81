// SPDX-License-Identifier: MIT
// C API: hole repair of a token stream (token_format.md §12.2): the grammar reads the ids with the official
// decoder's window rule, the accepted prefix becomes a mesh under the hole policy, and every
// finding comes back as figures and as a JSON report.
#include <cstring>
#include <memory>

#include <nlohmann/json.hpp>

#include "capi/capi_internal.h"
#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "tokenizer/cleanup/quantize.h"
#include "tokenizer/vocabulary_layout.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

namespace {

using Json = nlohmann::ordered_json;

Json ReportJson(size_t accepted, const silk::Rejection& illegal, int32_t illegal_id,
                const silk::TokenizerDecodedMesh& mesh, const silk::MeshBuildReport& rep) {
  Json j;
  j["tokens_accepted"] = accepted;
  j["illegal"] = illegal.ok() ? Json(nullptr)
                              : Json{{"position", accepted},
                                     {"id", illegal_id},
                                     {"reason", silk::RejectReasonName(illegal.reason)},
                                     {"message", illegal.message}};
  j["vertices"] = mesh.positions.size();
  j["faces"] = mesh.faces.size();
  j["watertight"] = silk::IsWatertight(mesh);
  j["window_findings"] = Json::array();
  for (const auto& f : rep.window_findings)
    j["window_findings"].push_back(
        {{"component", f.component}, {"layer", f.layer}, {"row_a", f.row_a}, {"row_b", f.row_b}});
  j["holes"] = Json::array();
  for (const auto& h : rep.holes)
    j["holes"].push_back({{"component", h.component},
                          {"loop", h.loop},
                          {"layers", h.layers},
                          {"repaired", h.repaired},
                          {"added_edges", h.added_edges}});
  j["faces_added"] = rep.faces_added;
  j["open_edges_before"] = rep.open_edges_before;
  j["open_edges_after"] = rep.open_edges_after;
  return j;
}

void FillStats(size_t accepted, bool illegal, const silk::TokenizerDecodedMesh& mesh, const silk::MeshBuildReport& rep,
               silk_repair_stats* stats) {
  silk_repair_stats o = silk::capi::Blank<silk_repair_stats>();
  silk_repair_stats* out = &o;
  out->tokens_accepted = static_cast<int64_t>(accepted);
  out->illegal_at = illegal ? static_cast<int64_t>(accepted) : -1;
  out->vertices = static_cast<int32_t>(mesh.positions.size());
  out->faces = static_cast<int32_t>(mesh.faces.size());
  out->watertight = silk::IsWatertight(mesh) ? 1 : 0;
  out->window_findings = static_cast<int32_t>(rep.window_findings.size());
  out->holes_found = static_cast<int32_t>(rep.holes.size());
  for (const auto& h : rep.holes) out->holes_repaired += h.repaired ? 1 : 0;
  out->faces_added = rep.faces_added;
  out->open_edges_before = rep.open_edges_before;
  out->open_edges_after = rep.open_edges_after;
  silk::capi::StoreOut(stats, o);
}

}  // namespace

extern "C" {

silk_repair_params silk_repair_default_params(void) {
  silk_repair_params p;
  p.struct_size = sizeof(p);
  p.holes = SILK_HOLES_REPAIR;
  p.max_fill_loop = silk::MeshBuildOptions{}.max_fill_loop;
  return p;
}

silk_status silk_tokens_repair(const silk_tokens* tokens, const silk_repair_params* params, silk_mesh** out_mesh,
                               silk_repair_stats* stats, silk_report** report) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(tokens && out_mesh, "silk_tokens_repair: tokens or out_mesh is NULL");
    *out_mesh = nullptr;
    if (report) *report = nullptr;
    SILK_CAPI_TRY(silk::capi::CheckParamsSize("silk_tokens_repair", "silk_repair_params", params,
                                              "silk_repair_default_params()"));
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_tokens_repair", "silk_repair_stats", stats));
    const silk_repair_params p = silk::capi::ReadParams(params, silk_repair_default_params());
    SILK_CAPI_CHECK("silk_tokens_repair",
                    silk::capi::CheckEnum("holes", p.holes, SILK_HOLES_OFF, SILK_HOLES_REPAIR, "silk_hole_policy"));
    SILK_CAPI_REQUIRE(p.max_fill_loop >= 0,
                      "silk_tokens_repair: max_fill_loop " + std::to_string(p.max_fill_loop) + " must be >= 0");
    silk::GrammarOptions gopt;
    gopt.max_length = 0;
    gopt.window_rule = silk::WindowRule::kUnion;
    silk::Grammar g(gopt);
    const std::vector<int32_t>& ids = tokens->ids;
    size_t pos = 0;
    silk::Rejection illegal;
    for (; pos < ids.size(); ++pos) {
      if (ids[pos] == silk::vocab::k_eos_id || ids[pos] == -1)
        break;  // EOS / data padding end the stream (token_format.md §9)
      illegal = g.Accept(ids[pos]);
      if (!illegal.ok()) break;
    }
    silk::MeshBuildOptions mopt;
    mopt.holes = p.holes == SILK_HOLES_REPAIR   ? silk::HolePolicy::kRepair
                 : p.holes == SILK_HOLES_REPORT ? silk::HolePolicy::kReport
                                                : silk::HolePolicy::kOff;
    mopt.max_fill_loop = p.max_fill_loop;
    silk::MeshBuildReport rep;
    auto mesh = silk::BuildMeshSoFar(g, mopt, &rep);
    if (!mesh.ok()) return SetError(mesh.status());
    auto m = silk::capi::MeshHandle(silk::DequantizePositions(mesh->positions), *mesh);
    if (stats) FillStats(pos, !illegal.ok(), *mesh, rep, stats);
    if (report) {
      auto r = std::make_unique<silk_report>();
      r->json = ReportJson(pos, illegal, pos < ids.size() ? ids[pos] : -1, *mesh, rep).dump(2);
      *report = r.release();
    }
    *out_mesh = m.release();
    return Ok();
  });
}

}  // extern "C"
