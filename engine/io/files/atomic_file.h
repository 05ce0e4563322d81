// SPDX-License-Identifier: MIT
// Atomic file output: a reader of `path` sees either the old file or the complete new one,
// never a partial write (a hidden temporary in the same folder, fsync, rename).
#pragma once
#include <cstddef>
#include <string>

#include "core/status.h"

namespace silk {

// The longest temporary name the writer makes: NAME_MAX of the common file systems.
constexpr size_t kTemporaryNameLimit = 255;

// On any failure the temp file is removed and `path` is left untouched. While the write is in
// progress the temporary is registered with DiscardPartialFiles (partial_files.h).
Status WriteFileAtomically(const std::string& path, const std::string& bytes);
// The temporary `path` is written through (exposed for the tests): hidden, in the same folder.
std::string TemporaryPathFor(const std::string& path, unsigned long pid, unsigned attempt);

}  // namespace silk
