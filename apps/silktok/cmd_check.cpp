// `silktok check`: run a token file through the grammar state machine; report the first
// illegal token (position, id, reason) or accept. Replays files the grammar tests dump.
#include <cstdio>

#include "commands.h"
#include "decoder/grammar.h"
#include "io/token_text.h"
#include "mesh_input.h"

namespace silktok {
namespace {

struct CheckArgs {
  std::string input;
  int32_t max_length = 10240;
  bool union_windows = false;
  bool allow_prefix = false;
};

int Run(const CheckArgs& a) {
  auto ids = silk::ReadTokenText(a.input);
  if (!ids.ok()) {
    ReportError(ids.status());
    return kExitFailure;
  }
  silk::GrammarOptions opt;
  opt.max_length = a.max_length;
  opt.window_rule = a.union_windows ? silk::WindowRule::kUnion : silk::WindowRule::kCanonical;
  size_t pos = 0;
  silk::Rejection r = silk::CheckTokens(*ids, opt, &pos, !a.allow_prefix);
  if (!r.ok()) {
    std::fprintf(stderr, "%s: illegal at position %zu (id %d): %s [%s]\n", a.input.c_str(), pos,
                 pos < ids->size() ? (*ids)[pos] : -1, r.message.c_str(), silk::RejectReasonName(r.reason));
    return kExitFailure;
  }
  std::printf("%s: %zu tokens accepted\n", a.input.c_str(), ids->size());
  return kExitOk;
}

}  // namespace

void RegisterCheckCommand(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Check a token file (one id per line, EOS 10267 optional at the end) against the grammar of\n"
      "spec §11 token by token. Prints the first illegal token's position, id and reason and exits 1,\n"
      "or exits 0.");
  cmd->add_option("input", args->input, "Token file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--max-length", args->max_length,
                  "Length limit in tokens including EOS; 0 = unlimited (default: 10240, spec §9)");
  cmd->add_flag("--union-windows", args->union_windows,
                "Accept self-layer rows that disagree about a pair, as the official decoder does (default: off)");
  cmd->add_flag("--prefix", args->allow_prefix, "Accept a sequence that stops inside a component (default: off)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
