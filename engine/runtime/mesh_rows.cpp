// SPDX-License-Identifier: MIT
// Many inputs as rows (mesh_rows.h): inputs are encoded while a source is free, their candidates
// share the rows, each ended candidate is scored in its input's order and an input whose
// candidates have all ended is concluded exactly as GenerationSession concludes it.
#include "runtime/mesh_rows.h"

#include <algorithm>
#include <string>
#include <utility>

#include "runtime/model/model_impl.h"
#include "runtime/sampling/generation_ranges.h"

namespace silk {

namespace {
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
const Status& CancelledBatch() {
  static const Status kCancelled(StatusCode::kCancelled, "generation cancelled");
  return kCancelled;
}
}  // namespace

MeshRows::MeshRows(const Model& model) : model_(model), session_(model), rows_(model) {}

bool MeshRows::ByRows() const { return parallel_ > 1 && model_.impl().rows_together; }

Status MeshRows::Open(int32_t parallel, int32_t rows, const MeshRowsCallbacks& callbacks) {
  SILK_RETURN_IF_ERROR(CheckSetting(ranges::kParallel, parallel));
  SILK_RETURN_IF_ERROR(CheckSetting(ranges::kRows, rows));
  session_.Abandon();
  rows_.Abandon();
  queue_.clear();
  flight_.clear();
  ended_.clear();
  parallel_ = parallel;
  rows_per_mesh_ = rows;
  callbacks_ = callbacks;
  added_ = 0;
  if (ByRows()) SILK_RETURN_IF_ERROR(rows_.Open(parallel * rows, parallel));
  return Status::Ok();
}

int32_t MeshRows::Add(const GenerationRequest& request, const GenerationInput& input) {
  Input in;
  in.index = added_++;
  if (ByRows()) {
    in.prepared = PrepareInput(model_, request, input, callbacks_.cancel, callbacks_.cancel);
  } else {  // GenerationSession prepares it when it starts
    in.request = request;
    in.input = input;
  }
  queue_.push_back(std::move(in));
  return added_ - 1;
}

int32_t MeshRows::AddError(Status error) {
  Input in;
  in.index = added_++;
  in.prepared = error;
  in.error = std::move(error);
  queue_.push_back(std::move(in));
  return added_ - 1;
}

void MeshRows::InterruptEncoder() {
  session_.InterruptEncoder();
  rows_.InterruptEncoder();
}

StatusOr<MeshRowsEnded> MeshRows::Next() {
  if (!ByRows()) return NextAlone();
  while (ended_.empty()) {
    if (queue_.empty() && flight_.empty())
      return InvalidArgument("batch: no input queued or in flight (add one first)");
    Status s = Cancelled() ? CancelledBatch() : Admit();
    if (s.ok() && ended_.empty() && !flight_.empty()) s = rows_.Advance(1 << 30, false, callbacks_.cancel);
    if (s.ok()) s = Collect();
    if (!s.ok()) SILK_RETURN_IF_ERROR(CancelAll(s));
  }
  MeshRowsEnded out = std::move(ended_.front());
  ended_.pop_front();
  return out;
}

// One after another: input by input on the session, as silk_generator_generate runs it.
StatusOr<MeshRowsEnded> MeshRows::NextAlone() {
  if (!ended_.empty()) {
    MeshRowsEnded out = std::move(ended_.front());
    ended_.pop_front();
    return out;
  }
  if (queue_.empty()) return InvalidArgument("batch: no input queued or in flight (add one first)");
  Input in = std::move(queue_.front());
  queue_.pop_front();
  MeshRowsEnded out;
  out.index = in.index;
  if (!in.error.ok()) {
    out.result = std::move(in.error);
    return out;
  }
  GenerateCallbacks cb;
  cb.cancel = callbacks_.cancel;
  if (callbacks_.progress)
    cb.progress = [this, index = in.index](const GenerateProgress& p) { callbacks_.progress(index, p); };
  Status s = session_.Start(in.request, in.input, cb, callbacks_.cancel);
  while (s.ok() && !session_.done()) s = session_.Advance(1 << 30);
  if (s.ok()) {
    out.result = session_.Finish(callbacks_.cancel);
  } else {
    session_.Abandon();
    out.result = s;
  }
  if (!out.result.ok() && out.result.status().code() == StatusCode::kCancelled) {
    session_.Abandon();
    EndQueued();  // a cancel stops the batch
  }
  return out;
}

Status MeshRows::Admit() {
  while (!queue_.empty() && rows_.free_sources() > 0) {
    Input in = std::move(queue_.front());
    queue_.pop_front();
    if (!in.prepared.ok()) {
      ended_.push_back(MeshRowsEnded{in.index, in.prepared.status()});
      continue;
    }
    Flight f;
    f.index = in.index;
    f.prepared = std::move(*in.prepared);
    f.started = Clock::now();
    const GenerateOptions& o = f.prepared.plan.options;  // its own rows at most, as alone
    const int32_t n = o.candidates;
    f.waiting.assign(static_cast<size_t>(n), std::nullopt);
    auto callbacks = [this, index = f.index, n](int32_t c) {
      GenerateCallbacks cb;
      cb.cancel = callbacks_.cancel;
      if (callbacks_.progress)
        cb.progress = [this, index, c, n](const GenerateProgress& p) {
          GenerateProgress tagged = p;
          tagged.candidate = c;
          tagged.candidates = n;
          callbacks_.progress(index, tagged);
        };
      return cb;
    };
    StatusOr<int32_t> id = rows_.AddMesh(f.prepared.points, o, callbacks, callbacks_.cancel);
    if (!id.ok()) {
      if (id.status().code() == StatusCode::kCancelled) return id.status();
      ended_.push_back(MeshRowsEnded{f.index, id.status()});
      continue;
    }
    flight_.emplace(*id, std::move(f));
  }
  return Status::Ok();
}

Status MeshRows::Collect() {
  std::vector<int32_t> over;
  for (CandidateRows::Ended& e : rows_.TakeEndedRows()) {
    Flight& f = flight_.at(e.mesh);
    if (!e.status.ok())
      ended_.push_back(MeshRowsEnded{f.index, std::move(e.status)});
    else
      f.waiting[static_cast<size_t>(e.candidate)] = std::move(e.result);
    if (e.last) over.push_back(e.mesh);
  }
  for (auto& [id, f] : flight_) {  // scored in candidate order, as one after another
    const uint64_t seed = f.prepared.plan.options.sampling.seed;
    SILK_RETURN_IF_ERROR(ScoreWaiting(f.choice.size(), &f.waiting, [&](int32_t index, GenerateResult* result) {
      return f.choice.Add(result, CandidateSeed(seed, index), f.prepared.points, callbacks_.cancel);
    }));
  }
  for (const int32_t id : over) Conclude(id);
  return Status::Ok();
}

// Mesh `id` has ended: concluded (every candidate scored) unless it failed (its error is in ended_).
void MeshRows::Conclude(int32_t id) {
  Flight& f = flight_.at(id);
  const GenerateOptions& o = f.prepared.plan.options;
  if (f.choice.size() == o.candidates) {
    // As GenerationSession: rows only when best of N asks for more than one (stats.rows: its own).
    const bool by_rows = CandidatesAsRows(o, model_);
    const RowsRun run{std::max(1, std::min(o.rows, o.candidates)), rows_.cache_bytes(), rows_.decoder_seconds(),
                      Since(f.started)};
    ended_.push_back(MeshRowsEnded{f.index, ConcludeChoice(&f.choice, f.prepared, true, by_rows ? &run : nullptr)});
  }
  flight_.erase(id);
}

// A cancel (or an error of the rows themselves): every input in flight ends with it.
Status MeshRows::CancelAll(Status why) {
  rows_.Abandon();
  if (ByRows()) SILK_RETURN_IF_ERROR(rows_.Open(parallel_ * rows_per_mesh_, parallel_));
  for (auto& [id, f] : flight_) ended_.push_back(MeshRowsEnded{f.index, why});
  flight_.clear();
  if (why.code() == StatusCode::kCancelled) EndQueued();  // a cancel stops the batch
  return Status::Ok();
}

void MeshRows::EndQueued() {
  for (const Input& in : queue_)
    ended_.push_back(MeshRowsEnded{in.index, Status(StatusCode::kCancelled, "generation cancelled before it started")});
  queue_.clear();
}

}  // namespace silk
