// SPDX-License-Identifier: MIT
// silktok: tokenize, decode, check, inspect and repair Mesh Silksong token streams.
#include <cstdio>

#include "../common/interrupt.h"
#include "../common/utf8_args.h"
#include "commands.h"
#include "silk/silk.h"

namespace silktok {
int& ExitCode() {
  static int code = kExitOk;
  return code;
}
}  // namespace silktok

int main(int argc, char** argv) {
  silkapp::UseUtf8Arguments(argc, argv);                   // Windows: UTF-8, not the ANSI code page
  silkapp::HandleInterrupts(silkapp::OnInterrupt::kExit);  // no partial file left by a signal
  CLI::App app{"silktok — Mesh Silksong tokenizer tools (token format v1, 128 bins)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", silk_version());
  silktok::RegisterEncodeCommand(app);
  silktok::RegisterDecodeCommand(app);
  silktok::RegisterStatsCommand(app);
  silktok::RegisterRoundtripCommand(app);
  silktok::RegisterCheckCommand(app);
  silktok::RegisterRepairCommand(app);
  silktok::RegisterSampleCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : silktok::kExitUsage;
  }
  return silktok::ExitCode();
}
