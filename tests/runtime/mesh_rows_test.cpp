// SPDX-License-Identifier: MIT
// MeshRows (issue 34, many meshes as rows): each input of a batch decoded together with others must
// get exactly its GenerationSession run alone (ids, triangles, chosen candidate, every candidate's
// score), at parallel 2 and 4; a broken input fails alone; a cancel ends the meshes in flight and
// the queued ones unstarted. A folder before contract v4 runs the same batch one after another.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "runtime/generation_session.h"
#include "runtime/mesh_rows.h"
#include "runtime_test_util.h"
#include "session_run.h"

namespace silk {
namespace {

struct Case {
  std::string mesh;  // samples/torus_knot.obj, else under the shared corpus/dev
  uint64_t seed;
  int32_t candidates, rows;
  double temperature;
};

// Different point sets, seeds and candidate counts (one with candidates 1, one with rows 1: its
// candidates one after another inside the batch).
const Case kCases[] = {
    {"torus_knot.obj", 3, 3, 2, 0.9},
    {"props__shield__hex_01.obj", 5, 1, 8, 0.9},
    {"torus_knot.obj", 9, 4, 4, 0.0},
    {"gaia__wrld_fol_bush_generic_1.obj", 11, 2, 1, 0.9},
    {"props__shield__round_b_f.obj", 4, 5, 8, 0.9},
};

GenerationInput InputOf(const Case& c) {
  GenerationInput in;
  in.name = c.mesh;
  auto m = ReadMeshFile(c.mesh == "torus_knot.obj" ? testing::SourcePath("samples/" + c.mesh)
                                                   : testing::SharedPath("corpus/dev/" + c.mesh));
  EXPECT_TRUE(m.ok()) << c.mesh;
  if (m.ok()) in.mesh = std::move(*m);
  return in;
}

GenerationInput BrokenInput() {
  GenerationInput in = testing::SampleMeshInput();
  in.name = "broken";
  in.mesh.positions[0][1] = std::numeric_limits<double>::quiet_NaN();
  return in;
}

GenerationRequest RequestOf(const Case& c) {
  GenerationRequest r;
  r.seed = c.seed;
  r.temperature = c.temperature;
  r.top_k = 50;
  r.max_tokens = 160;
  r.candidates = c.candidates;
  r.rows = c.rows;
  r.surface_tolerance = 2;
  return r;
}

struct Variant {
  const char* folder;
  std::optional<DecoderPrecision> decoder;
  KvPrecision kv;
};

class MeshRowsTest : public ::testing::TestWithParam<Variant> {
 protected:
  void SetUp() override {
    ModelLoadOptions o;
    o.threads = 1;
    o.decoder = GetParam().decoder;
    o.kv = GetParam().kv;
    auto m = Model::Load(testing::SourcePath(std::string("tests/models/") + GetParam().folder), o);
    ASSERT_TRUE(m.ok()) << m.status().ToString();
    model_ = std::move(*m);
    GenerationSession session(*model_);
    for (const Case& c : kCases) alone_.push_back(testing::RunSession(&session, RequestOf(c), InputOf(c)));
  }
  // Runs every case (a broken input at `broken`, if >= 0) through MeshRows; the results by index,
  // the order the inputs ended and the most inputs seen progressing between two ends.
  std::map<int32_t, StatusOr<SessionResult>> RunBatch(int32_t parallel, int32_t broken, std::vector<int32_t>* order,
                                                      int32_t* interleaved) {
    MeshRows batch(*model_);
    std::vector<int32_t> seen;
    MeshRowsCallbacks cb;
    cb.progress = [&](int32_t index, const GenerateProgress&) {
      if (std::find(seen.begin(), seen.end(), index) == seen.end()) seen.push_back(index);
    };
    EXPECT_TRUE(batch.Open(parallel, 4, cb).ok());
    int32_t index = 0;
    for (const Case& c : kCases) {
      if (index == broken) EXPECT_EQ(batch.Add(RequestOf(c), BrokenInput()), index++);
      EXPECT_EQ(batch.Add(RequestOf(c), InputOf(c)), index++);
    }
    std::map<int32_t, StatusOr<SessionResult>> out;
    *interleaved = 0;
    while (!batch.idle()) {
      EXPECT_LE(batch.in_flight(), parallel);
      auto ended = batch.Next();
      EXPECT_TRUE(ended.ok()) << ended.status().ToString();
      if (!ended.ok()) break;
      *interleaved = std::max(*interleaved, static_cast<int32_t>(seen.size()));
      seen.clear();
      order->push_back(ended->index);
      out.emplace(ended->index, std::move(ended->result));
    }
    EXPECT_EQ(batch.Next().status().code(), StatusCode::kInvalidArgument);  // nothing left
    return out;
  }
  std::unique_ptr<Model> model_;
  std::vector<SessionResult> alone_;
};

TEST_P(MeshRowsTest, EachInputIsItsRunAlone) {
  const bool rows = model_->impl().rows_contract;
  for (const int32_t parallel : {2, 4}) {
    std::vector<int32_t> order;
    int32_t interleaved = 0;
    auto got = RunBatch(parallel, -1, &order, &interleaved);
    ASSERT_EQ(got.size(), std::size(kCases));
    for (size_t i = 0; i < std::size(kCases); ++i) {
      const std::string what = "parallel " + std::to_string(parallel) + " input " + std::to_string(i);
      auto& r = got.at(static_cast<int32_t>(i));
      ASSERT_TRUE(r.ok()) << what << ": " << r.status().ToString();
      testing::ExpectSameChoice(*r, alone_[i], what);
      const GenerationStats &a = r->generation.stats, &b = alone_[i].generation.stats;
      EXPECT_EQ(a.candidates.size(), static_cast<size_t>(kCases[i].candidates)) << what;
      EXPECT_EQ(a.stop_reason, b.stop_reason) << what;
      EXPECT_EQ(a.faces, b.faces) << what;
      EXPECT_EQ(a.components, b.components) << what;
      EXPECT_EQ(a.watertight, b.watertight) << what;
      EXPECT_EQ(a.rows, b.rows) << what;
      EXPECT_EQ(r->output.positions, alone_[i].output.positions) << what;
    }
    // Rows: several meshes progress between two ends (one after another: one, in input order).
    if (rows) {
      EXPECT_GE(interleaved, 2) << "parallel " << parallel;
    } else {
      EXPECT_EQ(interleaved, 1);
      EXPECT_TRUE(std::is_sorted(order.begin(), order.end()));
    }
  }
}

TEST_P(MeshRowsTest, ABrokenInputFailsAloneAndTheOthersFinish) {
  std::vector<int32_t> order;
  int32_t interleaved = 0;
  auto got = RunBatch(3, 2, &order, &interleaved);
  ASSERT_EQ(got.size(), std::size(kCases) + 1);
  ASSERT_FALSE(got.at(2).ok());
  EXPECT_EQ(got.at(2).status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(got.at(2).status().message().find("broken: "), std::string::npos) << got.at(2).status().ToString();
  for (size_t i = 0; i < std::size(kCases); ++i) {
    const int32_t index = static_cast<int32_t>(i < 2 ? i : i + 1);
    ASSERT_TRUE(got.at(index).ok()) << got.at(index).status().ToString();
    testing::ExpectSameChoice(*got.at(index), alone_[i], "input " + std::to_string(index));
  }
}

TEST_P(MeshRowsTest, ACancelEndsTheInputsInFlightAndTheQueuedUnstarted) {
  MeshRows batch(*model_);
  int reports = 0;
  MeshRowsCallbacks cb;
  cb.progress = [&](int32_t, const GenerateProgress&) { ++reports; };
  cb.cancel = [&] { return reports >= 150; };
  ASSERT_TRUE(batch.Open(2, 4, cb).ok());
  for (const Case& c : kCases) batch.Add(RequestOf(c), InputOf(c));
  int32_t cancelled = 0, finished = 0, unstarted = 0;
  std::vector<int32_t> indexes;
  while (!batch.idle()) {
    auto ended = batch.Next();
    ASSERT_TRUE(ended.ok()) << ended.status().ToString();
    indexes.push_back(ended->index);
    if (ended->result.ok()) {
      ++finished;
      testing::ExpectSameChoice(*ended->result, alone_[static_cast<size_t>(ended->index)], "before the cancel");
    } else {
      EXPECT_EQ(ended->result.status().code(), StatusCode::kCancelled);
      const bool before = ended->result.status().message().find("before it started") != std::string::npos;
      (before ? unstarted : cancelled) += 1;
    }
  }
  std::sort(indexes.begin(), indexes.end());
  EXPECT_EQ(indexes, (std::vector<int32_t>{0, 1, 2, 3, 4}));  // each comes back once
  EXPECT_GE(cancelled, 1);
  EXPECT_LE(cancelled, 2);  // in flight
  EXPECT_GE(unstarted, 1);  // queued, never started
  // The batch opens again after a cancel and runs.
  reports = -1000000;
  ASSERT_TRUE(batch.Open(2, 4, cb).ok());
  batch.Add(RequestOf(kCases[1]), InputOf(kCases[1]));
  auto again = batch.Next();
  ASSERT_TRUE(again.ok() && again->result.ok());
  testing::ExpectSameChoice(*again->result, alone_[1], "after the cancel");
}

TEST_P(MeshRowsTest, MisuseIsRefused) {
  MeshRows batch(*model_);
  EXPECT_EQ(batch.Next().status().code(), StatusCode::kInvalidArgument);  // nothing added
  EXPECT_EQ(batch.Open(0, 4).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(batch.Open(17, 4).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(batch.Open(2, 65).code(), StatusCode::kInvalidArgument);
  ASSERT_TRUE(batch.Open(2, 4).ok());
  GenerationRequest bad = RequestOf(kCases[0]);
  bad.candidates = 0;  // refused when resolved: that input's result
  EXPECT_EQ(batch.Add(bad, InputOf(kCases[0])), 0);
  auto ended = batch.Next();
  ASSERT_TRUE(ended.ok());
  EXPECT_EQ(ended->result.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(ended->result.status().message().find("candidates"), std::string::npos);
  EXPECT_TRUE(batch.idle());
}

INSTANTIATE_TEST_SUITE_P(Models, MeshRowsTest,
                         ::testing::Values(Variant{"tiny-rows", DecoderPrecision::kInt4, KvPrecision::kInt8},
                                           Variant{"tiny", std::nullopt, KvPrecision::kFp32}),
                         [](const auto& info) { return std::string(info.param.folder[4] == '-' ? "rows" : "batch1"); });

}  // namespace
}  // namespace silk
