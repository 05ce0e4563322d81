// SPDX-License-Identifier: MIT
// silktok subcommands: each lives in its own cmd_*.cpp and registers itself on the app.
#pragma once
#include <CLI/CLI.hpp>

namespace silktok {

void RegisterEncodeCommand(CLI::App& app);
void RegisterDecodeCommand(CLI::App& app);
void RegisterStatsCommand(CLI::App& app);
void RegisterRoundtripCommand(CLI::App& app);
void RegisterCheckCommand(CLI::App& app);
void RegisterRepairCommand(CLI::App& app);
void RegisterSampleCommand(CLI::App& app);

// The exit code the chosen subcommand's callback produced.
int& ExitCode();

// Exit codes shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;  // bad input, I/O error, refused mesh, failed check
inline constexpr int kExitUsage = 2;    // command-line error (CLI11)

}  // namespace silktok
