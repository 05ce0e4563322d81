// SPDX-License-Identifier: MIT
// `silktok check`: run a token file through the grammar state machine; report the first
// illegal token (position, id, reason) or accept. Replays files the grammar tests dump.
#include <cstdio>

#include "../common/app_files.h"
#include "commands.h"
#include "cli_errors.h"

namespace silktok {
namespace {

struct CheckArgs {
  std::string input;
  int32_t max_length = 10240;
  bool union_windows = false;
  bool allow_prefix = false;
};

int Run(const CheckArgs& a) {
  silk_check_params p = silk_check_default_params();
  p.max_length = a.max_length;
  p.window_rule = a.union_windows ? SILK_WINDOW_UNION : SILK_WINDOW_CANONICAL;
  p.allow_prefix = a.allow_prefix ? 1 : 0;
  size_t count = 0;
  silk_check_result r = silk_cpp::Sized<silk_check_result>();
  try {
    const silk_cpp::Tokens tokens = silk_cpp::Tokens::Load(a.input);
    count = tokens.size();
    r = tokens.GrammarCheck(p);
  } catch (const silk_cpp::Error& e) {
    ReportError(e);
    return kExitFailure;
  }
  if (!r.accepted) {
    std::fprintf(stderr, "%s: illegal at position %lld (id %d): %s [%s]\n", a.input.c_str(),
                 static_cast<long long>(r.position), r.id, r.message, silk_reject_reason_name(r.reason));
    return kExitFailure;
  }
  std::printf("%s: %zu tokens accepted\n", a.input.c_str(), count);
  return kExitOk;
}

}  // namespace

void RegisterCheckCommand(CLI::App& app) {
  auto args = std::make_shared<CheckArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Check a token file (one id per line, EOS 10267 optional at the end) against the grammar of\n"
      "token_format.md §11 token by token. Prints the first illegal token's position, id and reason and exits 1,\n"
      "or exits 0.");
  cmd->add_option("input", args->input, "Token file")->required()->check(silkapp::ExistingFile());
  cmd->add_option("--max-length", args->max_length,
                  "Length limit in tokens including EOS; 0 = unlimited (default: 10240, token_format.md §9)");
  cmd->add_flag("--union-windows", args->union_windows,
                "Accept self-layer rows that disagree about a pair, as the official decoder does (default: off)");
  cmd->add_flag("--prefix", args->allow_prefix, "Accept a sequence that stops inside a component (default: off)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
