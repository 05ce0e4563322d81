// SPDX-License-Identifier: MIT
// C API: the step-wise generator (start / advance / query / cancel / finish) and the one-call
// silk_generator_run (start + advance to the end + finish), both over the runtime's GenerationSession:
// here only the C structs <-> runtime types, argument checks, errors and the call state.
#if defined(SILK_HAVE_RUNTIME)
#include <memory>

#include "capi/capi_generator.h"

using silk::capi::Busy;
using silk::capi::BusyLock;
using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;
using silk::capi::ToInput;
using silk::capi::ToRequest;

namespace {

// The generator's own cancel flag alone (silk_generator_cancel): what the loops the caller's
// callback is not polled in (input conversion and checks, scoring) poll in chunks.
silk::CancelCheck FlagCheck(silk_generator* g) {
  return [g] { return g->cancelled(); };
}

// The user's callbacks plus the generator's own cancel flag (silk_generator_cancel).
silk::GenerateCallbacks ToCallbacks(silk_generator* g, const silk_generate_params& p) {
  silk::GenerateCallbacks cb;
  if (p.progress) {
    cb.progress = [fn = p.progress, user = p.user_data](const silk::GenerateProgress& x) {
      const silk_generate_progress c = silk::capi::ToCProgress(x);
      fn(&c, user);
    };
  }
  cb.cancel = [g, fn = p.cancel, user = p.user_data]() { return g->cancelled() || (fn && fn(user) != 0); };
  return cb;
}

// Start of a run (step-wise or one-call): the call's first cancel poll, the params and input
// converted, the settings recorded for the report, then the session's start (request resolved,
// input checked, points prepared, candidate 0's encoder run). The run's cancel flag was cleared
// as the call took the generator (BusyLock), so a cancel from then on is never lost.
silk_status Start(silk_generator* g, const silk_generate_input& input, const silk_generate_params& p) {
  const silk::GenerateCallbacks cb = ToCallbacks(g, p);
  if (cb.cancel()) {  // the call's first poll, before the (long) input conversion
    g->has_result = false;
    return SetError(SILK_ERR_CANCELLED, "generation cancelled");
  }
  auto request = ToRequest(p, g->unconstrained);
  if (!request.ok()) return SetError(request.status().WithContext("silk_generator_start: "));
  auto in = ToInput(input, FlagCheck(g));  // its problems, like the session's, name the input's file
  if (!in.ok())
    return SetError(
        in.status().WithContext((input.mesh && !input.mesh->source.empty() ? input.mesh->source : "input") + ": "));
  g->has_result = false;
  GenerationSettings& s = g->settings;
  s = GenerationSettings{};
  s.input_name = input.mesh ? (input.mesh->source.empty() ? "mesh" : input.mesh->source) : "points";
  s.point_cloud = in->point_cloud;
  s.input_vertices = static_cast<int32_t>(in->mesh.positions.size());
  s.input_faces = static_cast<int32_t>(in->mesh.triangles.size());
  s.params = p;
  s.unconstrained = g->unconstrained;
  return SetError(g->session.Start(*request, *in, cb, FlagCheck(g)));
}

silk_status Advance(silk_generator* g, int32_t max_ids, int32_t until) {
  return SetError(
      g->session.Advance(max_ids, until == SILK_ADVANCE_LAYER ? silk::AdvanceUntil::kLayer : silk::AdvanceUntil::kIds));
}

// The runtime's figures into the caller's stats (only its struct_size bytes).
void StoreStats(const silk::GenerationStats& st, silk_generate_stats* out) {
  silk_generate_stats full;
  silk::capi::FillStats(st, &full);
  silk::capi::StoreOut(out, full);
}

// A finished generation (the chosen candidate) as the caller's mesh, ids and figures.
silk_status Deliver(silk_generator* g, silk::SessionResult r, silk_mesh** out_mesh, silk_tokens** out_tokens,
                    silk_generate_stats* stats) {
  g->result = std::move(r.generation);
  const silk::GenerationStats& st = g->result.stats;
  g->has_result = true;
  auto mesh = silk::capi::MeshHandle(std::move(r.output.positions), g->result.mesh);
  std::unique_ptr<silk_tokens> tokens;
  if (out_tokens) {
    tokens = std::make_unique<silk_tokens>();
    tokens->ids = g->result.tokens;
  }
  if (stats) StoreStats(st, stats);
  silk::capi::Log(SILK_LOG_DEBUG, "generated " + std::to_string(st.tokens) + " ids (" +
                                      silk::StopReasonName(st.stop_reason) + ") -> " + std::to_string(st.faces) +
                                      " faces");
  *out_mesh = mesh.release();
  if (out_tokens) *out_tokens = tokens.release();
  return Ok();
}

// A cancelled one-call run: the ids and stats of the candidate in progress (stop reason
// cancelled) are kept for silk_generator_get_tokens/get_stats; the run is released unscored, its mesh
// is not returned and there is no report of it.
silk_status Cancelled(silk_generator* g, silk_generate_stats* stats) {
  const std::string message = silk_last_error();
  g->result = silk::GenerateResult{};
  g->result.tokens = g->session.tokens();
  g->result.stats = g->session.CancelledStats();
  g->session.Abandon();
  g->has_result = false;
  if (stats) StoreStats(g->result.stats, stats);
  return SetError(SILK_ERR_CANCELLED, message);
}

// Finishes the run (the chosen candidate); `scoring` (one-call runs) may stop the scoring: then
// the run is cancelled.
silk_status Finish(silk_generator* g, silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats,
                   const silk::CancelCheck& scoring = {}) {
  auto r = g->session.Finish(scoring);
  if (!r.ok()) {
    const silk_status s = SetError(r.status());
    return s == SILK_ERR_CANCELLED ? Cancelled(g, stats) : s;
  }
  return Deliver(g, std::move(*r), out_mesh, out_tokens, stats);
}

// A one-call run cancelled after its last poll (while its output was built): the output is
// dropped, as if the cancel had come a moment earlier.
silk_status DropOutput(silk_generator* g, silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  delete *out_mesh;
  *out_mesh = nullptr;
  if (out_tokens) {
    delete *out_tokens;
    *out_tokens = nullptr;
  }
  if (stats) {
    silk_generate_stats st = silk::capi::Blank<silk_generate_stats>();
    st.stop_reason = SILK_STOP_CANCELLED;
    silk::capi::StoreOut(stats, st);
  }
  g->has_result = false;
  return SetError(SILK_ERR_CANCELLED, "generation cancelled");
}

// start + advance to the end + finish; a cancel still fills the stats.
silk_status RunAll(silk_generator* g, const silk_generate_input& input, const silk_generate_params* params,
                   silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  const silk_generate_params p = silk::capi::ReadParams(params, silk_generate_default_params());
  if (stats) silk::capi::StoreOut(stats, silk::capi::Blank<silk_generate_stats>());
  silk_status s = Start(g, input, p);
  if (s == SILK_OK) s = Advance(g, INT32_MAX, SILK_ADVANCE_IDS);
  if (s == SILK_ERR_CANCELLED) return Cancelled(g, stats);
  if (s != SILK_OK) return s;
  return Finish(g, out_mesh, out_tokens, stats, ToCallbacks(g, p).cancel);  // the last candidate's scoring
}

// The struct_size checks of a call taking an input, params and stats (each may be NULL here).
silk_status CheckSizes(const char* function, const silk_generate_input* input, const silk_generate_params* params,
                       const silk_generate_stats* stats) {
  if (input)
    SILK_CAPI_TRY(silk::capi::CheckStructSize(function, "silk_generate_input", input->struct_size,
                                              sizeof(silk_generate_input),
                                              "set struct_size = sizeof(silk_generate_input) before the call"));
  SILK_CAPI_TRY(
      silk::capi::CheckParamsSize(function, "silk_generate_params", params, "silk_generate_default_params()"));
  return silk::capi::CheckOutSize(function, "silk_generate_stats", stats);
}

}  // namespace

extern "C" {

silk_status silk_generator_create(const silk_model* model, silk_generator** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_generator_create: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(model, "silk_generator_create: model is NULL");
    *out = new silk_generator(model->model);
    return Ok();
  });
}

void silk_generator_destroy(silk_generator* generator) {
  if (!generator || silk::capi::DeferDestroy(generator)) return;  // deferred: the call inside frees it
  delete generator;
}

silk_status silk_generator_start(silk_generator* g, const silk_generate_input* input,
                                 const silk_generate_params* params) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && input, "silk_generator_start: generator or input is NULL");
    SILK_CAPI_TRY(CheckSizes("silk_generator_start", input, params, nullptr));
    BusyLock lock(g, BusyLock::kBegin);
    if (!lock.ok()) return Busy("silk_generator_start");
    const silk_status s = Start(g, *input, silk::capi::ReadParams(params, silk_generate_default_params()));
    if (s == SILK_OK) lock.KeepRun();  // the run goes on until finish (a cancel now is for it)
    return s;
  });
}

silk_status silk_generator_advance(silk_generator* g, int32_t max_ids, int32_t until, int32_t* out_done) {
  return Guard([&] {
    if (out_done) *out_done = 0;
    SILK_CAPI_REQUIRE(g, "silk_generator_advance: generator is NULL");
    SILK_CAPI_REQUIRE(max_ids >= 1, "silk_generator_advance: max_ids must be at least 1");
    SILK_CAPI_REQUIRE(until == SILK_ADVANCE_IDS || until == SILK_ADVANCE_LAYER,
                      "silk_generator_advance: until is not a silk_advance_until (0..1)");
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_advance");
    if (!g->session.active())
      return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_advance: no generation started");
    const silk_status s = Advance(g, max_ids, until);
    if (out_done) *out_done = g->session.done() ? 1 : 0;
    return s;
  });
}

void silk_generator_cancel(silk_generator* g) {
  if (g) silk::capi::CancelRun(g);  // flag first: Start polls it after clearing the terminate flag
}

silk_status silk_generator_get_tokens(silk_generator* g, silk_tokens** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_get_tokens: NULL argument");
    *out = nullptr;
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_get_tokens");
    auto t = std::make_unique<silk_tokens>();
    t->ids = g->session.active() ? g->session.tokens() : g->result.tokens;
    *out = t.release();
    return Ok();
  });
}

silk_status silk_generator_get_mesh(silk_generator* g, silk_mesh** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_get_mesh: NULL argument");
    *out = nullptr;
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_get_mesh");
    if (!g->session.active())
      return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_get_mesh: no generation in progress");
    auto preview = g->session.Preview();
    if (!preview.ok()) return SetError(preview.status());
    auto h = silk::capi::MeshHandle(std::move(preview->output.positions), preview->grid);
    *out = h.release();
    return Ok();
  });
}

silk_status silk_generator_get_stats(silk_generator* g, silk_generate_stats* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_get_stats: NULL argument");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_generator_get_stats", "silk_generate_stats", out));
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_get_stats");
    if (!g->session.active()) {
      StoreStats(g->result.stats, out);
      return Ok();
    }
    silk_generate_stats st;
    silk::capi::FillStats(g->session.stats(), &st);
    auto preview = g->session.Preview();
    if (preview.ok()) {
      st.faces = static_cast<int32_t>(preview->grid.faces.size());
      st.vertices = static_cast<int32_t>(preview->grid.positions.size());
      st.components = preview->grid.components;
    }
    st.candidates = g->session.candidates();       // during a run: N
    st.chosen_candidate = g->session.candidate();  // and the one in progress
    silk::capi::StoreOut(out, st);
    return Ok();
  });
}

silk_status silk_generator_finish(silk_generator* g, silk_mesh** out_mesh, silk_tokens** out_tokens,
                                  silk_generate_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_mesh, "silk_generator_finish: out_mesh is NULL");
    *out_mesh = nullptr;
    if (out_tokens) *out_tokens = nullptr;
    SILK_CAPI_REQUIRE(g, "silk_generator_finish: generator is NULL");
    SILK_CAPI_TRY(CheckSizes("silk_generator_finish", nullptr, nullptr, stats));
    BusyLock lock(g, BusyLock::kEnd);
    if (!lock.ok()) return Busy("silk_generator_finish");
    if (!g->session.active())
      return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_finish: no generation started");
    return Finish(g, out_mesh, out_tokens, stats);
  });
}

silk_status silk_generator_report(silk_generator* g, int32_t trace, silk_report** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_generator_report: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(g, "silk_generator_report: generator is NULL");
    SILK_CAPI_REQUIRE(trace == 0 || trace == 1, "silk_generator_report: trace takes 0 or 1");
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_report");
    if (!g->has_result) return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_report: no finished generation");
    if (trace && !(g->settings.params.report_flags & SILK_GENERATE_RECORD_TRACE))
      return SetError(SILK_ERR_INVALID_ARGUMENT,
                      "silk_generator_report: the generation ran without report_flags SILK_GENERATE_RECORD_TRACE");
    auto r = std::make_unique<silk_report>();
    r->json = silk::capi::ReportJson(*g, trace != 0);
    *out = r.release();
    return Ok();
  });
}

silk_status silk_generator_run(silk_generator* g, const silk_generate_input* input, const silk_generate_params* params,
                               silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_mesh, "silk_generator_run: out_mesh is NULL");
    *out_mesh = nullptr;
    if (out_tokens) *out_tokens = nullptr;
    SILK_CAPI_REQUIRE(g && input, "silk_generator_run: generator or input is NULL");
    SILK_CAPI_TRY(CheckSizes("silk_generator_run", input, params, stats));
    BusyLock lock(g, BusyLock::kWhole);  // the run, and its cancel flag, begin here
    if (!lock.ok()) return Busy("silk_generator_run");
    const silk_status s = RunAll(g, *input, params, out_mesh, out_tokens, stats);
    // The run ends here: a cancel that came before is honoured even if no poll was left to see it.
    if (lock.EndRun() && s == SILK_OK) return DropOutput(g, out_mesh, out_tokens, stats);
    return s;
  });
}

}  // extern "C"
#endif
