// SPDX-License-Identifier: MIT
// The generation handles behind silk.h: silk_model shares its Model with every generator made
// from it (destroy order is free), and silk_generator carries one GenerationSession (the runtime's
// generation, runtime/generation_session.h), the settings as the caller gave them, the last
// result, and a call state word: busy (concurrent use -> SILK_ERR_BUSY), run, cancel, and a
// destroy deferred to the end of the call in progress.
#pragma once
#if defined(SILK_HAVE_RUNTIME)
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "capi/capi_internal.h"
#include "runtime/generation_session.h"
#include "runtime/model/model.h"

struct silk_model {
  std::shared_ptr<silk::Model> model;
};

// What the report needs to say about the last generation besides its stats and the session's
// resolved plan and points: the input and the params as given.
struct GenerationSettings {
  std::string input_name;
  bool point_cloud = false;
  int32_t input_vertices = 0, input_faces = 0;
  silk_generate_params params{};
  bool unconstrained = false;  // the generator's measurement mode at the start (capi/capi_measurement.h)
};

struct silk_generator {
  explicit silk_generator(std::shared_ptr<silk::Model> m) : model(std::move(m)), session(*model) {}
  std::shared_ptr<silk::Model> model;  // keeps the model alive as long as the generator
  silk::GenerationSession session;
  // kBusy: a call is inside. kRun: a run is in progress (a silk_generator_run call; step-wise, from
  // start until finish or a failed start). kCancel: the run is cancelled (set only under kRun,
  // cleared when a run begins or ends). kDoomed: destroyed during a call, which frees the handle.
  enum State : uint32_t { kBusy = 1, kRun = 2, kCancel = 4, kDoomed = 8 };
  std::atomic<uint32_t> state{0};
  // Held across a cancel's flag + encoder interrupt and while a run begins, so an interrupt meant
  // for one run never reaches the next.
  std::mutex cancel_mu;
  bool cancelled() const { return (state.load() & kCancel) != 0; }
  GenerationSettings settings;
  // Measurement mode, no part of silk.h: generations without the grammar mask (in-tree tools and
  // tests set it through capi/capi_measurement.h).
  bool unconstrained = false;
  bool has_result = false;      // a finished generation (for the report)
  silk::GenerateResult result;  // tokens, stats, trace of the last finished (or cancelled) one
};

namespace silk::capi {

// Holds a generator for one call: ok() is false (SILK_ERR_BUSY) when another call is inside.
// Declared first in the call, so it is released last: its release ends the run when the call's
// `run` says so, and frees the generator when silk_generator_destroy came during the call.
class BusyLock {
 public:
  enum Run {
    kKeep,   // queries, advance: the run (and its cancel) go on
    kBegin,  // start: a run begins (its cancel flag cleared in the same step); ends unless KeepRun()
    kWhole,  // silk_generator_run: a run begins and ends with the call
    kEnd,    // finish: the run ends with the call
  };
  explicit BusyLock(silk_generator* g, Run run = kKeep);
  ~BusyLock();
  bool ok() const { return ok_; }
  // Ends the run now (kCancel with it): a cancel after this point is no longer for this run.
  // Returns true when the run was cancelled before it ended.
  bool EndRun();
  void KeepRun() { end_run_ = false; }

 private:
  silk_generator* g_;
  bool ok_ = false;
  bool end_run_;
};

// SILK_ERR_BUSY with the one message for a call refused because another is inside the generator.
silk_status Busy(const char* function);
// silk_generator_cancel / silk_generator_destroy on the state word (capi_generator_state.cpp).
void CancelRun(silk_generator* g);
// True: a call is inside; it is cancelled and frees the generator as it returns. False: the
// caller deletes it now.
bool DeferDestroy(silk_generator* g);

// The C params as the runtime's request (capi_request.cpp): the C-only checks (flags, enums,
// reserved slots), SILK_MODEL_VALUE as unset; `unconstrained` is the measurement mode.
StatusOr<GenerationRequest> ToRequest(const silk_generate_params& p, bool unconstrained);
// The caller's input (mesh, point cloud or raw points) as a GenerationInput, polling `cancel`.
StatusOr<GenerationInput> ToInput(const silk_generate_input& in, const CancelCheck& cancel);
// A progress report as the C callbacks get it.
silk_generate_progress ToCProgress(const GenerateProgress& x);
// GenerationStats -> silk_generate_stats (the C view of the one stats struct): a full struct
// (struct_size = sizeof), for StoreOut into the caller's.
void FillStats(const GenerationStats& s, silk_generate_stats* out);
// The report JSON (settings, input, figures; trace: points and every id's legal set).
std::string ReportJson(const silk_generator& g, bool trace);

}  // namespace silk::capi
#endif
