// SPDX-License-Identifier: MIT
// Names of grammar rejection reasons, for messages, replay files and JSON reports.
#include "decoder/grammar_rejection.h"

namespace silk {

const char* RejectReasonName(RejectReason r) {
  switch (r) {
    case RejectReason::kNone:
      return "none";
    case RejectReason::kOutOfVocabulary:
      return "out_of_vocabulary";
    case RejectReason::kPadToken:
      return "pad_token";
    case RejectReason::kAfterEos:
      return "after_eos";
    case RejectReason::kWrongClass:
      return "wrong_class";
    case RejectReason::kEosNotAfterE:
      return "eos_not_after_e";
    case RejectReason::kLayerZeroSize:
      return "layer_zero_size";
    case RejectReason::kXNotIncreasing:
      return "x_not_increasing";
    case RejectReason::kXOutOfRange:
      return "x_out_of_range";
    case RejectReason::kWindowBeyondLayer:
      return "window_beyond_layer";
    case RejectReason::kNotCanonical:
      return "not_canonical";
    case RejectReason::kBOutsidePrevLayer:
      return "b_outside_prev_layer";
    case RejectReason::kBContinuation:
      return "b_continuation";
    case RejectReason::kLayerNotClosable:
      return "layer_not_closable";
    case RejectReason::kLayerTooLarge:
      return "layer_too_large";
    case RejectReason::kTooManyLayers:
      return "too_many_layers";
    case RejectReason::kTooLong:
      return "too_long";
    case RejectReason::kZeroLengthEdge:
      return "zero_length_edge";
    case RejectReason::kIncomplete:
      return "incomplete";
  }
  return "unknown";
}

}  // namespace silk
