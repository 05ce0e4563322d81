// SPDX-License-Identifier: MIT
// Issue 20 (the runtime owns generation), silk.h only: the step-wise API honours best of N.
// start / advance / finish with N = 3 returns exactly what silk_generator_run returns (ids, faces,
// parts, chosen candidate), advancing by layers crosses the candidates (stats and progress name
// the one in progress), a cancel in candidate 2 of 3 leaves finish usable (these two with rows 1,
// one candidate after another; the rows' own steps and cancel: tests/runtime/candidate_rows_test.cpp),
// and the stop reasons have their names.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "silk/silk.h"
#include "silk/silk.hpp"
#include "support/capi_generate.h"
#include "support/test_paths.h"

namespace {

// What a finished generation returned, as plain vectors.
struct Outcome {
  std::vector<int32_t> ids, triangles, parts;
  std::vector<double> positions;
  silk_generate_stats stats = silk_cpp::Sized<silk_generate_stats>();
};

// Every element of a silk.h copy function (size query, then copy).
template <typename T, typename H>
std::vector<T> All(silk_status (*copy)(const H*, T*, size_t, size_t*), const H* h) {
  size_t n = 0;
  EXPECT_EQ(copy(h, nullptr, 0, &n), SILK_OK) << silk_last_error();
  std::vector<T> out(n);
  if (n) {
    EXPECT_EQ(copy(h, out.data(), n, nullptr), SILK_OK) << silk_last_error();
  }
  return out;
}

Outcome Collect(silk_mesh* m, silk_tokens* t, const silk_generate_stats& st) {
  Outcome o;
  o.stats = st;
  o.ids = All(silk_tokens_copy, t);
  o.triangles = All(silk_mesh_copy_triangles, m);
  o.parts = All(silk_mesh_copy_triangle_components, m);
  o.positions = All(silk_mesh_copy_positions, m);
  silk_tokens_destroy(t);
  silk_mesh_destroy(m);
  return o;
}

class CapiBestOfN : public silk::testing::TinyGeneratorTest {
 protected:
  // Candidates matter here; the id cap is one value throughout.
  static silk_generate_params Params(uint64_t seed, int32_t candidates) {
    silk_generate_params p = TinyModelTest::Params(seed, 200);
    p.candidates = candidates;
    return p;
  }
  Outcome OneCall(const silk_generate_params& p) {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    EXPECT_EQ(silk::testing::GenerateFromMesh(g_, mesh_, &p, &m, &t, &st), SILK_OK) << silk_last_error();
    return Collect(m, t, st);
  }
  Outcome Finish() {
    silk_mesh* m = nullptr;
    silk_tokens* t = nullptr;
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    EXPECT_EQ(silk_generator_finish(g_, &m, &t, &st), SILK_OK) << silk_last_error();
    return Collect(m, t, st);
  }
};

void ExpectSame(const Outcome& a, const Outcome& b, const std::string& what) {
  EXPECT_EQ(a.ids, b.ids) << what;
  EXPECT_EQ(a.triangles, b.triangles) << what;
  EXPECT_EQ(a.parts, b.parts) << what;
  EXPECT_EQ(a.positions, b.positions) << what;
  EXPECT_EQ(a.stats.candidates, b.stats.candidates) << what;
  EXPECT_EQ(a.stats.chosen_candidate, b.stats.chosen_candidate) << what;
  EXPECT_EQ(a.stats.score, b.stats.score) << what;
  EXPECT_EQ(a.stats.stop_reason, b.stats.stop_reason) << what;
}

TEST_F(CapiBestOfN, StepWiseEqualsOneCall) {
  int chosen_later = 0;
  for (uint64_t seed : {5, 8}) {
    const silk_generate_params p = Params(seed, 3);
    const Outcome want = OneCall(p);
    ASSERT_EQ(want.stats.candidates, 3);
    chosen_later += want.stats.chosen_candidate > 0;
    for (int32_t until : {SILK_ADVANCE_IDS, SILK_ADVANCE_LAYER}) {
      ASSERT_EQ(silk_generator_start(g_, &in_, &p), SILK_OK) << silk_last_error();
      int32_t done = 0;
      while (!done) ASSERT_EQ(silk_generator_advance(g_, 7, until, &done), SILK_OK) << silk_last_error();
      ExpectSame(Finish(), want, "seed " + std::to_string(seed) + " until " + std::to_string(until));
    }
  }
  // The equality is only telling when a later candidate wins somewhere.
  EXPECT_GT(chosen_later, 0) << "candidate 0 won every time: pick other seeds";
}

struct Progress {
  std::vector<int32_t> candidates;  // the candidate of each progress call, deduplicated
  int32_t n = 0;
};

TEST_F(CapiBestOfN, LayerStepsCrossTheCandidatesAndNameTheOneInProgress) {
  Progress pr;
  silk_generate_params p = Params(5, 3);
  p.rows = 1;  // one candidate after another (rows: candidate_rows_test)
  p.user_data = &pr;
  p.progress = [](const silk_generate_progress* x, void* u) {
    auto* pr = static_cast<Progress*>(u);
    pr->n = x->candidates;
    if (pr->candidates.empty() || pr->candidates.back() != x->candidate) pr->candidates.push_back(x->candidate);
  };
  ASSERT_EQ(silk_generator_start(g_, &in_, &p), SILK_OK) << silk_last_error();
  int32_t done = 0, last = 0, switches = 0;
  size_t last_faces = 0;
  while (!done) {
    ASSERT_EQ(silk_generator_advance(g_, 100000, SILK_ADVANCE_LAYER, &done), SILK_OK) << silk_last_error();
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    ASSERT_EQ(silk_generator_get_stats(g_, &st), SILK_OK);
    EXPECT_EQ(st.candidates, 3);
    silk_mesh* so_far = nullptr;
    ASSERT_EQ(silk_generator_get_mesh(g_, &so_far), SILK_OK) << silk_last_error();
    const size_t faces = All(silk_mesh_copy_triangle_components, so_far).size();
    silk_mesh_destroy(so_far);
    EXPECT_EQ(static_cast<size_t>(st.faces), faces);
    if (st.chosen_candidate != last) {  // the next candidate began: its preview starts again
      EXPECT_EQ(st.chosen_candidate, last + 1);
      ++switches;
    } else {
      EXPECT_GE(faces, last_faces);
    }
    last = st.chosen_candidate;
    last_faces = faces;
  }
  EXPECT_EQ(switches, 2);
  EXPECT_EQ(pr.candidates, (std::vector<int32_t>{0, 1, 2}));
  EXPECT_EQ(pr.n, 3);
  const Outcome got = Finish();
  EXPECT_EQ(got.stats.candidates, 3);
  EXPECT_EQ(got.stats.stop_reason, SILK_STOP_EOS);
}

struct CancelAt {
  silk_generator* g = nullptr;
  int32_t candidate = 1;
  int64_t tokens = 20;
};

// Cancelled 20 ids into candidate 2 of 3 (index 1): advance says so, the run is done, finish
// returns the better of candidate 1 (complete) and candidate 2 (its completed layers) with stop
// reason CANCELLED; candidate 1 alone is the plain run of the seed.
TEST_F(CapiBestOfN, CancelInTheSecondCandidateLeavesFinishUsable) {
  CancelAt at{g_};
  silk_generate_params p = Params(5, 3);
  p.rows = 1;  // one candidate after another (rows: candidate_rows_test)
  p.user_data = &at;
  p.progress = [](const silk_generate_progress* x, void* u) {
    auto* at = static_cast<CancelAt*>(u);
    if (x->candidate == at->candidate && x->tokens == at->tokens) silk_generator_cancel(at->g);
  };
  ASSERT_EQ(silk_generator_start(g_, &in_, &p), SILK_OK) << silk_last_error();
  int32_t done = 0;
  EXPECT_EQ(silk_generator_advance(g_, 1 << 30, SILK_ADVANCE_IDS, &done), SILK_ERR_CANCELLED);
  EXPECT_EQ(done, 1);
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  ASSERT_EQ(silk_generator_get_stats(g_, &st), SILK_OK);
  EXPECT_EQ(st.chosen_candidate, 1);
  EXPECT_EQ(st.tokens, 20);
  EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);
  const Outcome got = Finish();
  EXPECT_EQ(got.stats.stop_reason, SILK_STOP_CANCELLED);
  EXPECT_EQ(got.stats.candidates, 2);
  EXPECT_EQ(static_cast<size_t>(got.stats.faces), got.triangles.size() / 3);
  const Outcome first = OneCall(Params(5, 1));
  if (got.stats.chosen_candidate == 0) {
    EXPECT_EQ(got.ids, first.ids);
  } else {
    EXPECT_EQ(got.stats.chosen_candidate, 1);
    EXPECT_EQ(got.ids.size(), 20u);
    EXPECT_LE(got.stats.score, first.stats.score);
  }
  // The generator runs again as usual.
  const Outcome again = OneCall(Params(5, 3));
  EXPECT_EQ(again.stats.candidates, 3);
}

// Issue 35 (left over): a one-call run cancelled 20 ids into candidate 2 of 3 reports the two
// candidates it started (it said 0), the one in progress as the one whose figures are shown.
TEST_F(CapiBestOfN, OneCallCancelCountsTheCandidatesStarted) {
  CancelAt at{g_};
  silk_generate_params p = Params(5, 3);
  p.rows = 1;  // one candidate after another (rows: candidate_rows_test)
  p.user_data = &at;
  p.progress = [](const silk_generate_progress* x, void* u) {
    auto* at = static_cast<CancelAt*>(u);
    if (x->candidate == at->candidate && x->tokens == at->tokens) silk_generator_cancel(at->g);
  };
  silk_mesh* m = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  EXPECT_EQ(silk::testing::GenerateFromMesh(g_, mesh_, &p, &m, nullptr, &st), SILK_ERR_CANCELLED);
  EXPECT_EQ(m, nullptr);
  EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);
  EXPECT_EQ(st.candidates, 2);
  EXPECT_EQ(st.chosen_candidate, 1);
  EXPECT_EQ(st.tokens, 20);
  EXPECT_EQ(st.score, 0);  // the cancelled one was not scored
  silk_generate_stats kept = silk_cpp::Sized<silk_generate_stats>();
  ASSERT_EQ(silk_generator_get_stats(g_, &kept), SILK_OK);
  EXPECT_EQ(kept.candidates, 2);
}

TEST(CapiStopReason, Names) {
  EXPECT_STREQ(silk_stop_reason_name(SILK_STOP_EOS), "eos");
  EXPECT_STREQ(silk_stop_reason_name(SILK_STOP_MAX_TOKENS), "max_tokens");
  EXPECT_STREQ(silk_stop_reason_name(SILK_STOP_MAX_FACES), "max_faces");
  EXPECT_STREQ(silk_stop_reason_name(SILK_STOP_GRAMMAR_DEAD_END), "grammar_dead_end");
  EXPECT_STREQ(silk_stop_reason_name(SILK_STOP_CANCELLED), "cancelled");
  EXPECT_STREQ(silk_stop_reason_name(SILK_STOP_NONE), "none");
  EXPECT_STREQ(silk_stop_reason_name(5), "unknown");
  EXPECT_STREQ(silk_stop_reason_name(-2), "unknown");
}

}  // namespace
