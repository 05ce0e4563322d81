// SPDX-License-Identifier: MIT
// Best of N's parts: seed derivation, Chamfer scoring in the model frame, the running choice.
#include "runtime/candidates.h"

#include <chrono>
#include <cmath>
#include <initializer_list>
#include <utility>

#include "core/splitmix64.h"
#include "mesh/chamfer_distance.h"
#include "mesh/point_preprocessing.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {

namespace {
// Surface samples per candidate: enough for a stable mean (the encoder sees 4,096 points).
constexpr int32_t kScoreSamples = 4096;
constexpr uint64_t kScoreSeed = 0x5CE1E;

using Clock = std::chrono::steady_clock;

CandidateScore Entry(const GenerateResult& r, uint64_t seed, double score) {
  CandidateScore c;
  c.seed = seed;
  c.score = score;
  c.faces = static_cast<int32_t>(r.mesh.faces.size());
  c.tokens = static_cast<int64_t>(r.tokens.size());
  c.seconds = r.stats.generation_seconds;
  return c;
}

// a beats b: faces first (an empty mesh never wins), then the lower score.
bool Better(const CandidateScore& a, const CandidateScore& b) {
  if ((a.faces > 0) != (b.faces > 0)) return a.faces > 0;
  return a.score < b.score;
}
}  // namespace

uint64_t CandidateSeed(uint64_t seed, int32_t index) {
  if (index == 0) return seed;
  SplitMix64 rng(seed + static_cast<uint64_t>(index));
  return rng.Next();
}

StatusOr<double> ScoreAgainstPoints(const TokenizerDecodedMesh& mesh, const std::vector<float>& points,
                                    const CancelCheck& cancel) {
  if (CancelRequested(cancel)) return CancelledStatus("scoring");  // before copying up to 2^20 points
  IoMesh m;
  m.positions = DequantizePositions(mesh.positions);
  m.triangles = mesh.faces;
  SILK_ASSIGN_OR_RETURN(const ChamferDistance d,
                        MeshToPointsChamfer(m, PointRowPositions(points), kScoreSamples, kScoreSeed, cancel));
  return d.value();
}

double ScoreAgainstPoints(const TokenizerDecodedMesh& mesh, const std::vector<float>& points) {
  return ScoreAgainstPoints(mesh, points, CancelCheck{}).value();
}

Status CandidateChoice::Add(GenerateResult* r, uint64_t seed, const std::vector<float>& points,
                            const CancelCheck& cancel) {
  const auto t0 = Clock::now();
  SILK_ASSIGN_OR_RETURN(const double score, ScoreAgainstPoints(r->mesh, points, cancel));
  all_.push_back(Entry(*r, seed, score));
  r->stats.seconds.scoring += std::chrono::duration<double>(Clock::now() - t0).count();
  const PhaseSeconds& s = r->stats.seconds;
  using Sum = std::pair<double*, double>;
  for (const Sum& e : std::initializer_list<Sum>{{&total_.encoder, s.encoder},
                                                 {&total_.decoder, s.decoder},
                                                 {&total_.grammar, s.grammar},
                                                 {&total_.sampling, s.sampling},
                                                 {&total_.build_mesh, s.build_mesh},
                                                 {&total_.guidance, s.guidance},
                                                 {&total_.face_guidance, s.face_guidance},
                                                 {&total_.scoring, s.scoring}})
    *e.first += e.second;
  generation_seconds_ += r->stats.generation_seconds;
  const int32_t index = size() - 1;
  if (index == 0 || Better(all_.back(), all_[static_cast<size_t>(chosen_)])) {
    chosen_ = index;
    best_ = std::move(*r);
  }
  return Status::Ok();
}

GenerateResult CandidateChoice::Take() {
  GenerateResult best = std::move(best_);
  best.stats.candidates = std::move(all_);
  best.stats.chosen_candidate = chosen_;
  best.stats.seconds = total_;
  best.stats.generation_seconds = generation_seconds_;
  *this = CandidateChoice{};
  return best;
}

Status ScoreWaiting(int32_t next, std::vector<std::optional<GenerateResult>>* waiting,
                    const std::function<Status(int32_t index, GenerateResult* result)>& score) {
  for (size_t i = static_cast<size_t>(next); i < waiting->size() && (*waiting)[i]; ++i) {
    SILK_RETURN_IF_ERROR(score(static_cast<int32_t>(i), &*(*waiting)[i]));
    (*waiting)[i].reset();
  }
  return Status::Ok();
}

}  // namespace silk
