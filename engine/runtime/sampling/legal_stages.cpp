// SPDX-License-Identifier: MIT
// The grammar mask and surface guidance stages (runtime/sampling/legal_stages.h).
#include "runtime/sampling/legal_stages.h"

#include <chrono>

#include "decoder/grammar.h"
#include "runtime/generation_stats.h"
#include "runtime/sampling/surface_guide.h"
#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

class GrammarMaskStage : public SamplerStage {
 public:
  GrammarMaskStage(Grammar* grammar, GenerationStats* stats) : grammar_(grammar), stats_(stats) {}
  void Apply(SamplerCandidates* c) override {
    const auto t0 = Clock::now();
    c->forced = grammar_->Forced();
    c->mask = &grammar_->LegalMask();
    if (stats_) stats_->seconds.grammar += Since(t0);
    c->done = c->mask->Empty();
  }

 private:
  Grammar* grammar_;
  GenerationStats* stats_;
};

class SurfaceGuideStage : public SamplerStage {
 public:
  SurfaceGuideStage(const SurfaceGuide* guide, const Grammar* grammar, GenerationStats* stats)
      : guide_(guide), grammar_(grammar), stats_(stats ? stats : &own_stats_) {}
  void Apply(SamplerCandidates* c) override {
    const auto t0 = Clock::now();
    const bool offsets = grammar_->phase() == GrammarPhase::kWantO;
    const int32_t block = offsets ? grammar_->tokens().back() : -1;  // the K id just taken
    if (c->forced >= 0) {
      CheckForced(c->forced, offsets, block);
      stats_->seconds.guidance += Since(t0);
      return;
    }
    const int32_t first_k = c->mask->Next(vocab::kKBegin);
    if (!offsets && (first_k < 0 || first_k >= vocab::kKEnd)) return;  // no vertex id legal now
    guided_ = *c->mask;
    const bool fallback = offsets ? guide_->RestrictOffsets(block, &guided_) : guide_->RestrictBlocks(&guided_);
    c->mask = &guided_;
    ++stats_->guided_tokens;
    stats_->guidance_fallbacks += fallback ? 1 : 0;
    stats_->seconds.guidance += Since(t0);
  }

 private:
  // A forced block or offset id outside the tolerance is a fallback too.
  void CheckForced(int32_t id, bool offsets, int32_t block) {
    if (id >= vocab::kKBegin && id < vocab::kKEnd)
      stats_->guidance_fallbacks += guide_->Within(guide_->BlockDistance2(id - vocab::kKBegin)) ? 0 : 1;
    else if (offsets && id >= vocab::kOBegin && id < vocab::kOEnd)
      stats_->guidance_fallbacks += guide_->Within(guide_->CellDistance2(VertexOfTokens(block, id))) ? 0 : 1;
  }
  const SurfaceGuide* guide_;
  const Grammar* grammar_;
  GenerationStats own_stats_;  // when the caller keeps none
  GenerationStats* stats_;
  TokenMask guided_;  // the legal mask after guidance (what is sampled from)
};

}  // namespace

std::unique_ptr<SamplerStage> MakeGrammarMaskStage(Grammar* grammar, GenerationStats* stats) {
  return std::make_unique<GrammarMaskStage>(grammar, stats);
}

std::unique_ptr<SamplerStage> MakeSurfaceGuideStage(const SurfaceGuide* guide, const Grammar* grammar,
                                                    GenerationStats* stats) {
  return std::make_unique<SurfaceGuideStage>(guide, grammar, stats);
}

}  // namespace silk
