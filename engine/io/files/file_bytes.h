// SPDX-License-Identifier: MIT
// Reads a whole file into memory with a size limit; errors name the path and the OS reason.
#pragma once
#include <cstdint>
#include <string>

#include "core/status.h"

namespace silk {

StatusOr<std::string> ReadFileBytes(const std::string& path, uint64_t max_bytes);

}  // namespace silk
