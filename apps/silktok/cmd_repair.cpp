// `silktok repair`: decode a token file through the grammar with hole detection and repair
// (spec §12.2) and write the mesh; report every repair, as text or JSON.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "io/obj_writer.h"
#include "io/token_text.h"
#include "mesh_input.h"
#include "tokenizer/quantize.h"

namespace silktok {
namespace {

struct RepairArgs {
  std::string input, output;
  bool json = false;
  std::string policy = "repair";
  int32_t max_loop = 8;
};

int Run(const RepairArgs& a) {
  auto ids = silk::ReadTokenText(a.input);
  if (!ids.ok()) {
    ReportError(ids.status());
    return kExitFailure;
  }
  silk::GrammarOptions gopt;
  gopt.max_length = 0;
  gopt.window_rule = silk::WindowRule::kUnion;
  silk::Grammar g(gopt);
  size_t pos = 0;
  for (; pos < ids->size(); ++pos) {
    if ((*ids)[pos] == 10267 || (*ids)[pos] == -1) break;  // stop at EOS / data padding (spec §9)
    silk::Rejection r = g.Accept((*ids)[pos]);
    if (!r.ok()) {
      std::fprintf(stderr, "%s: illegal at position %zu: %s (decoding the accepted prefix)\n", a.input.c_str(), pos,
                   r.message.c_str());
      break;
    }
  }
  silk::MeshBuildOptions mopt;
  mopt.holes = a.policy == "off" ? silk::HolePolicy::kOff
               : a.policy == "report" ? silk::HolePolicy::kReport : silk::HolePolicy::kRepair;
  mopt.max_fill_loop = a.max_loop;
  silk::MeshBuildReport rep;
  auto mesh = silk::BuildMeshSoFar(g, mopt, &rep);
  if (!mesh.ok()) {
    ReportError(mesh.status().WithContext(a.input + ": "));
    return kExitFailure;
  }
  silk::OutputMesh out;
  for (const silk::QVec& q : mesh->positions)
    out.positions.push_back({silk::DequantizeCoord(q.x), silk::DequantizeCoord(q.y), silk::DequantizeCoord(q.z)});
  out.triangles = mesh->faces;
  silk::Status st = silk::WriteObjFile(a.output, out);
  if (!st.ok()) {
    ReportError(st);
    return kExitFailure;
  }
  int32_t repaired = 0;
  for (const auto& h : rep.holes) repaired += h.repaired;
  if (a.json) {
    nlohmann::json j;
    j["input"] = a.input;
    j["tokens_accepted"] = pos;
    j["vertices"] = mesh->positions.size();
    j["faces"] = mesh->faces.size();
    j["watertight"] = silk::IsWatertight(*mesh);
    j["window_findings"] = nlohmann::json::array();
    for (const auto& f : rep.window_findings)
      j["window_findings"].push_back({{"component", f.component}, {"layer", f.layer}, {"row_a", f.row_a}, {"row_b", f.row_b}});
    j["holes"] = nlohmann::json::array();
    for (const auto& h : rep.holes)
      j["holes"].push_back({{"component", h.component}, {"loop", h.loop}, {"layers", h.layers},
                            {"repaired", h.repaired}, {"added_edges", h.added_edges}});
    j["faces_added"] = rep.faces_added;
    j["open_edges_before"] = rep.open_edges_before;
    j["open_edges_after"] = rep.open_edges_after;
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("%s: %zu vertices, %zu faces; %zu window disagreements OR-ed; %zu holes, %d repaired (+%d faces); "
                "open edges %d -> %d; %s\n",
                a.input.c_str(), mesh->positions.size(), mesh->faces.size(), rep.window_findings.size(),
                rep.holes.size(), repaired, rep.faces_added, rep.open_edges_before, rep.open_edges_after,
                silk::IsWatertight(*mesh) ? "watertight" : "not watertight");
    for (const auto& h : rep.holes) {
      std::printf("  hole in component %d, %zu edges%s", h.component, h.loop.size(), h.repaired ? ", repaired:" : "");
      for (const auto& e : h.added_edges) std::printf(" [%s]", e.c_str());
      std::printf("\n");
    }
  }
  return kExitOk;
}

}  // namespace

void RegisterRepairCommand(CLI::App& app) {
  auto args = std::make_shared<RepairArgs>();
  CLI::App* cmd = app.add_subcommand(
      "repair",
      "Decode a token file through the grammar (self-layer disagreements OR-ed like the official\n"
      "decoder), find holes (loops of open edges) and close those of <= --max-loop edges whose chords\n"
      "join vertices of equal or adjacent layers. Writes the mesh and reports every repair.\n"
      "An illegal token stops reading; the accepted prefix (closed layers) is decoded.");
  cmd->add_option("input", args->input, "Token file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "Output OBJ file")->required();
  cmd->add_flag("--json", args->json, "Print the report as JSON (default: text)");
  cmd->add_option("--policy", args->policy, "off | report | repair (default: repair)")
      ->check(CLI::IsMember({"off", "report", "repair"}));
  cmd->add_option("--max-loop", args->max_loop, "Longest hole loop that is triangulated (default: 8)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
