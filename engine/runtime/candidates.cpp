// Best of N over Generator::Run: seed derivation, Chamfer scoring in the model frame, choice.
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

Status ScoreSingle(GenerateResult* result, uint64_t seed, const std::vector<float>& points,
                   const CancelCheck& cancel) {
  const auto t0 = Clock::now();
  SILK_ASSIGN_OR_RETURN(const double score, ScoreAgainstPoints(result->mesh, points, cancel));
  result->stats.candidates = {Entry(*result, seed, score)};
  result->stats.chosen_candidate = 0;
  result->stats.seconds.scoring += std::chrono::duration<double>(Clock::now() - t0).count();
  return Status::Ok();
}

StatusOr<GenerateResult> RunCandidates(Generator* generator, const std::vector<float>& points,
                                       const GenerateOptions& options, const GenerateCallbacks& callbacks,
                                       const CancelCheck& scoring_cancel) {
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(options));
  GenerateResult best;
  std::vector<CandidateScore> all;
  PhaseSeconds total;
  double generation_seconds = 0;
  int32_t chosen = 0;
  for (int32_t i = 0; i < options.candidates; ++i) {
    GenerateOptions o = options;
    o.sampling.seed = CandidateSeed(options.sampling.seed, i);
    SILK_ASSIGN_OR_RETURN(GenerateResult r, generator->Run(points, o, callbacks));
    const auto t0 = Clock::now();
    SILK_ASSIGN_OR_RETURN(const double score, ScoreAgainstPoints(r.mesh, points, scoring_cancel));
    all.push_back(Entry(r, o.sampling.seed, score));
    r.stats.seconds.scoring += std::chrono::duration<double>(Clock::now() - t0).count();
    const PhaseSeconds& s = r.stats.seconds;
    using Sum = std::pair<double*, double>;
    for (const Sum& e : std::initializer_list<Sum>{{&total.encoder, s.encoder}, {&total.decoder, s.decoder},
                                                   {&total.grammar, s.grammar}, {&total.sampling, s.sampling},
                                                   {&total.build_mesh, s.build_mesh}, {&total.guidance, s.guidance},
                                                   {&total.scoring, s.scoring}})
      *e.first += e.second;
    generation_seconds += r.stats.generation_seconds;
    if (i == 0 || Better(all.back(), all[chosen])) {
      chosen = i;
      best = std::move(r);
    }
  }
  best.stats.candidates = std::move(all);
  best.stats.chosen_candidate = chosen;
  best.stats.seconds = total;
  best.stats.generation_seconds = generation_seconds;
  return best;
}

}  // namespace silk
