// SPDX-License-Identifier: MIT
// `silktok roundtrip`: encode, decode, and compare with the processed mesh; fails if a
// representable face is missing or reversed.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "../common/app_files.h"
#include "commands.h"
#include "mesh_input.h"

namespace silktok {
namespace {

struct RoundtripArgs {
  std::string input;
  bool json = false;
};

int Run(const RoundtripArgs& a) {
  silk_roundtrip_report r = silk_cpp::Sized<silk_roundtrip_report>();
  try {
    const silk_cpp::Mesh mesh = LoadMesh(a.input);
    try {
      r = mesh.Roundtrip();
    } catch (const silk_cpp::Error& e) {
      throw WithContext(e, a.input + ": ");
    }
  } catch (const silk_cpp::Error& e) {
    ReportError(e);
    return kExitFailure;
  }
  if (a.json) {
    nlohmann::json j{{"file", a.input},
                     {"tokens", r.tokens},
                     {"processed_faces", r.processed_faces},
                     {"representable_faces", r.representable_faces},
                     {"recovered", r.recovered},
                     {"reversed", r.reversed},
                     {"missing", r.missing},
                     {"extra_faces", r.extra},
                     {"decoded_faces", r.decoded_faces},
                     {"exact", r.exact != 0}};
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf(
        "%s: %lld tokens; %lld processed faces, %lld representable: %lld recovered, %lld reversed, "
        "%lld missing; %lld extra faces (%lld decoded) -> %s\n",
        a.input.c_str(), static_cast<long long>(r.tokens), static_cast<long long>(r.processed_faces),
        static_cast<long long>(r.representable_faces), static_cast<long long>(r.recovered),
        static_cast<long long>(r.reversed), static_cast<long long>(r.missing), static_cast<long long>(r.extra),
        static_cast<long long>(r.decoded_faces), r.exact ? "exact" : "NOT EXACT");
  }
  return r.exact ? kExitOk : kExitFailure;
}

}  // namespace

void RegisterRoundtripCommand(CLI::App& app) {
  auto args = std::make_shared<RoundtripArgs>();
  CLI::App* cmd =
      app.add_subcommand("roundtrip",
                         "Encode a mesh, decode the tokens, and compare with the processed mesh: representable faces\n"
                         "recovered, reversed windings, missing and extra faces. Exit 1 if a representable face is\n"
                         "missing or reversed.");
  cmd->add_option("input", args->input, "Input mesh file")->required()->check(silkapp::ExistingFile());
  cmd->add_flag("--json", args->json, "Print JSON instead of text (default: text)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
