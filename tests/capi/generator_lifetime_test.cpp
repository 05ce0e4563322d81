// SPDX-License-Identifier: MIT
// Issue 20, findings 1 and 4 (silk.h only): destroying a generator (or its model) while a call on
// it runs is safe, and a silk_generator_cancel issued at any moment of a call is never lost.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "silk/silk.h"
#include "support/capi_generate.h"
#include "silk/silk.hpp"
#include "support/capi_counts.h"
#include "support/test_paths.h"

namespace {

using Clock = std::chrono::steady_clock;

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

double Ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

std::vector<int32_t> IdsOf(silk_tokens* t) {
  std::vector<int32_t> ids(t ? silk::testing::TokenCount(t) : 0);
  if (!ids.empty()) silk_tokens_copy(t, ids.data(), ids.size(), nullptr);
  return ids;
}

class CapiLifetime : public silk::testing::TinyModelTest {};

// What a callback needs to reach the handles (user_data).
struct Handles {
  silk_generator* g = nullptr;
  silk_model* model = nullptr;
  int64_t at = 5;  // the id whose progress call acts
  std::atomic<bool> inside{false};
};

// Finding 1: silk_generator_destroy from another thread while silk_generator_run runs on the generator
// (before: SIGSEGV). The destroy lands at random moments of the call; the call returns SILK_OK
// (destroy after its end; delays up to 120 ms, about a call's length) or SILK_ERR_CANCELLED (destroy during it: the
// call is cancelled and frees the generator as it returns) and never crashes; ASan/LSan check the memory.
TEST_F(CapiLifetime, DestroyFromAnotherThreadDuringACallIsSafe) {
  const int iterations = kSanitized ? 12 : 40;
  std::mt19937 rng(20);
  int cancelled = 0;
  for (int i = 0; i < iterations; ++i) {
    Handles h;
    ASSERT_EQ(silk_generator_create(model_, &h.g), SILK_OK);
    silk_generate_params p = Params(i, 200);
    p.user_data = &h;
    p.cancel = [](void* u) -> int32_t {
      static_cast<Handles*>(u)->inside = true;
      return 0;
    };
    silk_status s = SILK_ERR_INTERNAL;
    silk_mesh* out = nullptr;
    std::thread caller([&] { s = silk::testing::GenerateFromMesh(h.g, mesh_, &p, &out, nullptr, nullptr); });
    while (!h.inside) std::this_thread::yield();
    std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 120000)(rng)));
    silk_generator_destroy(h.g);  // the generator is not used after this by anyone
    caller.join();
    ASSERT_TRUE(s == SILK_OK || s == SILK_ERR_CANCELLED) << i << ": " << silk_status_name(s);
    if (s == SILK_ERR_CANCELLED) {
      ++cancelled;
      EXPECT_EQ(out, nullptr);
    } else {
      EXPECT_NE(out, nullptr);
    }
    silk_mesh_destroy(out);
  }
  std::printf("[ destroy ] %d of %d calls were running when destroyed (cancelled)\n", cancelled, iterations);
  EXPECT_GT(cancelled, 0) << "no destroy landed inside a call: the test did not test";
}

// Finding 1: silk_generator_destroy from the generator's own progress callback (before: a
// use-after-free, "internal error: vector::reserve"). The call is cancelled and the generator
// freed as it returns; one-call and step-wise.
TEST_F(CapiLifetime, DestroyFromItsOwnProgressCallbackIsSafe) {
  Handles h;
  ASSERT_EQ(silk_generator_create(model_, &h.g), SILK_OK);
  silk_generate_params p = Params(3, 120);
  p.user_data = &h;
  p.progress = [](const silk_generate_progress* pr, void* u) {
    auto* h = static_cast<Handles*>(u);
    if (pr->tokens == h->at) silk_generator_destroy(h->g);
  };
  silk_mesh* out = nullptr;
  silk_tokens* t = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  EXPECT_EQ(silk::testing::GenerateFromMesh(h.g, mesh_, &p, &out, &t, &st), SILK_ERR_CANCELLED) << silk_last_error();
  EXPECT_EQ(out, nullptr);
  EXPECT_EQ(t, nullptr);
  EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);
  EXPECT_EQ(st.tokens, 5);

  // Step-wise: destroyed inside advance; advance returns cancelled and the handle is gone.
  ASSERT_EQ(silk_generator_create(model_, &h.g), SILK_OK);
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = mesh_;
  ASSERT_EQ(silk_generator_start(h.g, &in, &p), SILK_OK) << silk_last_error();
  int32_t done = 0;
  EXPECT_EQ(silk_generator_advance(h.g, 100, SILK_ADVANCE_IDS, &done), SILK_ERR_CANCELLED) << silk_last_error();
}

// The model a running generator uses may be destroyed mid-call (the generator holds a reference):
// the call completes with the ids of an undisturbed run.
TEST_F(CapiLifetime, ModelDestroyedDuringACallIsSafe) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  silk_generate_params p = Params(4, 120);
  silk_mesh* out = nullptr;
  silk_tokens* t = nullptr;
  ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, &t, nullptr), SILK_OK) << silk_last_error();
  const std::vector<int32_t> expected = IdsOf(t);
  silk_tokens_destroy(t);
  silk_mesh_destroy(out);
  Handles h;
  h.model = model_;
  p.user_data = &h;
  p.progress = [](const silk_generate_progress* pr, void* u) {
    auto* h = static_cast<Handles*>(u);
    if (pr->tokens == h->at) silk_model_destroy(h->model);
  };
  model_ = nullptr;
  EXPECT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, &t, nullptr), SILK_OK) << silk_last_error();
  EXPECT_EQ(IdsOf(t), expected);
  silk_tokens_destroy(t);
  silk_mesh_destroy(out);
  silk_generator_destroy(g);
}

// Finding 4: a cancel after the last id's poll (while the mesh is built and scored) was lost
// (SILK_OK with every id). Issued from the last id's progress call, it must cancel the call.
TEST_F(CapiLifetime, CancelAfterTheLastIdIsNotLost) {
  Handles h;
  ASSERT_EQ(silk_generator_create(model_, &h.g), SILK_OK);
  silk_generate_params p = Params(6, 120);
  p.user_data = &h;
  p.progress = [](const silk_generate_progress* pr, void* u) {
    if (pr->tokens == pr->max_tokens) silk_generator_cancel(static_cast<Handles*>(u)->g);
  };
  silk_mesh* out = nullptr;
  silk_tokens* t = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  EXPECT_EQ(silk::testing::GenerateFromMesh(h.g, mesh_, &p, &out, &t, &st), SILK_ERR_CANCELLED) << silk_last_error();
  EXPECT_EQ(out, nullptr);
  EXPECT_EQ(t, nullptr);
  EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);
  // The cancel belonged to that call: the next one runs to its end.
  p.progress = nullptr;
  EXPECT_EQ(silk::testing::GenerateFromMesh(h.g, mesh_, &p, &out, &t, &st), SILK_OK) << silk_last_error();
  EXPECT_FALSE(IdsOf(t).empty());
  silk_tokens_destroy(t);
  silk_mesh_destroy(out);
  silk_generator_destroy(h.g);
}

// One call of the stress test below, timed on the caller's clock.
struct Trial {
  silk_status status = SILK_ERR_INTERNAL;
  std::vector<int32_t> ids;
  bool mesh = false;
  Clock::time_point called, returned, cancel_issued;
};

// The call on this thread; `delay` (if any) after the call begins, silk_generator_cancel on another.
Trial RunAndCancel(silk_generator* g, const std::vector<double>& pts, const silk_generate_params& p,
                   const Clock::duration* delay) {
  Trial r;
  std::atomic<bool> started{false};
  std::thread canceller([&] {
    if (!delay) return;
    while (!started) std::this_thread::yield();
    std::this_thread::sleep_until(r.called + *delay);
    r.cancel_issued = Clock::now();
    silk_generator_cancel(g);
  });
  silk_mesh* out = nullptr;
  silk_tokens* t = nullptr;
  r.called = Clock::now();
  started = true;
  r.status = silk::testing::GenerateFromPoints(g, pts.data(), pts.size() / 6, &p, &out, &t, nullptr);
  r.returned = Clock::now();
  canceller.join();
  r.ids = IdsOf(t);
  r.mesh = out != nullptr;
  silk_tokens_destroy(t);
  silk_mesh_destroy(out);
  return r;
}

// Finding 4: silk_generator_cancel at random moments of a 2^20-point call (input conversion and
// checks take the first ~10-20 ms; before, a cancel there was lost: SILK_OK with all ids). Every
// call must either return SILK_ERR_CANCELLED with no output, or SILK_OK with exactly the ids of an
// uncancelled run, and then the cancel must have been issued when the call had not yet begun or
// had already ended. "Begun" and "ended" are the caller's clock readings just before the call and
// just after its return; a cancel is honoured from the call's first instruction to its last, so
// only a band of `slack` at either end (the few instructions between the clock reading and the
// call's own start or end, a thread switch) cannot be ordered and excuses an SILK_OK.
TEST_F(CapiLifetime, CancelAtRandomMomentsIsNeverLost) {
  const std::vector<double> pts = silk::testing::FibonacciSphere(size_t{1} << 20);
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  const silk_generate_params p = Params(7, 120);
  Trial base = RunAndCancel(g, pts, p, nullptr);  // warm-up, then the uncancelled reference
  base = RunAndCancel(g, pts, p, nullptr);
  ASSERT_EQ(base.status, SILK_OK) << silk_last_error();
  const Clock::duration length = base.returned - base.called;
  const Clock::duration slack = std::chrono::microseconds(kSanitized ? 2000 : 300);
  const int iterations = kSanitized ? 8 : 40;
  std::mt19937 rng(4);
  int cancelled = 0, after_end = 0, excused = 0;
  for (int i = 0; i < iterations; ++i) {
    // Half the delays fall in the first 25 ms (conversion, checks, pre-processing), half anywhere.
    const int64_t length_us = std::chrono::duration_cast<std::chrono::microseconds>(length).count();
    const int64_t span_us = i % 2 ? 25000 : length_us * 13 / 10;
    const Clock::duration delay = std::chrono::microseconds(std::uniform_int_distribution<int64_t>(0, span_us)(rng));
    const Trial r = RunAndCancel(g, pts, p, &delay);
    if (r.status == SILK_ERR_CANCELLED) {
      ++cancelled;
      EXPECT_FALSE(r.mesh) << i;
      EXPECT_TRUE(r.ids.empty()) << i;
      EXPECT_LE(r.cancel_issued, r.returned) << i << ": a call cancelled by a cancel issued after it returned";
      continue;
    }
    ASSERT_EQ(r.status, SILK_OK) << i << ": " << silk_last_error();
    EXPECT_TRUE(r.mesh);
    EXPECT_EQ(r.ids, base.ids) << i;
    const bool before = r.cancel_issued <= r.called + slack, after = r.cancel_issued >= r.returned - slack;
    if (r.cancel_issued >= r.returned)
      ++after_end;
    else if (before || after)
      ++excused;
    EXPECT_TRUE(before || after) << i << ": cancel issued " << Ms(r.cancel_issued - r.called) << " ms into a "
                                 << Ms(r.returned - r.called) << " ms call was lost (SILK_OK)";
  }
  std::printf(
      "[ cancel ] %d calls of %.1f ms: %d cancelled, %d ended before the cancel, %d SILK_OK within %.2f ms of an end\n",
      iterations, Ms(length), cancelled, after_end, excused, Ms(slack));
  silk_generator_destroy(g);
}

}  // namespace
