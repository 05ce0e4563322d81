// SPDX-License-Identifier: MIT
// C API 1.5: the step-wise view of best of N's candidates (silk_generator_candidate_count,
// _get_candidate, _get_candidate_mesh) over GenerationSession::Candidates / PreviewCandidate, so a
// client shows every candidate while they run, the best so far marked, as the runtime sees them.
#if defined(SILK_HAVE_RUNTIME)
#include <string>

#include "capi/capi_generator.h"

using silk::capi::Busy;
using silk::capi::BusyLock;
using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

namespace {

// SILK_OK when a generation is in progress and `index` names one of its N candidates; otherwise
// SILK_ERR_INVALID_ARGUMENT naming `function`, the index and N.
silk_status CheckCandidate(const silk_generator& g, const char* function, int32_t index) {
  if (!g.session.active())
    return SetError(SILK_ERR_INVALID_ARGUMENT, std::string(function) + ": no generation in progress");
  const int32_t n = g.session.candidates();
  if (index < 0 || index >= n)
    return SetError(SILK_ERR_INVALID_ARGUMENT, std::string(function) + ": candidate " + std::to_string(index) +
                                                   " is out of range (the generation has " + std::to_string(n) +
                                                   " candidates: 0 to " + std::to_string(n - 1) + ")");
  return SILK_OK;
}

silk_candidate_state ToCState(silk::CandidateView::State s) {
  switch (s) {
    case silk::CandidateView::State::kWaiting:
      return SILK_CANDIDATE_WAITING;
    case silk::CandidateView::State::kRunning:
      return SILK_CANDIDATE_RUNNING;
    case silk::CandidateView::State::kEnded:
      return SILK_CANDIDATE_ENDED;
    case silk::CandidateView::State::kScored:
      return SILK_CANDIDATE_SCORED;
  }
  return SILK_CANDIDATE_WAITING;
}

}  // namespace

extern "C" {

silk_status silk_generator_candidate_count(silk_generator* g, int32_t* n) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && n, "silk_generator_candidate_count: NULL argument");
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_candidate_count");
    if (!g->session.active())
      return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_candidate_count: no generation in progress");
    *n = g->session.candidates();
    return Ok();
  });
}

silk_status silk_generator_get_candidate(silk_generator* g, int32_t index, silk_candidate_info* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_get_candidate: NULL argument");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_generator_get_candidate", "silk_candidate_info", out));
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_get_candidate");
    SILK_CAPI_TRY(CheckCandidate(*g, "silk_generator_get_candidate", index));
    const silk::CandidateView v = g->session.Candidates()[static_cast<size_t>(index)];
    auto c = silk::capi::Blank<silk_candidate_info>();
    c.index = v.index;
    c.state = ToCState(v.state);
    c.faces = v.faces;
    c.tokens = v.tokens;
    c.score = v.score;
    c.best = v.best ? 1 : 0;
    silk::capi::StoreOut(out, c);
    return Ok();
  });
}

silk_status silk_generator_get_candidate_mesh(silk_generator* g, int32_t index, silk_mesh** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_get_candidate_mesh: NULL argument");
    *out = nullptr;
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_get_candidate_mesh");
    SILK_CAPI_TRY(CheckCandidate(*g, "silk_generator_get_candidate_mesh", index));
    auto preview = g->session.PreviewCandidate(index);
    if (!preview.ok()) return SetError(preview.status());
    *out = silk::capi::MeshHandle(std::move(preview->output.positions), preview->grid).release();
    return Ok();
  });
}

}  // extern "C"
#endif
