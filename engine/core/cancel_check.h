// SPDX-License-Identifier: MIT
// A stop request that long loops in the lower layers (point sampling, pre-processing) poll without
// knowing who asks: the runtime hands its generator's cancel flag and callback down as this.
#pragma once
#include <cstdint>
#include <functional>

#include "core/status.h"

namespace silk {

// Returns true to stop. Empty: never stops.
using CancelCheck = std::function<bool()>;

// Loops poll once per this many iterations (a poll costs a call; 64 K samples take ~5 ms).
inline constexpr int64_t kCancelPollInterval = 65536;

inline bool CancelRequested(const CancelCheck& cancel) { return cancel && cancel(); }

inline Status CancelledStatus(const std::string& during) {
  return Status(StatusCode::kCancelled, "generation cancelled during " + during);
}

}  // namespace silk
