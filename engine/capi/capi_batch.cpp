// SPDX-License-Identifier: MIT
// C API 1.6: a batch of inputs, several meshes decoded together (silk_batch_*), over the runtime's
// MeshRows: here only the C structs <-> runtime types, argument checks, errors and the call state.
#if defined(SILK_HAVE_RUNTIME)
#include <atomic>
#include <memory>
#include <string>

#include "capi/capi_generator.h"
#include "runtime/mesh_rows.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

struct silk_batch {
  explicit silk_batch(std::shared_ptr<silk::Model> m) : model(std::move(m)), rows(*model) {}
  std::shared_ptr<silk::Model> model;  // keeps the model alive as long as the batch
  silk::MeshRows rows;
  silk_batch_params params{};
  std::atomic<bool> busy{false}, cancelled{false};
  bool closed = false;
  bool Cancelled() const { return cancelled.load() || (params.cancel && params.cancel(params.user_data) != 0); }
};

namespace {

// One call at a time on a batch (its callbacks may not call back into it).
class BatchCall {
 public:
  explicit BatchCall(silk_batch* b) : b_(b), ok_(!b->busy.exchange(true)) {}
  ~BatchCall() {
    if (ok_) b_->busy.store(false);
  }
  bool ok() const { return ok_; }

 private:
  silk_batch* b_;
  bool ok_;
};

silk_status Busy(const char* function) {
  return SetError(SILK_ERR_BUSY, std::string(function) + ": another call is inside this batch");
}

silk::MeshRowsCallbacks ToCallbacks(silk_batch* b) {
  silk::MeshRowsCallbacks cb;
  cb.cancel = [b] { return b->Cancelled(); };
  if (b->params.progress)
    cb.progress = [b](int32_t input, const silk::GenerateProgress& x) {
      const silk_generate_progress c = silk::capi::ToCProgress(x);
      b->params.progress(input, &c, b->params.user_data);
    };
  return cb;
}

// An input's request and copy; a conversion error becomes that input's result.
int32_t AddInput(silk_batch* b, const silk_generate_input& input, const silk_generate_params& p) {
  auto request = silk::capi::ToRequest(p, false);
  if (!request.ok()) return b->rows.AddError(request.status().WithContext("silk_batch_add: "));
  auto in = silk::capi::ToInput(input, [b] { return b->Cancelled(); });
  if (!in.ok())
    return b->rows.AddError(
        in.status().WithContext((input.mesh && !input.mesh->source.empty() ? input.mesh->source : "input") + ": "));
  return b->rows.Add(*request, *in);
}

// An ended input's result into the caller's outs.
silk_status Deliver(silk::MeshRowsEnded e, silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  if (!e.result.ok()) {
    if (stats && e.result.status().code() == silk::StatusCode::kCancelled) {
      silk_generate_stats st = silk::capi::Blank<silk_generate_stats>();
      st.stop_reason = SILK_STOP_CANCELLED;
      silk::capi::StoreOut(stats, st);
    }
    return SetError(e.result.status());
  }
  silk::SessionResult& r = *e.result;
  auto mesh = silk::capi::MeshHandle(std::move(r.output.positions), r.generation.mesh);
  if (out_tokens) {
    auto tokens = std::make_unique<silk_tokens>();
    tokens->ids = std::move(r.generation.tokens);
    *out_tokens = tokens.release();
  }
  if (stats) {
    silk_generate_stats full;
    silk::capi::FillStats(r.generation.stats, &full);
    silk::capi::StoreOut(stats, full);
  }
  *out_mesh = mesh.release();
  return Ok();
}

}  // namespace

extern "C" {

silk_status silk_batch_create(const silk_model* model, const silk_batch_params* params, silk_batch** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_batch_create: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(model, "silk_batch_create: model is NULL");
    SILK_CAPI_TRY(
        silk::capi::CheckParamsSize("silk_batch_create", "silk_batch_params", params, "silk_batch_default_params()"));
    auto b = std::make_unique<silk_batch>(model->model);
    b->params = silk::capi::ReadParams(params, silk_batch_default_params());
    const int32_t rows =
        silk::ResolveRows(b->params.rows == SILK_MODEL_VALUE ? std::nullopt : std::optional<int32_t>(b->params.rows),
                          model->model->config());
    if (silk::Status s = b->rows.Open(b->params.parallel, rows, ToCallbacks(b.get())); !s.ok())
      return SetError(s.WithContext("silk_batch_create: "));
    *out = b.release();
    return Ok();
  });
}

void silk_batch_destroy(silk_batch* batch) { delete batch; }

silk_status silk_batch_add(silk_batch* b, const silk_generate_input* input, const silk_generate_params* params,
                           int32_t* out_index) {
  return Guard([&] {
    if (out_index) *out_index = -1;
    SILK_CAPI_REQUIRE(b && input, "silk_batch_add: batch or input is NULL");
    SILK_CAPI_TRY(silk::capi::CheckStructSize("silk_batch_add", "silk_generate_input", input->struct_size,
                                              sizeof(silk_generate_input),
                                              "set struct_size = sizeof(silk_generate_input) before the call"));
    SILK_CAPI_TRY(silk::capi::CheckParamsSize("silk_batch_add", "silk_generate_params", params,
                                              "silk_generate_default_params()"));
    BatchCall call(b);
    if (!call.ok()) return Busy("silk_batch_add");
    SILK_CAPI_REQUIRE(!b->closed, "silk_batch_add: the batch is closed (silk_batch_close)");
    SILK_CAPI_REQUIRE(!b->Cancelled(), "silk_batch_add: the batch was cancelled");
    const int32_t index = AddInput(b, *input, silk::capi::ReadParams(params, silk_generate_default_params()));
    if (out_index) *out_index = index;
    return Ok();
  });
}

silk_status silk_batch_close(silk_batch* b) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(b, "silk_batch_close: batch is NULL");
    BatchCall call(b);
    if (!call.ok()) return Busy("silk_batch_close");
    b->closed = true;
    return Ok();
  });
}

silk_status silk_batch_next(silk_batch* b, int32_t* out_index, silk_mesh** out_mesh, silk_tokens** out_tokens,
                            silk_generate_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_index && out_mesh, "silk_batch_next: out_index or out_mesh is NULL");
    *out_index = -1;
    *out_mesh = nullptr;
    if (out_tokens) *out_tokens = nullptr;
    SILK_CAPI_REQUIRE(b, "silk_batch_next: batch is NULL");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_batch_next", "silk_generate_stats", stats));
    BatchCall call(b);
    if (!call.ok()) return Busy("silk_batch_next");
    if (stats) silk::capi::StoreOut(stats, silk::capi::Blank<silk_generate_stats>());
    auto ended = b->rows.Next();
    if (!ended.ok()) return SetError(ended.status().WithContext("silk_batch_next: "));
    *out_index = ended->index;
    return Deliver(std::move(*ended), out_mesh, out_tokens, stats);
  });
}

silk_status silk_batch_counts(silk_batch* b, int32_t* in_flight, int32_t* queued) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(b, "silk_batch_counts: batch is NULL");
    BatchCall call(b);
    if (!call.ok()) return Busy("silk_batch_counts");
    if (in_flight) *in_flight = b->rows.in_flight();
    if (queued) *queued = b->rows.queued();
    return Ok();
  });
}

void silk_batch_cancel(silk_batch* b) {
  if (!b) return;
  b->cancelled.store(true);
  b->rows.InterruptEncoder();
}

}  // extern "C"
#endif
