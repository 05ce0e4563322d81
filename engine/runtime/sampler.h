// Sampler: the token sampling chain, applied to the logits of the legal ids only (the
// grammar mask comes first): temperature -> top-k -> top-p -> one uniform draw from a seeded
// SplitMix64. Fully specified so tests/models/reference_loop.py reproduces it exactly.
// With top_p_temperature > 0 the chain is the official one (official_network.md §4): top-k on the
// logits, top-p on softmax(survivors / top_p_temperature) keeping the top id and the one that
// crosses top_p, then softmax(kept / temperature) and the draw.
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/splitmix64.h"
#include "decoder/token_mask.h"

namespace silk {

struct SamplingParams {
  double temperature = 1.0;  // <= 0: greedy (largest logit, lowest id on ties; no draw)
  int32_t top_k = 0;         // 0: off
  double top_p = 1.0;        // >= 1: off
  double top_p_temperature = 0;  // > 0: top-p computed at this temperature (official chain)
  uint64_t seed = 0;
};

class Sampler {
 public:
  explicit Sampler(const SamplingParams& params) : params_(params), rng_(params.seed) {}

  // Samples among the ids set in `legal` (nullptr: every id of logits except PAD). Returns -1
  // when no id is allowed. `logits` has vocab::k_model_vocab_size entries.
  int32_t Sample(const float* logits, const TokenMask* legal);
  // Same chain over an explicit candidate list (ascending ids).
  int32_t SampleFrom(const float* logits, const std::vector<int32_t>& candidates);

  const SamplingParams& params() const { return params_; }

 private:
  SamplingParams params_;
  SplitMix64 rng_;
  std::vector<int32_t> ids_;
  std::vector<std::pair<double, int32_t>> scored_;
  std::vector<double> probs_;

  // How many of the first `keep` sorted candidates the official top-p rule keeps.
  size_t OfficialTopP(const float* logits, size_t keep);
};

}  // namespace silk
