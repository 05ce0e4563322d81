// SPDX-License-Identifier: MIT
// Small file-system helpers for tools that write outputs (folders for batch outputs).
#pragma once
#include <string>

#include "core/status.h"

namespace silk {

bool IsDirectory(const std::string& path);
bool IsRegularFile(const std::string& path);
// mkdir -p; ok if it already exists as a folder.
Status MakeDirectories(const std::string& path);

}  // namespace silk
