// Best of N: several generations of one input with derived seeds, the one closest to the input
// kept (symmetric Chamfer distance from its surface samples to the encoder's points).
#pragma once
#include <cstdint>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "runtime/generator.h"

namespace silk {

// Candidate i's sampling seed: i = 0 is the seed itself (so N = 1 is exactly a plain run);
// i >= 1 is the first output of SplitMix64 seeded with seed + i.
uint64_t CandidateSeed(uint64_t seed, int32_t index);

// Surface samples of a generated mesh (grid coordinates, dequantised to the model frame) scored
// against the encoder's points (rows of 6 floats, xyz first): the symmetric Chamfer distance
// (mean of both directions, like silk-export eval's CD; one direction alone would reward a
// small patch lying on the surface). +infinity for a mesh without a face of positive area.
double ScoreAgainstPoints(const TokenizerDecodedMesh& mesh, const std::vector<float>& points);
// The same, polling `cancel` in chunks (kCancelled when it asks to stop; the score is identical).
StatusOr<double> ScoreAgainstPoints(const TokenizerDecodedMesh& mesh, const std::vector<float>& points,
                                    const CancelCheck& cancel);

// options.candidates generations with CandidateSeed(options.sampling.seed, i), each a full
// Generator::Run on the same points (the decoder graph has batch 1, docs/runtime.md). Returns the
// lowest-scoring one (the earliest on ties; a candidate with faces always beats one without),
// with stats.candidates listing every candidate and stats.chosen_candidate its index; the
// stats' times cover all candidates. A failure or cancel of any candidate fails the whole.
// `scoring_cancel` is polled while candidates are scored (callbacks.cancel is not, so a caller's
// callback sees the polls it always saw).
StatusOr<GenerateResult> RunCandidates(Generator* generator, const std::vector<float>& points,
                                       const GenerateOptions& options, const GenerateCallbacks& callbacks = {},
                                       const CancelCheck& scoring_cancel = {});

// Puts a single generation's own entry (its seed, score) into stats.candidates (index 0);
// kCancelled (nothing put) when `cancel` stops the scoring.
Status ScoreSingle(GenerateResult* result, uint64_t seed, const std::vector<float>& points,
                   const CancelCheck& cancel = {});

}  // namespace silk
