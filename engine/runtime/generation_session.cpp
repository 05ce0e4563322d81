// SPDX-License-Identifier: MIT
// GenerationSession: request -> encoder points -> candidates one after another -> the chosen one
// in the input frame. A candidate's end is handled lazily (scored as the next one starts), so a
// caller stepping by layers sees each candidate's last layer before the next begins.
#include "runtime/generation_session.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>

#include "runtime/generation_output.h"
#include "runtime/input_generation.h"
#include "runtime/model/model_impl.h"

namespace silk {

namespace {
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

GenerationSession::GenerationSession(const Model& model) : model_(model), generator_(model), rows_(model) {}

void GenerationSession::Reset() {
  active_ = cancelled_ = failed_ = false;
  candidate_ = 0;
  choice_ = CandidateChoice{};
  ended_.reset();
  rows_.Abandon();
  by_rows_ = false;
  waiting_.clear();
  built_.clear();
  last_ended_ = LastEnded{};
}

Status GenerationSession::Score(GenerateResult* result, int32_t index, const CancelCheck& cancel) {
  TokenizerDecodedMesh mesh = result->mesh;  // the choice may take the result
  SILK_RETURN_IF_ERROR(choice_.Add(result, CandidateSeed(plan_.options.sampling.seed, index), points_, cancel));
  if (built_.size() <= static_cast<size_t>(index)) built_.resize(static_cast<size_t>(index) + 1);
  built_[static_cast<size_t>(index)] = std::move(mesh);
  return Status::Ok();
}

Status GenerationSession::Start(const GenerationRequest& request, const GenerationInput& input,
                                const GenerateCallbacks& callbacks, const CancelCheck& flag) {
  Reset();
  SILK_ASSIGN_OR_RETURN(PreparedInput prepared, PrepareInput(model_, request, input, callbacks.cancel, flag));
  plan_ = std::move(prepared.plan);
  points_ = std::move(prepared.points);
  transform_ = prepared.transform;
  prepare_seconds_ = prepared.prepare_seconds;
  callbacks_ = callbacks;
  flag_ = flag;
  // A decoder before contract v4 takes one row per call: rows would run one after another anyway
  // and only hold R caches at once, so such a folder runs its candidates one after another; so
  // does an INT8 decoder, whose rows are not each exactly their own (RowsTogether).
  by_rows_ = CandidatesAsRows(plan_.options, model_);
  if (by_rows_) {
    started_ = Clock::now();
    waiting_.assign(static_cast<size_t>(candidates()), std::nullopt);
    SILK_RETURN_IF_ERROR(rows_.Start(
        points_, plan_.options, plan_.options.rows, [this](int32_t i) { return CandidateCallbacks(i); },
        callbacks.cancel));
  } else {
    SILK_RETURN_IF_ERROR(StartCandidate());
  }
  active_ = true;
  return Status::Ok();
}

// Candidate `index`'s callbacks: the caller's cancel, progress reports tagged with its index.
GenerateCallbacks GenerationSession::CandidateCallbacks(int32_t index) {
  GenerateCallbacks cb;
  cb.cancel = callbacks_.cancel;
  if (callbacks_.progress) {
    cb.progress = [this, index](const GenerateProgress& p) {
      GenerateProgress tagged = p;
      tagged.candidate = index;
      tagged.candidates = candidates();
      callbacks_.progress(tagged);
    };
  }
  return cb;
}

// Candidate candidate_ on the generator, with its derived seed.
Status GenerationSession::StartCandidate() {
  GenerateOptions o = plan_.options;
  o.sampling.seed = CandidateSeed(plan_.options.sampling.seed, candidate_);
  return generator_.Start(points_, o, CandidateCallbacks(candidate_));
}

// The candidate that has ended (or is ended now: Generator::Finish cancels one in progress):
// its mesh built, then scored into the choice, polling `cancel`.
Status GenerationSession::CloseCandidate(const CancelCheck& cancel) {
  if (!ended_) {
    SILK_ASSIGN_OR_RETURN(GenerateResult r, generator_.Finish(cancel));
    ended_ = std::move(r);
  }
  SILK_RETURN_IF_ERROR(Score(&*ended_, candidate_, cancel));
  ended_.reset();
  return Status::Ok();
}

// Scoring polls the caller's flag and the callbacks' cancel: with a million encoder points it runs
// for seconds between two ids.
CancelCheck GenerationSession::ScoringCheck() const {
  return [this] { return CancelRequested(flag_) || CancelRequested(callbacks_.cancel); };
}

Status GenerationSession::NextCandidate() {
  SILK_RETURN_IF_ERROR(CloseCandidate(ScoringCheck()));
  ++candidate_;
  return StartCandidate();
}

Status GenerationSession::Note(Status status) {
  if (status.code() == StatusCode::kCancelled)
    cancelled_ = true;
  else if (!status.ok())
    failed_ = true;
  return status;
}

bool GenerationSession::done() const {
  if (by_rows_) return active_ && (cancelled_ || rows_.done());
  return active_ && (cancelled_ || (candidate_ + 1 >= candidates() && generator_.finished()));
}

int32_t GenerationSession::candidate() const {
  if (!by_rows_) return candidate_;
  return rows_.lead() ? rows_.lead_candidate() : std::max(last_ended_.candidate, 0);
}

Status GenerationSession::ScoreEnded(const CancelCheck& cancel) {
  for (auto& [index, result] : rows_.TakeEnded()) {
    last_ended_.candidate = index;  // shown once no candidate runs
    last_ended_.tokens = result.tokens;
    last_ended_.stats = result.stats;
    waiting_[static_cast<size_t>(index)] = std::move(result);
  }
  return ScoreWaiting(choice_.size(), &waiting_,
                      [&](int32_t index, GenerateResult* result) { return Score(result, index, cancel); });
}

Status GenerationSession::AdvanceRows(int32_t max_ids, AdvanceUntil until) {
  SILK_RETURN_IF_ERROR(Note(rows_.Advance(max_ids, until == AdvanceUntil::kLayer, ScoringCheck())));
  return Note(ScoreEnded(ScoringCheck()));
}

Status GenerationSession::Advance(int32_t max_ids, AdvanceUntil until) {
  if (!active_ || failed_) return InvalidArgument("generate: no generation in progress (Start first)");
  if (by_rows_) return done() ? Status::Ok() : AdvanceRows(max_ids, until);
  int64_t layers = generator_.layers_closed();
  for (int32_t ids = 0; ids < max_ids && !done();) {
    if (generator_.finished()) {  // a candidate before the last has ended
      if (until == AdvanceUntil::kLayer && ids > 0) break;
      SILK_RETURN_IF_ERROR(Note(NextCandidate()));
      layers = 0;
      continue;
    }
    SILK_RETURN_IF_ERROR(Note(generator_.Step()));
    ++ids;
    if (until == AdvanceUntil::kLayer && generator_.layers_closed() > layers) break;
  }
  return Status::Ok();
}

StatusOr<SessionResult> GenerationSession::Finish(const CancelCheck& scoring) {
  if (!active_) return InvalidArgument("generate: no generation started");
  if (failed_) {
    Reset();
    return InvalidArgument("generate: no generation to finish (it failed)");
  }
  if (by_rows_) return FinishRows(scoring);
  const bool complete = done() && !cancelled_;
  if (generator_.active() || ended_) {
    if (Status s = CloseCandidate(scoring); !s.ok()) {
      if (s.code() != StatusCode::kCancelled) Reset();
      return s;
    }
  }
  return Conclude(complete);
}

// Rows mode: every candidate still in progress ended now (a cancelled run), all scored in order.
StatusOr<SessionResult> GenerationSession::FinishRows(const CancelCheck& scoring) {
  const bool complete = done() && !cancelled_;
  Status s = rows_.done() ? Status::Ok() : rows_.EndLive(scoring);
  if (s.ok()) s = ScoreEnded(scoring);
  if (!s.ok()) {
    if (s.code() != StatusCode::kCancelled) Reset();
    return s;
  }
  return Conclude(complete);
}

// The chosen candidate in the input frame, with the whole run's times; ends the run.
SessionResult GenerationSession::Conclude(bool complete) {
  PreparedInput input;
  input.transform = transform_;
  input.prepare_seconds = prepare_seconds_;
  RowsRun run;
  if (by_rows_) run = RowsRun{rows_.rows(), rows_.cache_bytes(), rows_.decoder_seconds(), Since(started_)};
  SessionResult out = ConcludeChoice(&choice_, input, complete, by_rows_ ? &run : nullptr);
  Reset();
  return out;
}

void GenerationSession::Abandon() {
  if (active_ && generator_.active()) generator_.Release();  // the candidate's state
  Reset();
}

const Generator* GenerationSession::Shown() const {
  if (!active_) return nullptr;
  if (by_rows_) return rows_.lead();
  return generator_.active() ? &generator_ : nullptr;
}

const std::vector<int32_t>& GenerationSession::tokens() const {
  static const std::vector<int32_t> kNone;
  if (!active_) return kNone;
  if (by_rows_) return rows_.lead() ? rows_.lead()->tokens() : last_ended_.tokens;
  if (generator_.active()) return generator_.tokens();
  return ended_ ? ended_->tokens : kNone;
}

const GenerationStats& GenerationSession::stats() const {
  static const GenerationStats kNone;
  if (!active_) return kNone;
  if (by_rows_) return rows_.lead() ? rows_.lead()->stats() : last_ended_.stats;
  if (generator_.active()) return generator_.stats();
  return ended_ ? ended_->stats : kNone;
}

GenerationStats GenerationSession::CancelledStats() const {
  GenerationStats st = stats();
  st.candidates = choice_.scored();
  if (active_ && (Shown() || ended_)) {
    CandidateScore c;
    c.seed = CandidateSeed(plan_.options.sampling.seed, candidate());
    c.faces = st.faces;
    c.tokens = st.tokens;
    c.seconds = st.generation_seconds;
    st.candidates.push_back(c);
  }
  st.chosen_candidate = st.candidates.empty() ? 0 : static_cast<int32_t>(st.candidates.size()) - 1;
  st.stop_reason = StopReason::kCancelled;
  return st;
}

StatusOr<SessionPreview> GenerationSession::Preview() const {
  if (!active_) return InvalidArgument("generate: no generation in progress");
  SessionPreview p;
  if (const Generator* g = Shown()) {
    SILK_ASSIGN_OR_RETURN(p.grid, g->MeshSoFar());
  } else if (ended_) {
    p.grid = ended_->mesh;
  }
  p.output = ToInputFrame(p.grid, transform_);
  return p;
}

const Generator* GenerationSession::RunningGenerator(int32_t index) const {
  if (by_rows_) {
    for (const auto& [i, g] : rows_.live())
      if (i == index) return g;
    return nullptr;
  }
  return index == candidate_ && generator_.active() ? &generator_ : nullptr;
}

const GenerateResult* GenerationSession::EndedResult(int32_t index) const {
  if (by_rows_)
    return static_cast<size_t>(index) < waiting_.size() && waiting_[static_cast<size_t>(index)]
               ? &*waiting_[static_cast<size_t>(index)]
               : nullptr;
  return index == candidate_ && ended_ ? &*ended_ : nullptr;
}

std::vector<CandidateView> GenerationSession::Candidates() const {
  std::vector<CandidateView> out;
  if (!active_) return out;
  const std::vector<CandidateScore>& scored = choice_.scored();
  for (int32_t i = 0; i < candidates(); ++i) {
    CandidateView v;
    v.index = i;
    if (static_cast<size_t>(i) < scored.size()) {
      const CandidateScore& c = scored[static_cast<size_t>(i)];
      v.state = CandidateView::State::kScored;
      v.tokens = c.tokens;
      v.faces = c.faces;
      v.score = c.score;
      v.best = i == choice_.chosen();
    } else if (const GenerateResult* r = EndedResult(i)) {
      v.state = CandidateView::State::kEnded;
      v.tokens = static_cast<int64_t>(r->tokens.size());
      v.faces = static_cast<int32_t>(r->mesh.faces.size());
    } else if (const Generator* g = RunningGenerator(i)) {
      v.state = CandidateView::State::kRunning;
      v.tokens = static_cast<int64_t>(g->tokens().size());
    }
    out.push_back(v);
  }
  return out;
}

StatusOr<SessionPreview> GenerationSession::PreviewCandidate(int32_t index) const {
  if (!active_) return InvalidArgument("generate: no generation in progress");
  if (index < 0 || index >= candidates())
    return InvalidArgument("generate: candidate " + std::to_string(index) + " is not in [0, " +
                           std::to_string(candidates()) + ")");
  SessionPreview p;
  if (static_cast<size_t>(index) < choice_.scored().size()) {
    p.grid = built_[static_cast<size_t>(index)];
  } else if (const GenerateResult* r = EndedResult(index)) {
    p.grid = r->mesh;
  } else if (const Generator* g = RunningGenerator(index)) {
    SILK_ASSIGN_OR_RETURN(p.grid, g->MeshSoFar());
  }
  p.output = ToInputFrame(p.grid, transform_);
  return p;
}

std::vector<double> GenerationSession::InputFramePoints() const {
  std::vector<double> out(points_.size());
  for (size_t i = 0; i + 6 <= points_.size(); i += 6) {
    const auto p = UndoNormalization({points_[i], points_[i + 1], points_[i + 2]}, transform_);
    for (int a = 0; a < 3; ++a) out[i + a] = p[a], out[i + 3 + a] = points_[i + 3 + a];
  }
  return out;
}

}  // namespace silk
