// SPDX-License-Identifier: MIT
// Why the grammar refused a token: a stable enum (for tests and tools) plus a message naming
// the position, the id and the rule (spec section) that it breaks.
#pragma once
#include <cstdint>
#include <string>

namespace silk {

enum class RejectReason : int32_t {
  kNone = 0,
  kOutOfVocabulary,    // id < 0 or id >= model vocabulary
  kPadToken,           // PAD is never part of a sequence (token_format.md §9)
  kAfterEos,           // nothing follows EOS
  kWrongClass,         // token class not legal in this state (token_format.md §11.1)
  kEosNotAfterE,       // EOS only after the E of a component (token_format.md §9, §11.4)
  kLayerZeroSize,      // layer 0 holds exactly the root (token_format.md §8.3)
  kXNotIncreasing,     // X values strictly increasing within a vertex (§11.2)
  kXOutOfRange,        // X value outside [8, 190] or beyond the layer's limit N-10 (§6)
  kWindowBeyondLayer,  // S bit at a distance >= N for every size N still possible (§11.2)
  kNotCanonical,       // S/X/B token leaves no layer size at which the layer is canonical
  kBOutsidePrevLayer,  // B segment reaches past the previous layer (§11.3)
  kBContinuation,      // B start before the continuation minimum (§7.3, §11.3)
  kLayerNotClosable,   // U/E at a layer size where a deferred rule fails (§11.2, §11.4)
  kLayerTooLarge,      // more than 200 vertices in a layer (§1.3)
  kTooManyLayers,      // layer index 200 or more (§1.3)
  kTooLong,            // over the length limit incl. EOS (§9)
  kZeroLengthEdge,     // edge between two vertices at the same position (geometric rule)
  kIncomplete,         // the ids end inside a component (token_format.md §11.1: must end after E)
};

const char* RejectReasonName(RejectReason r);

struct Rejection {
  RejectReason reason = RejectReason::kNone;
  std::string message;
  bool ok() const { return reason == RejectReason::kNone; }
};

}  // namespace silk
