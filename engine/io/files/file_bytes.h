// SPDX-License-Identifier: MIT
// Reads a whole file into memory with a size limit; errors name the path and the OS reason.
// The one place Silk opens a file for reading: only regular files are read (FIFOs, devices,
// sockets and folders are refused by type, before opening).
#pragma once
#include <cstdint>
#include <string>

#include "core/status.h"

namespace silk {

// Ok for a regular file (symlinks followed), with its size in *size when given; an IoError naming
// the path and what it is otherwise.
Status CheckRegularFile(const std::string& path, uint64_t* size = nullptr);
StatusOr<std::string> ReadFileBytes(const std::string& path, uint64_t max_bytes);

}  // namespace silk
