// SPDX-License-Identifier: MIT
// Best of N as rows: rows step their forced ids alone, then every row waiting for logits takes
// part in one decoder feed; rows that end are built, and the last row moves into the freed slot.
#include "runtime/candidate_rows.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include "runtime/candidates.h"
#include "runtime/model/model_impl.h"

namespace silk {

namespace {
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
int64_t ChunksOf(int64_t n) { return (n + kDecoderChunk - 1) / kDecoderChunk; }
}  // namespace

CandidateRows::CandidateRows(const Model& model) : model_(model), encoder_run_(std::make_unique<Ort::RunOptions>()) {}
CandidateRows::~CandidateRows() = default;

void CandidateRows::InterruptEncoder() { encoder_run_->SetTerminate(); }

Status CandidateRows::Start(const std::vector<float>& points, const GenerateOptions& options, int32_t rows,
                            const std::function<GenerateCallbacks(int32_t)>& callbacks, const CancelCheck& cancel) {
  Abandon();
  const Model::Impl& m = model_.impl();
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(options));
  if (points.empty() || points.size() % 6 != 0)
    return InvalidArgument("generate: points must be a non-empty array of rows of 6 floats");
  candidates_ = options.candidates;
  const int32_t R = std::max(1, std::min(rows, candidates_));
  options_ = options;
  points_ = points;
  callbacks_ = callbacks;
  decoder_seconds_ = 0;
  encoder_run_->UnsetTerminate();
  const auto t0 = Clock::now();
  SILK_ASSIGN_OR_RETURN(Ort::Value cross, EncodeInput(m, points, *encoder_run_, cancel));
  encoder_seconds_ = Since(t0);
  // BOS + every id but the last of the longest sequence the model allows.
  SILK_RETURN_IF_ERROR(cache_.Reserve(R, m.config.dims.max_seq_len - 1, ModelKvShape(m)));
  decoder_ = std::make_unique<RowsDecoder>(m, &cache_);
  decoder_->SetSources(1);
  decoder_->SetSource(0, cross.GetTensorMutableData<void>());
  rows_.resize(static_cast<size_t>(R));
  for (Row& r : rows_) r.generator = std::make_unique<Generator>(model_);
  for (int32_t slot = 0; slot < R; ++slot) SILK_RETURN_IF_ERROR(StartNext(slot));
  return Status::Ok();
}

// The next candidate in row `slot` (an empty slot at live_), sharing row 0's per-input state.
Status CandidateRows::StartNext(int32_t slot) {
  Row& r = rows_[static_cast<size_t>(slot)];
  GenerateOptions o = options_;
  o.sampling.seed = CandidateSeed(options_.sampling.seed, next_);
  r.generator->ShareInput(*rows_[0].generator, points_);
  cache_.Clear(slot);
  r.candidate = next_;
  r.ready = false;
  // Only the first candidate's stats count the encoder run (the others share it).
  SILK_RETURN_IF_ERROR(r.generator->StartRow(points_, o, callbacks_ ? callbacks_(next_) : GenerateCallbacks{},
                                             next_ == 0 ? encoder_seconds_ : 0));
  ++next_;
  ++live_;
  return Status::Ok();
}

Status CandidateRows::Advance(int32_t max_ids, bool until_layer, const CancelCheck& finishing) {
  int32_t ids = 0;
  bool stop = false;
  while (ids < max_ids && !stop && live_ > 0) {
    SILK_RETURN_IF_ERROR(StepWithoutLogits(max_ids, until_layer, &ids, &stop));
    const size_t ended = ended_.size();
    SILK_RETURN_IF_ERROR(Retire(finishing));
    if (until_layer && ended_.size() > ended) stop = true;
    if (ids >= max_ids || stop || live_ == 0) break;
    if (!AllWaiting()) continue;  // a new candidate took a row: its forced ids first
    SILK_RETURN_IF_ERROR(Decode(max_ids, &ids));
  }
  return Status::Ok();
}

bool CandidateRows::AllWaiting() const {
  for (int32_t s = 0; s < live_; ++s) {
    const Row& r = rows_[static_cast<size_t>(s)];
    if (r.ready || !r.generator->waiting_for_logits()) return false;
  }
  return true;
}

Status CandidateRows::StepWithoutLogits(int32_t max_ids, bool until_layer, int32_t* ids, bool* stop) {
  for (int32_t s = 0; s < live_ && *ids < max_ids && !*stop; ++s) {
    Row& r = rows_[static_cast<size_t>(s)];
    Generator& g = *r.generator;
    const int64_t layers = g.layers_closed();
    while (*ids < max_ids && !(until_layer && g.layers_closed() > layers)) {
      if (r.ready) {
        r.ready = false;
        SILK_RETURN_IF_ERROR(g.StepWithLogits(r.logits.data()));
        ++*ids;
        continue;
      }
      SILK_ASSIGN_OR_RETURN(const Generator::RowStep step, g.StepWithoutLogits());
      if (step != Generator::RowStep::kStepped) break;
      ++*ids;
    }
    if (until_layer && (g.layers_closed() > layers || g.finished())) *stop = true;
  }
  return Status::Ok();
}

// How many pending ids each row feeds in the next call. Contract v4: the fewest any row has (at
// most one chunk), so no row is padded: a row with a longer forced run feeds that many of it now and
// the rest in the next calls (a position's logits do not depend on the cut), while the rows that
// need their logits sooner go on sampling. A batch-1 decoder runs each row alone: all of it.
int64_t CandidateRows::FeedWidth() const {
  if (!model_.impl().rows_together) return std::numeric_limits<int64_t>::max();
  int64_t width = kDecoderChunk;
  for (int32_t s = 0; s < live_; ++s)
    width = std::min<int64_t>(width, static_cast<int64_t>(rows_[static_cast<size_t>(s)].generator->pending().size()));
  return std::max<int64_t>(width, 1);
}

Status CandidateRows::Decode(int32_t max_ids, int32_t* ids) {
  const int64_t width = FeedWidth();
  std::vector<RowFeed> feeds;
  for (int32_t s = 0; s < live_; ++s) {
    const std::vector<int32_t>& p = rows_[static_cast<size_t>(s)].generator->pending();
    const int64_t n = std::min(width, static_cast<int64_t>(p.size()));
    feeds.push_back(RowFeed{s, p.data(), n, 0, n == static_cast<int64_t>(p.size())});
  }
  const auto t0 = Clock::now();
  SILK_RETURN_IF_ERROR(decoder_->Feed(feeds));
  const double seconds = Since(t0);
  decoder_seconds_ += seconds;
  const int64_t vocab = model_.config().model_vocab_size;
  for (int32_t s = 0; s < live_; ++s) {
    Row& r = rows_[static_cast<size_t>(s)];
    const RowFeed& f = feeds[static_cast<size_t>(s)];
    r.generator->NoteFed(seconds, ChunksOf(f.n), f.n);
    if (!f.keep_logits) continue;  // more of its run in the next call
    if (*ids < max_ids) {
      SILK_RETURN_IF_ERROR(r.generator->StepWithLogits(decoder_->logits(s)));
      ++*ids;
    } else {  // the budget ran out: the logits wait for the next Advance
      r.logits.assign(decoder_->logits(s), decoder_->logits(s) + vocab);
      r.ready = true;
    }
  }
  return Status::Ok();
}

Status CandidateRows::Retire(const CancelCheck& finishing) {
  for (int32_t s = live_ - 1; s >= 0; --s) {
    Row& r = rows_[static_cast<size_t>(s)];
    if (!r.generator->finished()) continue;
    SILK_ASSIGN_OR_RETURN(GenerateResult result, r.generator->Finish(finishing));
    ended_.emplace_back(r.candidate, std::move(result));
    const int32_t last = live_ - 1;
    if (s != last) {
      cache_.Move(last, s);
      std::swap(rows_[static_cast<size_t>(s)], rows_[static_cast<size_t>(last)]);
    }
    rows_[static_cast<size_t>(last)].candidate = -1;
    --live_;
  }
  while (live_ < rows() && next_ < candidates_) SILK_RETURN_IF_ERROR(StartNext(live_));
  return Status::Ok();
}

Status CandidateRows::EndLive(const CancelCheck& finishing) {
  for (int32_t s = live_ - 1; s >= 0; --s) {
    Row& r = rows_[static_cast<size_t>(s)];
    SILK_ASSIGN_OR_RETURN(GenerateResult result, r.generator->Finish(finishing));  // cancels it
    ended_.emplace_back(r.candidate, std::move(result));
    r.candidate = -1;
    --live_;
  }
  next_ = candidates_;  // no more candidates start
  return Status::Ok();
}

std::vector<std::pair<int32_t, GenerateResult>> CandidateRows::TakeEnded() {
  std::vector<std::pair<int32_t, GenerateResult>> out = std::move(ended_);
  ended_.clear();
  return out;
}

void CandidateRows::Abandon() {
  for (Row& r : rows_)
    if (r.generator && r.generator->active()) r.generator->Release();
  ended_.clear();
  live_ = next_ = candidates_ = 0;
}

const Generator* CandidateRows::lead() const {
  const Generator* best = nullptr;
  for (int32_t s = 0; s < live_; ++s) {
    const Generator* g = rows_[static_cast<size_t>(s)].generator.get();
    if (!best || g->tokens().size() > best->tokens().size()) best = g;
  }
  return best;
}

std::vector<std::pair<int32_t, const Generator*>> CandidateRows::live() const {
  std::vector<std::pair<int32_t, const Generator*>> out;
  for (int32_t s = 0; s < live_; ++s)
    out.emplace_back(rows_[static_cast<size_t>(s)].candidate, rows_[static_cast<size_t>(s)].generator.get());
  return out;
}

int32_t CandidateRows::lead_candidate() const {
  const Generator* g = lead();
  for (int32_t s = 0; s < live_; ++s)
    if (rows_[static_cast<size_t>(s)].generator.get() == g) return rows_[static_cast<size_t>(s)].candidate;
  return -1;
}

}  // namespace silk
