// SPDX-License-Identifier: MIT
// Atomic file output: a reader of `path` sees either the old file or the complete new one,
// never a partial write (temp file in the same folder, fsync, rename).
#pragma once
#include <string>

#include "core/status.h"

namespace silk {

// On any failure the temp file is removed and `path` is left untouched.
Status WriteFileAtomically(const std::string& path, const std::string& bytes);

}  // namespace silk
