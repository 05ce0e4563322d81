// SPDX-License-Identifier: MIT
// C API: a generator's call state (issue 20): who is inside, which run a cancel belongs to, and a
// destroy that comes during a call, deferred to that call's end instead of freeing it under it.
#if defined(SILK_HAVE_RUNTIME)
#include "capi/capi_generator.h"

namespace silk::capi {

namespace {
constexpr uint32_t kBusy = silk_generator::kBusy, kRun = silk_generator::kRun, kCancel = silk_generator::kCancel,
                   kDoomed = silk_generator::kDoomed;
}  // namespace

BusyLock::BusyLock(silk_generator* g, Run run) : g_(g), end_run_(run != kKeep) {
  const bool begins = run == kBegin || run == kWhole;
  // A run begins under cancel_mu: an interrupt meant for the previous run has then been made,
  // and this run's Generator::Start clears it before its first poll.
  std::unique_lock<std::mutex> order(g->cancel_mu, std::defer_lock);
  if (begins) order.lock();
  uint32_t s = g->state.load();
  uint32_t next = 0;
  do {
    if (s & (kBusy | kDoomed)) return;
    next = begins ? ((s | kBusy | kRun) & ~kCancel) : (s | kBusy);
  } while (!g->state.compare_exchange_weak(s, next));
  ok_ = true;
}

bool BusyLock::EndRun() {
  uint32_t s = g_->state.load();
  while (!g_->state.compare_exchange_weak(s, s & ~(kRun | kCancel))) {
  }
  end_run_ = false;
  return (s & kCancel) != 0;
}

BusyLock::~BusyLock() {
  if (!ok_) return;
  uint32_t s = g_->state.load();
  uint32_t next = 0;
  do {
    next = end_run_ ? (s & ~(kBusy | kRun | kCancel)) : (s & ~kBusy);
  } while (!g_->state.compare_exchange_weak(s, next));
  if (!(s & kDoomed)) return;
  { std::lock_guard<std::mutex> wait(g_->cancel_mu); }  // a cancel still interrupting finishes first
  delete g_;
}

silk_status Busy(const char* function) {
  return SetError(SILK_ERR_BUSY,
                  std::string(function) + ": generator busy (in use on another thread; use one generator per thread)");
}

void CancelRun(silk_generator* g) {
  std::lock_guard<std::mutex> lock(g->cancel_mu);
  uint32_t s = g->state.load();
  do {
    if (!(s & kRun)) return;  // no run in progress: nothing to cancel (it never leaks into a later one)
  } while (!g->state.compare_exchange_weak(s, s | kCancel));
  g->session.InterruptEncoder();
}

bool DeferDestroy(silk_generator* g) {
  std::lock_guard<std::mutex> lock(g->cancel_mu);
  uint32_t s = g->state.load();
  for (;;) {
    if (s & kBusy) {  // a call is inside: cancel its run, and it frees the generator as it returns
      const uint32_t next = s | kDoomed | ((s & kRun) ? kCancel : 0u);
      if (!g->state.compare_exchange_weak(s, next)) continue;
      if (s & kRun) g->session.InterruptEncoder();
      return true;
    }
    if (g->state.compare_exchange_weak(s, s | kBusy | kDoomed)) return false;  // no call may begin now
  }
}

}  // namespace silk::capi
#endif
