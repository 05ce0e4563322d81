// SPDX-License-Identifier: MIT
// `silktok repair`: decode a token file through the grammar with hole detection and repair
// (token_format.md §12.2) and write the mesh; report every repair, as text or JSON.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "../common/app_files.h"
#include "silk/silk.hpp"
#include "commands.h"
#include "cli_errors.h"
#include "output_checks.h"

namespace silktok {
namespace {

struct RepairArgs {
  std::string input, output;
  bool json = false;
  std::string policy = silk_hole_policy_name(SILK_HOLES_REPAIR);
  int32_t max_loop = 8;
};

void PrintText(const std::string& input, const silk_repair_stats& st, const nlohmann::json& report) {
  std::printf(
      "%s: %d vertices, %d faces; %d window disagreements OR-ed; %d holes, %d repaired (+%d faces); "
      "open edges %d -> %d; %s\n",
      input.c_str(), st.vertices, st.faces, st.window_findings, st.holes_found, st.holes_repaired, st.faces_added,
      st.open_edges_before, st.open_edges_after, st.watertight ? "watertight" : "not watertight");
  for (const auto& h : report["holes"]) {
    const bool repaired = h["repaired"].get<bool>();
    std::printf("  hole in component %d, %zu edges%s", h["component"].get<int>(), h["loop"].size(),
                repaired ? ", repaired:" : "");
    for (const auto& e : h["added_edges"]) std::printf(" [%s]", e.get<std::string>().c_str());
    std::printf("\n");
  }
}

int Run(const RepairArgs& a) {
  if (int rc = CheckOutputs({a.input}, {a.output}); rc != kExitOk) return rc;
  silk_repair_params p = silk_repair_default_params();
  p.holes = silk_cpp::EnumValue(silk_hole_policy_from_name, a.policy);
  p.max_fill_loop = a.max_loop;
  silk_repair_stats st = silk_cpp::Sized<silk_repair_stats>();
  nlohmann::json report;
  try {
    const silk_cpp::Tokens tokens = silk_cpp::Tokens::Load(a.input);
    std::string json;
    silk_cpp::Mesh mesh = [&] {
      try {
        return silk_cpp::Mesh::Repair(tokens, p, &st, &json);
      } catch (const silk_cpp::Error& e) {
        throw WithContext(e, a.input + ": ");
      }
    }();
    report = nlohmann::json::parse(json);
    if (!report["illegal"].is_null())
      std::fprintf(stderr, "%s: illegal at position %lld: %s (decoding the accepted prefix)\n", a.input.c_str(),
                   static_cast<long long>(st.illegal_at), report["illegal"]["message"].get<std::string>().c_str());
    silk_save_params save = silk_save_default_params();
    save.format = SILK_FORMAT_OBJ;
    mesh.Save(a.output, save);
  } catch (const silk_cpp::Error& e) {
    ReportError(e);
    return kExitFailure;
  }
  if (a.json) {
    report.erase("illegal");  // reported on stderr
    report["input"] = a.input;
    std::printf("%s\n", report.dump(2).c_str());
  } else {
    PrintText(a.input, st, report);
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
  cmd->add_option("input", args->input, "Token file")->required()->check(silkapp::ExistingFile());
  cmd->add_option("-o,--output", args->output, "Output OBJ file")->required();
  cmd->add_flag("--json", args->json, "Print the report as JSON (default: text)");
  cmd->add_option("--policy", args->policy, "off | report | repair (default: repair)")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_hole_policy_name, SILK_HOLES_OFF)));
  cmd->add_option("--max-loop", args->max_loop, "Longest hole loop that is triangulated (default: 8)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
