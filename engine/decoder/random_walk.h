// SPDX-License-Identifier: MIT
// Seeded random legal sequences: ids drawn uniformly from the grammar's legal masks, with a
// bias toward closing layers (a target size per layer) so walks end. For property tests,
// `silktok sample` and benchmarks.
#pragma once
#include <cstdint>
#include <random>
#include <vector>

#include "decoder/grammar.h"

namespace silk {

struct RandomWalkOptions {
  int32_t max_components = 2;
  int32_t max_layers = 6;       // per component (index of the last layer)
  int32_t max_layer_size = 12;  // target sizes are drawn from [1, max_layer_size]
  double extra_b = 0.15;        // chance of a continuation B token when legal
  double extra_x = 0.05;        // chance of a free X token when legal
  double sparse = 0.85;         // chance of drawing S/B only among ids stating <= 2 edges
                                // (keeps random graphs mesh-like; 0 = uniform over the mask)
};

// Runs one walk from `grammar`'s current state (normally reset) until EOS; returns the ids
// accepted (EOS included). Never returns an illegal id; stops early (without EOS) only if a
// step finds an empty legal set, which would be a grammar bug.
std::vector<int32_t> RandomLegalWalk(Grammar* grammar, std::mt19937_64* rng, const RandomWalkOptions& options = {});

}  // namespace silk
