// SPDX-License-Identifier: MIT
// silktok's check before any work of a subcommand that writes: every output name is one the file
// system holds (silk_file_check_output) and no output is an input or another output
// (common/file_roles.h: Silk never writes to a file it reads).
#pragma once
#include <string>
#include <vector>

namespace silktok {

// kExitOk, or kExitFailure after printing "silktok: invalid argument: ..." naming both files.
int CheckOutputs(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs);

}  // namespace silktok
