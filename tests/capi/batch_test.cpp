// SPDX-License-Identifier: MIT
// The batch of inputs (C API 1.6, issue 34), silk.h only: every input pulled from silk_batch_next
// equals its silk_generator_run with the same params (ids, triangles, positions, chosen candidate
// and score), at parallel 3 on a decoder contract v4 folder (rows of several meshes) and on the
// batch-1 tiny folder (one after another); a broken input fails alone with its own message; a
// cancel ends the inputs in flight; misuse is a status and a message.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "silk/silk.h"
#include "silk/silk.hpp"
#include "support/capi_generate.h"
#include "support/test_paths.h"

namespace {

struct Output {
  silk_status status = SILK_ERR_INTERNAL;
  std::string error;
  std::vector<int32_t> ids, triangles;
  std::vector<double> positions;
  silk_generate_stats stats = silk_cpp::Sized<silk_generate_stats>();
};

Output Read(silk_status s, silk_mesh* mesh, silk_tokens* tokens, const silk_generate_stats& st) {
  Output o;
  o.status = s;
  o.stats = st;
  if (s != SILK_OK) {
    o.error = silk_last_error();
    return o;
  }
  size_t n = 0;
  silk_tokens_copy(tokens, nullptr, 0, &n);
  o.ids.resize(n);
  silk_tokens_copy(tokens, o.ids.data(), n, &n);
  silk_mesh_copy_triangles(mesh, nullptr, 0, &n);
  o.triangles.resize(n);
  silk_mesh_copy_triangles(mesh, o.triangles.data(), n, &n);
  silk_mesh_copy_positions(mesh, nullptr, 0, &n);
  o.positions.resize(n);
  silk_mesh_copy_positions(mesh, o.positions.data(), n, &n);
  silk_mesh_destroy(mesh);
  silk_tokens_destroy(tokens);
  return o;
}

class CapiBatch : public silk::testing::TinyModelTest {
 protected:
  void SetUp() override {
    TinyModelTest::SetUp();
    if (IsSkipped()) return;
    points_ = silk::testing::FibonacciSphere(3000);
    broken_ = points_;
    broken_[7] = std::numeric_limits<double>::quiet_NaN();
    params_ = {Params(3), Params(5), Params(9), Params(11)};
    params_[0].candidates = 3;
    params_[1].candidates = 1;
    params_[2].candidates = 4;
    params_[2].temperature = 0;
    params_[3].candidates = 2;
    params_[3].rows = 1;
  }
  // Input i: the sample mesh (even), the sphere's points (odd); `broken` replaces the points.
  silk_generate_input Input(size_t i, bool broken = false) const {
    silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
    if (i % 2 == 0 && !broken) {
      in.mesh = mesh_;
    } else {
      in.points = broken ? broken_.data() : points_.data();
      in.point_rows = points_.size() / 6;
    }
    return in;
  }
  Output Alone(size_t i) const {
    silk_generator* g = nullptr;
    EXPECT_EQ(silk_generator_create(model_, &g), SILK_OK);
    silk_generate_input in = Input(i);
    silk_mesh* mesh = nullptr;
    silk_tokens* tokens = nullptr;
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    const silk_status s = silk_generator_run(g, &in, &params_[i], &mesh, &tokens, &st);
    Output o = Read(s, mesh, tokens, st);
    silk_generator_destroy(g);
    return o;
  }
  silk_batch* Create(int32_t parallel, silk_batch_progress_fn progress = nullptr, void* user = nullptr) const {
    silk_batch_params bp = silk_batch_default_params();
    bp.parallel = parallel;
    bp.progress = progress;
    bp.user_data = user;
    silk_batch* b = nullptr;
    EXPECT_EQ(silk_batch_create(model_, &bp, &b), SILK_OK) << silk_last_error();
    return b;
  }
  // Pulls until nothing is left: the outputs by index.
  static std::map<int32_t, Output> PullAll(silk_batch* b) {
    std::map<int32_t, Output> out;
    for (;;) {
      int32_t index = -2;
      silk_mesh* mesh = nullptr;
      silk_tokens* tokens = nullptr;
      silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
      const silk_status s = silk_batch_next(b, &index, &mesh, &tokens, &st);
      if (index < 0) {
        EXPECT_EQ(s, SILK_ERR_INVALID_ARGUMENT);
        break;
      }
      EXPECT_EQ(out.count(index), 0u);
      out[index] = Read(s, mesh, tokens, st);
    }
    return out;
  }
  static void ExpectSame(const Output& a, const Output& b, const std::string& what) {
    ASSERT_EQ(a.status, SILK_OK) << what << ": " << a.error;
    ASSERT_EQ(b.status, SILK_OK) << what << ": " << b.error;
    EXPECT_EQ(a.ids, b.ids) << what;
    EXPECT_EQ(a.triangles, b.triangles) << what;
    EXPECT_EQ(a.positions, b.positions) << what;
    EXPECT_EQ(a.stats.candidates, b.stats.candidates) << what;
    EXPECT_EQ(a.stats.chosen_candidate, b.stats.chosen_candidate) << what;
    EXPECT_EQ(a.stats.score, b.stats.score) << what;
    EXPECT_EQ(a.stats.stop_reason, b.stats.stop_reason) << what;
    EXPECT_EQ(a.stats.rows, b.stats.rows) << what;
  }
  void EachInputIsItsRunAlone() {
    std::vector<Output> alone;
    for (size_t i = 0; i < params_.size(); ++i) alone.push_back(Alone(i));
    struct Seen {
      std::map<int32_t, int64_t> reports;
    } seen;
    silk_batch* b = Create(
        3, [](int32_t input, const silk_generate_progress*, void* u) { ++static_cast<Seen*>(u)->reports[input]; },
        &seen);
    ASSERT_TRUE(b);
    // Inputs 0, 1, a broken one (2), then 2 and 3 as indexes 3 and 4.
    for (size_t i = 0; i < params_.size(); ++i) {
      int32_t index = -1;
      if (i == 2) {
        silk_generate_input bad = Input(1, true);
        ASSERT_EQ(silk_batch_add(b, &bad, &params_[1], &index), SILK_OK);
        EXPECT_EQ(index, 2);
      }
      silk_generate_input in = Input(i);
      ASSERT_EQ(silk_batch_add(b, &in, &params_[i], &index), SILK_OK) << silk_last_error();
      EXPECT_EQ(index, static_cast<int32_t>(i < 2 ? i : i + 1));
    }
    int32_t in_flight = -1, queued = -1;
    ASSERT_EQ(silk_batch_counts(b, &in_flight, &queued), SILK_OK);
    EXPECT_EQ(in_flight + queued, 5);
    ASSERT_EQ(silk_batch_close(b), SILK_OK);
    silk_generate_input late = Input(0);
    EXPECT_EQ(silk_batch_add(b, &late, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(silk_last_error()).find("closed"), std::string::npos) << silk_last_error();
    std::map<int32_t, Output> got = PullAll(b);
    silk_batch_destroy(b);
    ASSERT_EQ(got.size(), 5u);
    EXPECT_EQ(got[2].status, SILK_ERR_INVALID_ARGUMENT);
    EXPECT_NE(got[2].error.find("input"), std::string::npos) << got[2].error;
    for (size_t i = 0; i < params_.size(); ++i)
      ExpectSame(got[static_cast<int32_t>(i < 2 ? i : i + 1)], alone[i], "input " + std::to_string(i));
    EXPECT_EQ(seen.reports.size(), 4u);  // every input that ran reported progress under its index
  }
  std::vector<double> points_, broken_;
  std::vector<silk_generate_params> params_;
};

class CapiBatchRows : public CapiBatch {
 protected:
  std::string ModelDir() const override { return "tests/models/tiny-rows"; }
};

TEST_F(CapiBatch, EachInputIsItsRunAloneOneAfterAnother) { EachInputIsItsRunAlone(); }
TEST_F(CapiBatchRows, EachInputIsItsRunAloneAsRows) { EachInputIsItsRunAlone(); }

TEST_F(CapiBatchRows, ACancelEndsTheInputsInFlight) {
  struct State {
    silk_batch* batch = nullptr;
    int64_t reports = 0;
  } state;
  state.batch = Create(
      2,
      [](int32_t, const silk_generate_progress*, void* u) {
        auto* s = static_cast<State*>(u);
        if (++s->reports == 100) silk_batch_cancel(s->batch);
      },
      &state);
  ASSERT_TRUE(state.batch);
  for (size_t i = 0; i < params_.size(); ++i) {
    silk_generate_input in = Input(i);
    ASSERT_EQ(silk_batch_add(state.batch, &in, &params_[i], nullptr), SILK_OK);
  }
  std::map<int32_t, Output> got = PullAll(state.batch);
  int cancelled = 0;
  for (const auto& [index, o] : got)
    if (o.status == SILK_ERR_CANCELLED) {
      ++cancelled;
      EXPECT_EQ(o.stats.stop_reason, SILK_STOP_CANCELLED);
    }
  EXPECT_GE(cancelled, 1);
  EXPECT_EQ(got.size(), params_.size());  // every input comes back, the queued ones unstarted
  EXPECT_NE(got.rbegin()->second.error.find("before it started"), std::string::npos) << got.rbegin()->second.error;
  silk_generate_input in = Input(0);
  EXPECT_EQ(silk_batch_add(state.batch, &in, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
  silk_batch_destroy(state.batch);
}

TEST_F(CapiBatchRows, MisuseIsAStatusAndAMessage) {
  silk_batch* b = nullptr;
  EXPECT_EQ(silk_batch_create(nullptr, nullptr, &b), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(silk_batch_create(model_, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
  silk_batch_params bp = silk_batch_default_params();
  EXPECT_EQ(bp.parallel, 1);
  bp.parallel = 17;
  EXPECT_EQ(silk_batch_create(model_, &bp, &b), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(silk_last_error()).find("parallel 17 is not in [1, 16]"), std::string::npos)
      << silk_last_error();
  double lo = 0, hi = 0;
  ASSERT_EQ(silk_param_range("parallel", &lo, &hi, nullptr), SILK_OK);
  EXPECT_EQ(lo, 1);
  EXPECT_EQ(hi, 16);
  bp = silk_batch_default_params();
  bp.struct_size = 3;
  EXPECT_EQ(silk_batch_create(model_, &bp, &b), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(b, nullptr);
  b = Create(2);
  ASSERT_TRUE(b);
  int32_t index = 5;
  silk_mesh* mesh = reinterpret_cast<silk_mesh*>(&index);
  EXPECT_EQ(silk_batch_next(b, &index, &mesh, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);  // nothing added
  EXPECT_EQ(index, -1);
  EXPECT_EQ(mesh, nullptr);
  EXPECT_NE(std::string(silk_last_error()).find("no input"), std::string::npos) << silk_last_error();
  EXPECT_EQ(silk_batch_next(nullptr, &index, &mesh, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(silk_batch_add(b, nullptr, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
  silk_generate_input in = Input(0);
  in.points = points_.data();  // both mesh and points: that input's error
  in.point_rows = 1;
  silk_generate_params p = Params(1);
  p.candidates = 65;  // refused when the input starts: its result
  ASSERT_EQ(silk_batch_add(b, &in, &p, &index), SILK_OK);
  in = Input(0);
  ASSERT_EQ(silk_batch_add(b, &in, &p, &index), SILK_OK);
  std::map<int32_t, Output> got = PullAll(b);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].status, SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(got[0].error.find("exactly one of mesh, points"), std::string::npos) << got[0].error;
  EXPECT_EQ(got[1].status, SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(got[1].error.find("candidates 65"), std::string::npos) << got[1].error;
  EXPECT_EQ(silk_batch_counts(nullptr, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(silk_batch_close(nullptr), SILK_ERR_INVALID_ARGUMENT);
  silk_batch_cancel(nullptr);
  silk_batch_destroy(nullptr);
  silk_batch_destroy(b);
}

}  // namespace
