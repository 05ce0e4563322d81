// SPDX-License-Identifier: MIT
// The SIGINT/SIGTERM handlers of interrupt.h: sigaction without SA_RESTART, so a blocked read or
// open returns EINTR; only async-signal-safe calls in the handler (a flag, alarm, unlink, raise).
// In cancel mode the first signal also arms a one-second alarm that ends the process if the work
// has not stopped by then.
#include "interrupt.h"

#include <csignal>

#include "silk/silk.h"

#ifndef _WIN32
#include <signal.h>
#include <unistd.h>
#endif

namespace silkapp {
namespace {

volatile std::sig_atomic_t g_signal = 0;
volatile std::sig_atomic_t g_cancel_mode = 0;

void Install(int sig, void (*handler)(int));

// Ends the process as `sig` would have, its temporaries removed.
void EndAs(int sig) {
  silk_file_discard_partial();
  Install(sig, SIG_DFL);
  std::raise(sig);
}

#ifndef _WIN32
// The work did not stop within a second of the first signal (a load or a loop without a cancel
// point): end as that signal.
extern "C" void OnDeadline(int) { EndAs(g_signal); }
#endif

extern "C" void OnSignal(int sig) {
  if (g_cancel_mode && g_signal == 0) {
    g_signal = sig;
#ifdef _WIN32
    Install(sig, OnSignal);  // Windows resets a handler to the default on delivery
#else
    Install(SIGALRM, OnDeadline);
    alarm(1);
#endif
    return;
  }
  EndAs(sig);
}

void Install(int sig, void (*handler)(int)) {
#ifdef _WIN32
  std::signal(sig, handler);
#else
  struct sigaction sa = {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocked call returns EINTR
  sigaction(sig, &sa, nullptr);
#endif
}

}  // namespace

void HandleInterrupts(OnInterrupt mode) {
  g_cancel_mode = mode == OnInterrupt::kCancel ? 1 : 0;
  Install(SIGINT, OnSignal);
  Install(SIGTERM, OnSignal);
#if defined(_WIN32) && defined(SIGBREAK)
  Install(SIGBREAK, OnSignal);
#endif
}

int InterruptSignal() { return g_signal; }

}  // namespace silkapp
