// SPDX-License-Identifier: MIT
// The numeric stages of the sampling chain (runtime/sampling/sampler.h), one small class each, and the
// function that appends them in order for a set of SamplingParams.
#pragma once
#include "runtime/sampling/sampler.h"

namespace silk {

// Appends candidates -> greedy draw (temperature <= 0), or candidates -> temperature -> top-k ->
// (official top-p, when top_p_temperature > 0) -> softmax -> (top-p, otherwise) -> draw; the
// top-p stages only when top_p < 1. The draw uses chain->rng().
void AddSamplingStages(SamplerChain* chain, const SamplingParams& params);

}  // namespace silk
