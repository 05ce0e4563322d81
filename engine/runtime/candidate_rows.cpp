// SPDX-License-Identifier: MIT
// Best of N as rows: rows step their forced ids alone, then every row waiting for logits takes
// part in one decoder feed; rows that end are built, and the last row moves into the freed slot.
// Rows may belong to several meshes, each attending to its own encoder output (a source).
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
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(options));
  SILK_RETURN_IF_ERROR(Open(std::max(1, std::min(rows, options.candidates)), 1));
  isolate_ = false;  // one mesh: a row's error fails the run
  GenerateOptions o = options;
  o.rows = this->rows();
  SILK_ASSIGN_OR_RETURN(const int32_t mesh, AddMesh(points, o, callbacks, cancel));
  (void)mesh;
  return Status::Ok();
}

Status CandidateRows::Open(int32_t rows, int32_t sources) {
  Abandon();
  if (rows < 1 || sources < 1 || sources > rows)
    return InvalidArgument("rows: " + std::to_string(rows) + " rows over " + std::to_string(sources) +
                           " meshes (need 1 <= meshes <= rows)");
  const Model::Impl& m = model_.impl();
  decoder_seconds_ = 0;
  next_mesh_ = 0;
  isolate_ = true;
  // BOS + every id but the last of the longest sequence the model allows.
  SILK_RETURN_IF_ERROR(cache_.Reserve(rows, m.config.dims.max_seq_len - 1, ModelKvShape(m)));
  decoder_ = std::make_unique<RowsDecoder>(m, &cache_);
  decoder_->SetSources(sources);
  free_sources_.clear();
  for (int32_t i = sources - 1; i >= 0; --i) free_sources_.push_back(i);
  rows_.resize(static_cast<size_t>(rows));
  for (Row& r : rows_)
    if (!r.generator) r.generator = std::make_unique<Generator>(model_);
  return Status::Ok();
}

StatusOr<int32_t> CandidateRows::AddMesh(const std::vector<float>& points, const GenerateOptions& options,
                                         const std::function<GenerateCallbacks(int32_t)>& callbacks,
                                         const CancelCheck& cancel) {
  if (!decoder_ || free_sources_.empty()) return InvalidArgument("rows: no free source for another mesh (Open first)");
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(options));
  if (points.empty() || points.size() % 6 != 0)
    return InvalidArgument("generate: points must be a non-empty array of rows of 6 floats");
  encoder_run_->UnsetTerminate();
  const auto t0 = Clock::now();
  SILK_ASSIGN_OR_RETURN(Ort::Value cross, EncodeInput(model_.impl(), points, *encoder_run_, cancel));
  Mesh mesh;
  mesh.encoder_seconds = Since(t0);
  mesh.points = points;
  mesh.options = options;
  mesh.callbacks = callbacks;
  mesh.cap = std::max(1, std::min(options.rows, options.candidates));
  mesh.source = free_sources_.back();
  free_sources_.pop_back();
  decoder_->SetSource(mesh.source, cross.GetTensorMutableData<void>());
  const int32_t id = next_mesh_++;
  meshes_.emplace(id, std::move(mesh));
  for (int32_t m = NextMesh(); live_ < rows() && m >= 0; m = NextMesh()) SILK_RETURN_IF_ERROR(StartNext(live_, m));
  return id;
}

int32_t CandidateRows::NextMesh() const {
  for (const auto& [id, m] : meshes_)
    if (!m.failed && m.next < m.options.candidates && m.live < m.cap) return id;
  return -1;
}

// Mesh `id`'s next candidate in row `slot` (an empty slot at live_), sharing the per-input state
// of a row on the same points.
Status CandidateRows::StartNext(int32_t slot, int32_t id) {
  Mesh& m = meshes_.at(id);
  Row& r = rows_[static_cast<size_t>(slot)];
  GenerateOptions o = m.options;
  o.sampling.seed = CandidateSeed(m.options.sampling.seed, m.next);
  const Generator* share = rows_[0].generator.get();
  for (int32_t s = 0; s < live_; ++s)
    if (rows_[static_cast<size_t>(s)].mesh == id) share = rows_[static_cast<size_t>(s)].generator.get();
  r.generator->ShareInput(*share, m.points);
  cache_.Clear(slot);
  r.mesh = id;
  r.candidate = m.next;
  r.ready = r.failed = false;
  ++m.next;
  ++m.live;
  ++live_;
  // Only the first candidate's stats count the encoder run (the others share it).
  const int32_t c = r.candidate;
  return Check(slot, r.generator->StartRow(m.points, o, m.callbacks ? m.callbacks(c) : GenerateCallbacks{},
                                           c == 0 ? m.encoder_seconds : 0));
}

Status CandidateRows::Check(int32_t slot, Status status) {
  if (status.ok() || !isolate_ || status.code() == StatusCode::kCancelled) return status;
  Row& r = rows_[static_cast<size_t>(slot)];
  Mesh& m = meshes_.at(r.mesh);
  if (!m.failed) {
    m.failed = true;
    Ended e;
    e.mesh = r.mesh;
    e.candidate = -1;
    e.status = std::move(status);
    ended_.push_back(std::move(e));
  }
  for (int32_t s = 0; s < live_; ++s)
    if (rows_[static_cast<size_t>(s)].mesh == r.mesh) rows_[static_cast<size_t>(s)].failed = true;
  return Status::Ok();
}

Status CandidateRows::Advance(int32_t max_ids, bool until_layer, const CancelCheck& finishing) {
  int32_t ids = 0;
  bool stop = false;
  mesh_ended_ = false;
  while (ids < max_ids && !stop && live_ > 0) {
    SILK_RETURN_IF_ERROR(StepWithoutLogits(max_ids, until_layer, &ids, &stop));
    const size_t ended = ended_.size();
    SILK_RETURN_IF_ERROR(Retire(finishing));
    if ((until_layer && ended_.size() > ended) || mesh_ended_) stop = true;
    if (ids >= max_ids || stop || live_ == 0) break;
    if (!AllWaiting()) continue;  // a new candidate took a row: its forced ids first
    SILK_RETURN_IF_ERROR(Decode(max_ids, &ids));
  }
  return Status::Ok();
}

bool CandidateRows::AllWaiting() const {
  for (int32_t s = 0; s < live_; ++s) {
    const Row& r = rows_[static_cast<size_t>(s)];
    if (r.ready || r.failed || !r.generator->waiting_for_logits()) return false;
  }
  return true;
}

Status CandidateRows::StepWithoutLogits(int32_t max_ids, bool until_layer, int32_t* ids, bool* stop) {
  for (int32_t s = 0; s < live_ && *ids < max_ids && !*stop; ++s) {
    Row& r = rows_[static_cast<size_t>(s)];
    Generator& g = *r.generator;
    const int64_t layers = g.layers_closed();
    while (!r.failed && *ids < max_ids && !(until_layer && g.layers_closed() > layers)) {
      if (r.ready) {
        r.ready = false;
        SILK_RETURN_IF_ERROR(Check(s, g.StepWithLogits(r.logits.data())));
        ++*ids;
        continue;
      }
      StatusOr<Generator::RowStep> step = g.StepWithoutLogits();
      SILK_RETURN_IF_ERROR(Check(s, step.status()));
      if (!step.ok() || *step != Generator::RowStep::kStepped) break;
      ++*ids;
    }
    if (r.failed) continue;
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
    feeds.push_back(RowFeed{s, p.data(), n, SourceOf(s), n == static_cast<int64_t>(p.size())});
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
      SILK_RETURN_IF_ERROR(Check(s, r.generator->StepWithLogits(decoder_->logits(s))));
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
    if (!r.failed && !r.generator->finished()) continue;
    const int32_t id = r.mesh;
    if (!r.failed) {
      StatusOr<GenerateResult> result = r.generator->Finish(finishing);
      SILK_RETURN_IF_ERROR(Check(s, result.status()));
      if (result.ok()) {
        Ended e;
        e.mesh = id;
        e.candidate = r.candidate;
        e.result = std::move(*result);
        ended_.push_back(std::move(e));
      }
    }
    if (r.failed && r.generator->active()) r.generator->Release();
    --meshes_.at(id).live;
    Vacate(s);
    Mesh& m = meshes_.at(id);
    if (m.live == 0 && (m.failed || m.next >= m.options.candidates)) {  // the mesh has ended
      for (auto it = ended_.rbegin(); it != ended_.rend(); ++it)
        if (it->mesh == id) {
          it->last = true;
          break;
        }
      free_sources_.push_back(m.source);
      meshes_.erase(id);
      mesh_ended_ = true;
    }
  }
  for (int32_t m = NextMesh(); live_ < rows() && m >= 0; m = NextMesh()) SILK_RETURN_IF_ERROR(StartNext(live_, m));
  return Status::Ok();
}

void CandidateRows::Vacate(int32_t slot) {
  const int32_t last = live_ - 1;
  if (slot != last) {
    cache_.Move(last, slot);
    std::swap(rows_[static_cast<size_t>(slot)], rows_[static_cast<size_t>(last)]);
  }
  rows_[static_cast<size_t>(last)].candidate = rows_[static_cast<size_t>(last)].mesh = -1;
  --live_;
}

int32_t CandidateRows::SourceOf(int32_t slot) const { return meshes_.at(rows_[static_cast<size_t>(slot)].mesh).source; }

Status CandidateRows::EndLive(const CancelCheck& finishing) {
  for (int32_t s = live_ - 1; s >= 0; --s) {
    Row& r = rows_[static_cast<size_t>(s)];
    if (r.failed) {
      if (r.generator->active()) r.generator->Release();
    } else {
      SILK_ASSIGN_OR_RETURN(GenerateResult result, r.generator->Finish(finishing));  // cancels it
      Ended e;
      e.mesh = r.mesh;
      e.candidate = r.candidate;
      e.result = std::move(result);
      ended_.push_back(std::move(e));
    }
    r.candidate = r.mesh = -1;
    --live_;
  }
  meshes_.clear();  // no more candidates start
  return Status::Ok();
}

std::vector<std::pair<int32_t, GenerateResult>> CandidateRows::TakeEnded() {
  std::vector<std::pair<int32_t, GenerateResult>> out;
  for (Ended& e : ended_) out.emplace_back(e.candidate, std::move(e.result));
  ended_.clear();
  return out;
}

std::vector<CandidateRows::Ended> CandidateRows::TakeEndedRows() {
  std::vector<Ended> out = std::move(ended_);
  ended_.clear();
  return out;
}

void CandidateRows::Abandon() {
  for (Row& r : rows_)
    if (r.generator && r.generator->active()) r.generator->Release();
  ended_.clear();
  meshes_.clear();
  free_sources_.clear();
  live_ = 0;
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
