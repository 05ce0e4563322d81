// SPDX-License-Identifier: MIT
// Whether a path can name an output file, decided before any work: an operator's run should not
// generate for minutes and then fail on a name the file system cannot hold.
#pragma once
#include <string>

#include "core/status.h"

namespace silk {

// Ok, or InvalidArgument naming the path and the problem: empty, a folder (existing, or the name
// ends in a separator, ".", ".."), a file name longer than the folder's file system holds
// (pathconf NAME_MAX; 255 bytes where unknown); IoError for a folder that does not exist. On Windows also the
// reserved device names (CON, NUL, COM1, ... with any extension), the characters <>:"|?* and
// control characters, a trailing dot or space, and a path past MAX_PATH without the \\?\ prefix.
// Creates nothing.
Status CheckOutputPath(const std::string& path);

}  // namespace silk
