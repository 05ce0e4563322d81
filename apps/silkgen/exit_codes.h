// SPDX-License-Identifier: MIT
// silkgen's exit statuses, shared by the single-input and --batch modes.
#pragma once

namespace silkgen {

constexpr int kExitOk = 0, kExitFail = 1, kExitUsage = 2;

}  // namespace silkgen
