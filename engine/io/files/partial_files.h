// SPDX-License-Identifier: MIT
// The temporaries of the atomic writes in progress, so a process ending on a signal can remove
// them from its handler (async-signal-safe: fixed slots, lock-free flags, unlink only).
#pragma once
#include <string>

namespace silk {

// Records `path` as a temporary being written; returns its slot, or -1 when every slot is taken
// (the write goes on untracked).
int RegisterPartialFile(const std::string& path);
// The write of `slot` ended (renamed into place or removed); -1 is ignored.
void ReleasePartialFile(int slot);
// Removes every registered temporary. Async-signal-safe.
void DiscardPartialFiles();

}  // namespace silk
