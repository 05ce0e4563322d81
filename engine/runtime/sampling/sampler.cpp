// SPDX-License-Identifier: MIT
// The chain's runner and its one assembly from the resolved settings (runtime/sampling/sampler.h).
#include "runtime/sampling/sampler.h"

#include "runtime/generation_stats.h"
#include "runtime/sampling/face_guide_stage.h"
#include "runtime/sampling/legal_stages.h"
#include "runtime/sampling/sampler_stages.h"

namespace silk {

const SamplerCandidates& SamplerChain::Narrow() {
  c_.forced = -1;
  c_.mask = nullptr;
  c_.penalties = nullptr;
  c_.face = FaceVerdict::kNotJudged;
  c_.id = -1;
  c_.done = false;
  for (const auto& stage : before_logits_) {
    if (c_.done) break;
    stage->Apply(&c_);
  }
  return c_;
}

int32_t SamplerChain::Sample(const float* logits, const TokenMask* mask) {
  c_.logits = logits;
  c_.mask = mask;
  c_.id = -1;
  c_.done = false;
  for (const auto& stage : on_logits_) {
    if (c_.done) break;
    stage->Apply(&c_);
  }
  return c_.id;
}

std::unique_ptr<SamplerChain> BuildSamplerChain(const SamplerChainSettings& s) {
  auto rng = std::make_shared<SplitMix64>(s.sampling.seed);
  auto chain = std::make_unique<SamplerChain>(rng);
  if (s.grammar) {
    chain->AddBeforeLogits(MakeGrammarMaskStage(s.grammar, s.stats));
    if (s.guide) chain->AddBeforeLogits(MakeSurfaceGuideStage(s.guide, s.grammar, s.stats));
    if (s.face_guide) {
      chain->AddBeforeLogits(MakeFaceGuideStage(s.face_guide, s.face_mode, s.grammar, s.stats));
      if (s.face_mode == FaceGuidance::kSoft) chain->Add(MakeFacePenaltyStage());
    }
  }
  AddSamplingStages(chain.get(), s.sampling);
  return chain;
}

}  // namespace silk
