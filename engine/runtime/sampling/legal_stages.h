// SPDX-License-Identifier: MIT
// The legality stages of the sampling chain (runtime/sampling/sampler.h): which ids may be chosen. The
// grammar mask and surface guidance narrow the mask before the decoder runs.
#pragma once
#include <cstdint>
#include <memory>

#include "runtime/sampling/sampler.h"

namespace silk {

// The grammar's forced id (or -1) and legal mask; an empty mask ends the step (a dead end).
// Its time counts as stats->seconds.grammar.
std::unique_ptr<SamplerStage> MakeGrammarMaskStage(Grammar* grammar, GenerationStats* stats);

// Surface guidance after the grammar mask: vertex ids restricted to the guide's tolerance
// (stats->guided_tokens), a forced vertex id checked; legal ids off the surface when no legal id
// is within it count as stats->guidance_fallbacks. Time: stats->seconds.guidance.
std::unique_ptr<SamplerStage> MakeSurfaceGuideStage(const SurfaceGuide* guide, const Grammar* grammar,
                                                    GenerationStats* stats);

}  // namespace silk
