// SPDX-License-Identifier: MIT
// Best of N's parts: the candidates' seeds, their score (symmetric Chamfer distance from a
// candidate's surface samples to the encoder's points) and the running choice of the closest.
// GenerationSession (runtime/generation_session.h) runs the candidates.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
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

// The choice among the candidates of one input, added in order: each scored, the lowest score
// kept (the earliest on ties; a candidate with faces always beats one without), the phase times
// summed over all.
class CandidateChoice {
 public:
  // Scores `*result` (generated with `seed`) against `points`, polling `cancel`; kCancelled leaves
  // `*result` and the choice as they were. Otherwise the result is taken when it is the best so far.
  Status Add(GenerateResult* result, uint64_t seed, const std::vector<float>& points, const CancelCheck& cancel);
  int32_t size() const { return static_cast<int32_t>(all_.size()); }
  const std::vector<CandidateScore>& scored() const { return all_; }  // in order
  int32_t chosen() const { return chosen_; }                          // the best so far (0 when none)
  // The chosen one, with stats.candidates listing every candidate, stats.chosen_candidate its
  // index, and stats.seconds / generation_seconds covering all candidates. Leaves the choice empty.
  GenerateResult Take();

 private:
  GenerateResult best_;
  std::vector<CandidateScore> all_;
  int32_t chosen_ = 0;
  PhaseSeconds total_;
  double generation_seconds_ = 0;
};

// Candidates scored in candidate order however their rows end: waiting[i] holds candidate i's
// result once it has ended; from candidate `next` (the first not yet scored) on, while there is
// one, `score(i, result)` runs and the result is cleared. Stops at the first error.
Status ScoreWaiting(int32_t next, std::vector<std::optional<GenerateResult>>* waiting,
                    const std::function<Status(int32_t index, GenerateResult* result)>& score);

}  // namespace silk
