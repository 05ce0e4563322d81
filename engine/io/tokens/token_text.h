// SPDX-License-Identifier: MIT
// The token-file format shared by silktok, the dataset builder and the goldens: one decimal
// token id per line, nothing else (shared/spec/golden/*.tokens.txt).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace silk {

// Strict: every non-empty line must be one integer in [-1, 2^31); errors name file and line.
// Files larger than max_bytes are refused before reading.
StatusOr<std::vector<int32_t>> ReadTokenText(const std::string& path, size_t max_bytes = size_t{1} << 28);
StatusOr<std::vector<int32_t>> ParseTokenText(const std::string& text, const std::string& name);
std::string FormatTokenText(const std::vector<int32_t>& ids);

}  // namespace silk
