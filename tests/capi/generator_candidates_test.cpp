// SPDX-License-Identifier: MIT
// Issue 34 (C API 1.5), silk.h only: every candidate of best of N is shown while the run goes on
// (silk_generator_candidate_count / _get_candidate / _get_candidate_mesh): states only move forward
// (waiting -> running -> ended -> scored), ids only grow, a built candidate's faces are those of its
// mesh, exactly one scored candidate is the best so far (the lowest score), the one finally marked
// is the one finish returns with its mesh, and the calls refuse a generator with no run or an index
// out of range, naming the index and N.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "silk/silk.h"
#include "silk/silk.hpp"
#include "support/capi_generate.h"
#include "support/test_paths.h"

namespace {

std::vector<double> Positions(const silk_mesh* m) {
  size_t n = 0;
  EXPECT_EQ(silk_mesh_copy_positions(m, nullptr, 0, &n), SILK_OK);
  std::vector<double> out(n);
  if (n) {
    EXPECT_EQ(silk_mesh_copy_positions(m, out.data(), n, nullptr), SILK_OK);
  }
  return out;
}

size_t Faces(const silk_mesh* m) {
  size_t n = 0;
  EXPECT_EQ(silk_mesh_copy_triangles(m, nullptr, 0, &n), SILK_OK) << silk_last_error();
  return n / 3;
}

class CapiCandidates : public silk::testing::TinyGeneratorTest {
 protected:
  // Contract v4: best of N runs as rows there (a batch-1 folder runs its candidates one after another).
  std::string ModelDir() const override { return "tests/models/tiny-rows"; }

 protected:
  std::vector<silk_candidate_info> View() {
    int32_t n = 0;
    EXPECT_EQ(silk_generator_candidate_count(g_, &n), SILK_OK) << silk_last_error();
    std::vector<silk_candidate_info> out(static_cast<size_t>(n), silk_cpp::Sized<silk_candidate_info>());
    for (int32_t i = 0; i < n; ++i)
      EXPECT_EQ(silk_generator_get_candidate(g_, i, &out[static_cast<size_t>(i)]), SILK_OK) << silk_last_error();
    return out;
  }
  silk_mesh* CandidateMesh(int32_t i) {
    silk_mesh* m = nullptr;
    EXPECT_EQ(silk_generator_get_candidate_mesh(g_, i, &m), SILK_OK) << silk_last_error();
    return m;
  }
  // One view's rules (every candidate, against the previous view of the same run).
  void CheckView(const std::vector<silk_candidate_info>& now, const std::vector<silk_candidate_info>& before) {
    int best = 0;
    double lowest = INFINITY;
    for (const silk_candidate_info& c : now)
      if (c.state == SILK_CANDIDATE_SCORED) lowest = std::fmin(lowest, c.score);
    for (size_t i = 0; i < now.size(); ++i) {
      const silk_candidate_info& c = now[i];
      const std::string at = "candidate " + std::to_string(i) + " (" + silk_candidate_state_name(c.state) + ")";
      EXPECT_EQ(c.index, static_cast<int32_t>(i));
      EXPECT_EQ(c.struct_size, sizeof(silk_candidate_info));
      if (!before.empty()) {
        EXPECT_GE(c.state, before[i].state) << at;
        EXPECT_GE(c.tokens, before[i].tokens) << at;
      }
      const bool built = c.state == SILK_CANDIDATE_ENDED || c.state == SILK_CANDIDATE_SCORED;
      silk_mesh* m = CandidateMesh(static_cast<int32_t>(i));
      if (built) {
        EXPECT_EQ(static_cast<size_t>(c.faces), Faces(m)) << at;
        EXPECT_GT(c.tokens, 0) << at;
      } else {
        EXPECT_EQ(c.faces, -1) << at;
      }
      if (c.state == SILK_CANDIDATE_WAITING) {
        EXPECT_EQ(c.tokens, 0) << at;
        EXPECT_EQ(Faces(m), 0u) << at;
      }
      silk_mesh_destroy(m);
      EXPECT_EQ(c.state == SILK_CANDIDATE_SCORED, !std::isnan(c.score)) << at;
      if (c.best) {
        ++best;
        EXPECT_EQ(c.state, SILK_CANDIDATE_SCORED) << at;
        EXPECT_EQ(c.score, lowest) << at;
      }
    }
    EXPECT_EQ(best, std::isinf(lowest) ? 0 : 1) << "one best among the scored";
  }
};

TEST_F(CapiCandidates, EveryCandidateIsShownWhileTheyRun) {
  int chosen_later = 0;
  // One after another (rows 1), and two rows at once (candidate 2 waits for a free row).
  for (const auto& [seed, rows] : {std::pair<uint64_t, int32_t>{5, 1}, {8, 1}, {5, 2}, {8, 2}}) {
    silk_generate_params p = Params(seed, 200);
    p.candidates = 3;
    p.rows = rows;
    ASSERT_EQ(silk_generator_start(g_, &in_, &p), SILK_OK) << silk_last_error();
    std::vector<silk_candidate_info> before = View();
    ASSERT_EQ(before.size(), 3u);
    EXPECT_EQ(before[0].state, SILK_CANDIDATE_RUNNING);
    EXPECT_EQ(before[1].state, rows > 1 ? SILK_CANDIDATE_RUNNING : SILK_CANDIDATE_WAITING);
    EXPECT_EQ(before[2].state, SILK_CANDIDATE_WAITING);
    CheckView(before, {});
    std::vector<int> seen(3, 0);  // bit per state seen, per candidate
    int32_t done = 0;
    while (!done) {
      ASSERT_EQ(silk_generator_advance(g_, 10, SILK_ADVANCE_IDS, &done), SILK_OK) << silk_last_error();
      const std::vector<silk_candidate_info> now = View();
      CheckView(now, before);
      // The candidate get_mesh shows (the one in progress) has the same mesh in the candidates' view.
      silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
      ASSERT_EQ(silk_generator_get_stats(g_, &st), SILK_OK);
      const silk_candidate_info& shown = now[static_cast<size_t>(st.chosen_candidate)];
      if (shown.state == SILK_CANDIDATE_RUNNING) {
        silk_mesh* a = nullptr;
        ASSERT_EQ(silk_generator_get_mesh(g_, &a), SILK_OK);
        silk_mesh* b = CandidateMesh(st.chosen_candidate);
        EXPECT_EQ(Positions(a), Positions(b));
        EXPECT_EQ(Faces(a), Faces(b));
        EXPECT_EQ(shown.tokens, st.tokens);
        silk_mesh_destroy(a);
        silk_mesh_destroy(b);
      }
      for (size_t i = 0; i < now.size(); ++i) seen[i] |= 1 << now[i].state;
      before = now;
    }
    for (size_t i = 0; i < 3; ++i) EXPECT_TRUE(seen[i] & (1 << SILK_CANDIDATE_RUNNING)) << "candidate " << i;
    EXPECT_TRUE(seen[0] & (1 << SILK_CANDIDATE_SCORED));
    // Finish returns the candidate with the ids and (once built) the mesh the view showed.
    std::vector<std::vector<double>> shown;
    for (int32_t i = 0; i < 3; ++i) {
      silk_mesh* m = CandidateMesh(i);
      shown.push_back(Positions(m));
      silk_mesh_destroy(m);
    }
    silk_mesh* out = nullptr;
    silk_tokens* ids = nullptr;
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    ASSERT_EQ(silk_generator_finish(g_, &out, &ids, &st), SILK_OK) << silk_last_error();
    const silk_candidate_info& chosen = before[static_cast<size_t>(st.chosen_candidate)];
    size_t n_ids = 0;
    EXPECT_EQ(silk_tokens_copy(ids, nullptr, 0, &n_ids), SILK_OK);
    EXPECT_EQ(static_cast<int64_t>(n_ids), chosen.tokens);
    if (chosen.state == SILK_CANDIDATE_SCORED) {  // (the last, built by finish, was not shown whole)
      EXPECT_EQ(static_cast<size_t>(chosen.faces), Faces(out));
      EXPECT_EQ(Positions(out), shown[static_cast<size_t>(st.chosen_candidate)]);
      EXPECT_EQ(chosen.score, st.score);
    }
    chosen_later += st.chosen_candidate > 0;
    silk_mesh_destroy(out);
    silk_tokens_destroy(ids);
    // After finish: no generation in progress.
    int32_t n = 0;
    EXPECT_EQ(silk_generator_candidate_count(g_, &n), SILK_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(silk_last_error(), "no generation in progress"), nullptr) << silk_last_error();
  }
  EXPECT_GT(chosen_later, 0) << "candidate 0 won every time: the best mark never moved; pick other seeds";
}

TEST_F(CapiCandidates, RefusesNoRunAndIndexOutOfRange) {
  int32_t n = -1;
  silk_candidate_info c = silk_cpp::Sized<silk_candidate_info>();
  silk_mesh* m = nullptr;
  EXPECT_EQ(silk_generator_candidate_count(g_, &n), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(silk_generator_get_candidate(g_, 0, &c), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(silk_generator_get_candidate_mesh(g_, 0, &m), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::strstr(silk_last_error(), "silk_generator_get_candidate_mesh: no generation in progress"), nullptr)
      << silk_last_error();
  EXPECT_EQ(m, nullptr);
  silk_generate_params p = Params(5, 60);
  p.candidates = 3;
  ASSERT_EQ(silk_generator_start(g_, &in_, &p), SILK_OK) << silk_last_error();
  ASSERT_EQ(silk_generator_candidate_count(g_, &n), SILK_OK);
  EXPECT_EQ(n, 3);
  for (int32_t bad : {3, -1, 1 << 30}) {
    EXPECT_EQ(silk_generator_get_candidate(g_, bad, &c), SILK_ERR_INVALID_ARGUMENT);
    const std::string e = silk_last_error();
    EXPECT_NE(e.find("candidate " + std::to_string(bad) + " is out of range"), std::string::npos) << e;
    EXPECT_NE(e.find("3 candidates"), std::string::npos) << e;
    EXPECT_EQ(silk_generator_get_candidate_mesh(g_, bad, &m), SILK_ERR_INVALID_ARGUMENT);
    EXPECT_EQ(m, nullptr);
  }
  silk_candidate_info unsized{};
  EXPECT_EQ(silk_generator_get_candidate(g_, 0, &unsized), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::strstr(silk_last_error(), "silk_candidate_info"), nullptr) << silk_last_error();
  EXPECT_EQ(silk_generator_candidate_count(g_, nullptr), SILK_ERR_INVALID_ARGUMENT);
}

// silk.hpp: Generator::Candidates / CandidateMesh over the same calls, one after another and as rows.
TEST_F(CapiCandidates, CppWrapperListsTheCandidates) {
  silk_model_params o = silk_model_default_params();
  o.threads = 1;
  const silk_cpp::Model model = silk_cpp::Model::Load(silk::testing::SourcePath("tests/models/tiny-rows"), o);
  silk_cpp::Generator gen(model);
  for (const auto& [n, rows] : {std::pair<int32_t, int32_t>{1, 1}, {2, 1}, {2, 2}}) {
    silk_generate_params p = Params(5, 40);
    p.candidates = n;
    p.rows = rows;
    gen.Start(in_, p);
    while (!gen.Advance(1000)) {
    }
    const std::vector<silk_candidate_info> all = gen.Candidates();
    ASSERT_EQ(all.size(), static_cast<size_t>(n));
    if (rows > 1) {  // rows: each candidate is built and scored as it ends
      for (const silk_candidate_info& c : all) EXPECT_EQ(c.state, SILK_CANDIDATE_SCORED);
    } else {
      EXPECT_EQ(all.front().state, n > 1 ? SILK_CANDIDATE_SCORED : SILK_CANDIDATE_RUNNING);
      EXPECT_EQ(all.back().state, SILK_CANDIDATE_RUNNING);  // one after another: built and scored by finish
    }
    EXPECT_GT(all.back().tokens, 0);
    EXPECT_GT(gen.CandidateMesh(n - 1).triangles().size(), 0u);
    EXPECT_THROW(gen.CandidateMesh(n), silk_cpp::Error);
    gen.Finish();
  }
}

}  // namespace
