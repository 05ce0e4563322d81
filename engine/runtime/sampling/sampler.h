// SPDX-License-Identifier: MIT
// The sampling chain, built as llama.cpp builds one: small stages behind one interface, each
// narrowing the candidate ids of one step or choosing among them, assembled once per generation
// by BuildSamplerChain from the resolved settings and run per step by Generator:
//   grammar mask -> surface guidance -> face guidance | (face penalties) -> candidates
//   -> temperature -> top-k
//   -> (official top-p) -> softmax -> (top-p) -> draw; greedy (temperature <= 0): candidates ->
//   greedy draw. Stages: runtime/sampling/sampler_stages.h (numeric), runtime/sampling/legal_stages.h (legality).
// Every draw comes from one seeded SplitMix64, so tests/models/reference_loop.py reproduces the
// chain bit for bit.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/splitmix64.h"
#include "decoder/token_mask.h"

namespace silk {

class Grammar;
class SurfaceGuide;
class FaceGuide;
enum class FaceGuidance : int32_t;
struct GenerationStats;

struct SamplingParams {
  double temperature = 1.0;      // <= 0: greedy (largest logit, lowest id on ties; no draw)
  int32_t top_k = 0;             // 0: off
  double top_p = 1.0;            // >= 1: off
  double top_p_temperature = 0;  // > 0: top-p computed at this temperature (official chain)
  uint64_t seed = 0;
};

// Face guidance's verdict on one step, for the trace: not judged (forced, off, or an id kind it
// does not judge), some legal id passed, or none did (the fallback kept the best-scoring ones).
enum class FaceVerdict : int8_t { kNotJudged = 0, kPassed = 1, kFallback = 2 };

// What the stages of one step share. Before the logits: the forced id and the mask; then the
// candidate ids, their scores (best first once ranked), the survivors' weights, the choice.
struct SamplerCandidates {
  int32_t forced = -1;              // the grammar's only legal id, or -1
  const TokenMask* mask = nullptr;  // the ids that may be chosen; null: every id but PAD
  // Soft face guidance: logit penalties (id, amount subtracted) of this step; null: none.
  const std::vector<std::pair<int32_t, float>>* penalties = nullptr;
  FaceVerdict face = FaceVerdict::kNotJudged;      // face guidance's verdict (the trace records it)
  const float* logits = nullptr;                   // vocab::k_model_vocab_size entries
  std::vector<int32_t> ids;                        // the candidates, ascending
  std::vector<std::pair<double, int32_t>> scored;  // (score, id)
  std::vector<double> probs;                       // unnormalised weights of the first `keep` of scored
  size_t keep = 0;                                 // survivors: the first `keep` of scored
  double mass = 0;                                 // the sum of probs over the survivors
  int32_t id = -1;                                 // the choice (-1: none)
  bool done = false;                               // the choice is made (or there is none): later stages are skipped
};

class SamplerStage {
 public:
  virtual ~SamplerStage() = default;
  virtual void Apply(SamplerCandidates* c) = 0;
};

class SamplerChain {
 public:
  // `rng`: the generation's one seeded stream, every draw of every stage.
  explicit SamplerChain(std::shared_ptr<SplitMix64> rng) : rng_(std::move(rng)) {}

  // Stages that need no logits (grammar mask, surface guidance), run by Narrow, in order.
  void AddBeforeLogits(std::unique_ptr<SamplerStage> stage) { before_logits_.push_back(std::move(stage)); }
  // Stages on the logits, run by Sample, in order.
  void Add(std::unique_ptr<SamplerStage> stage) { on_logits_.push_back(std::move(stage)); }
  SplitMix64* rng() const { return rng_.get(); }

  // A step's start, before the decoder runs: the forced id and the mask to sample from (an
  // empty mask: a dead end; the later stages are skipped).
  const SamplerCandidates& Narrow();
  // The id chosen among the ids of `mask` (null: every id but PAD); -1 when there is none.
  int32_t Sample(const float* logits, const TokenMask* mask);

 private:
  std::shared_ptr<SplitMix64> rng_;
  std::vector<std::unique_ptr<SamplerStage>> before_logits_, on_logits_;
  SamplerCandidates c_;
};

// The resolved settings of one generation's chain.
struct SamplerChainSettings {
  SamplingParams sampling;
  Grammar* grammar = nullptr;             // the grammar mask's source; null: no mask (unconstrained)
  const SurfaceGuide* guide = nullptr;    // surface guidance (needs the grammar); null: off
  const FaceGuide* face_guide = nullptr;  // face guidance (needs the grammar); null: off
  FaceGuidance face_mode{};               // kHard or kSoft when face_guide is set
  GenerationStats* stats = nullptr;       // counters and phase seconds of the stages; may be null
};

std::unique_ptr<SamplerChain> BuildSamplerChain(const SamplerChainSettings& settings);

}  // namespace silk
