// SPDX-License-Identifier: MIT
// Why a generation stopped: the one enum the generator sets, the session, the report JSON,
// silk_generate_stats (silk_stop_reason, same values) and silkgen read, with its one name per reason.
#pragma once
#include <cstdint>

namespace silk {

enum class StopReason : int32_t {
  kNone = -1,  // still running
  kEos = 0,
  kMaxTokens = 1,
  kMaxFaces = 2,
  kGrammarDeadEnd = 3,  // no legal id left (a grammar bug; the closed part is kept)
  kCancelled = 4,
};

// "none", "eos", "max_tokens", "max_faces", "grammar_dead_end", "cancelled".
constexpr const char* StopReasonName(StopReason reason) {
  switch (reason) {
    case StopReason::kNone:
      return "none";
    case StopReason::kEos:
      return "eos";
    case StopReason::kMaxTokens:
      return "max_tokens";
    case StopReason::kMaxFaces:
      return "max_faces";
    case StopReason::kGrammarDeadEnd:
      return "grammar_dead_end";
    case StopReason::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

}  // namespace silk
