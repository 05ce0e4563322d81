// `silktok roundtrip`: encode, decode, and compare with the processed mesh; fails if a
// representable face is missing or reversed.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "mesh_input.h"
#include "tokenizer/roundtrip_check.h"

namespace silktok {
namespace {

struct RoundtripArgs {
  std::string input;
  bool json = false;
};

int Run(const RoundtripArgs& a) {
  auto enc = LoadAndEncode(a.input, {});
  if (!enc.ok()) {
    ReportError(enc.status());
    return kExitFailure;
  }
  auto dec = silk::DecodeTokens(enc->tokens);
  if (!dec.ok()) {
    ReportError(dec.status().WithContext(a.input + ": decoding our own tokens: "));
    return kExitFailure;
  }
  const silk::RoundTripReport r = silk::CompareRoundTrip(*enc, *dec);
  if (a.json) {
    nlohmann::json j{{"file", a.input},
                     {"tokens", enc->tokens.size()},
                     {"processed_faces", r.processed_faces},
                     {"representable_faces", r.representable_faces},
                     {"recovered", r.recovered},
                     {"reversed", r.reversed},
                     {"missing", r.missing},
                     {"extra_faces", r.extra},
                     {"decoded_faces", dec->faces.size()},
                     {"exact", r.exact()}};
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("%s: %zu tokens; %lld processed faces, %lld representable: %lld recovered, %lld reversed, "
                "%lld missing; %lld extra faces (%zu decoded) -> %s\n",
                a.input.c_str(), enc->tokens.size(), static_cast<long long>(r.processed_faces),
                static_cast<long long>(r.representable_faces), static_cast<long long>(r.recovered),
                static_cast<long long>(r.reversed), static_cast<long long>(r.missing),
                static_cast<long long>(r.extra), dec->faces.size(), r.exact() ? "exact" : "NOT EXACT");
  }
  return r.exact() ? kExitOk : kExitFailure;
}

}  // namespace

void RegisterRoundtripCommand(CLI::App& app) {
  auto args = std::make_shared<RoundtripArgs>();
  CLI::App* cmd = app.add_subcommand(
      "roundtrip",
      "Encode a mesh, decode the tokens, and compare with the processed mesh: representable faces\n"
      "recovered, reversed windings, missing and extra faces. Exit 1 if a representable face is\n"
      "missing or reversed.");
  cmd->add_option("input", args->input, "Input mesh file")->required()->check(CLI::ExistingFile);
  cmd->add_flag("--json", args->json, "Print JSON instead of text (default: text)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
