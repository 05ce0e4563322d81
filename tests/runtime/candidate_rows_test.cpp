// SPDX-License-Identifier: MIT
// Rows (issue 34): many sequences per decoder call must give each sequence exactly what it gets
// alone. RowsDecoder's per-row logits and caches against DecoderRunner fed the same chunks (bit for
// bit with the ai.silk kernels of a contract v4 folder, and with a batch-1 folder run row by row);
// CandidateRows' candidates against plain Generator runs with their seeds; GenerationSession with
// rows against rows 1 (the same choice, scores and ids), stepped by ids and layers, and cancelled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "runtime/candidate_rows.h"
#include "runtime/candidates.h"
#include "runtime/decoder_runner.h"
#include "runtime/generation_session.h"
#include "runtime/rows_decoder.h"
#include "runtime_test_util.h"
#include "session_run.h"

namespace silk {
namespace {

struct Variant {
  const char* folder;  // under tests/models
  std::optional<DecoderPrecision> decoder;
  KvPrecision kv;
  bool rows_contract;
};

std::string Name(const Variant& v) {
  std::string folder = v.folder;
  for (char& c : folder)
    if (c == '-') c = '_';
  return folder + "_" + (v.decoder ? DecoderPrecisionName(*v.decoder) : "default") + "_" + KvPrecisionName(v.kv);
}

std::unique_ptr<Model> Load(const Variant& v) {
  ModelLoadOptions o;
  o.threads = 1;
  o.decoder = v.decoder;
  o.kv = v.kv;
  auto m = Model::Load(testing::SourcePath(std::string("tests/models/") + v.folder), o);
  EXPECT_TRUE(m.ok()) << m.status().ToString();
  return m.ok() ? std::move(*m) : nullptr;
}

// The v4 folder's INT4 decoder with its fp16 and int8 caches (ai.silk kernels), and the batch-1
// tiny model (fp32 cache: onnxruntime's own attention), which runs its rows one after another.
const Variant kVariants[] = {
    {"tiny-rows", DecoderPrecision::kInt4, KvPrecision::kFp16, true},
    {"tiny-rows", DecoderPrecision::kInt4, KvPrecision::kInt8, true},
    {"tiny-rows", DecoderPrecision::kFp32, KvPrecision::kFp16, true},
    {"tiny", std::nullopt, KvPrecision::kFp32, false},
};

class RowsTest : public ::testing::TestWithParam<Variant> {
 protected:
  void SetUp() override {
    model_ = Load(GetParam());
    ASSERT_TRUE(model_);
    ASSERT_EQ(model_->impl().rows_contract, GetParam().rows_contract);
    points_ = testing::SamplePoints(*model_);
    ASSERT_FALSE(points_.empty());
  }
  std::unique_ptr<Model> model_;
  std::vector<float> points_;
};

// Each row's feeds: chunks of ids (BOS first); row 2 takes a run longer than one decoder chunk.
std::vector<std::vector<std::vector<int32_t>>> Feeds() {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int32_t> id(0, 10266);
  auto run = [&](int n) {
    std::vector<int32_t> v(static_cast<size_t>(n));
    for (int32_t& x : v) x = id(rng);
    return v;
  };
  std::vector<std::vector<std::vector<int32_t>>> rows(3);
  rows[0] = {{10269}, run(1), run(4), run(1), run(1), run(2)};
  rows[1] = {{10269}, run(3), run(1), run(1)};
  rows[2] = {{10269}, run(300), run(1), run(2), run(1), run(1)};
  for (auto& r : rows)
    for (size_t i = 1; i < r.size(); ++i) r[i].insert(r[i].begin(), 0);  // "the last id" sits in each feed
  return rows;
}

TEST_P(RowsTest, EachRowOfAFeedIsTheRowAlone) {
  const Model::Impl& m = model_->impl();
  auto cross = RunEncoder(m, points_.data(), static_cast<int64_t>(points_.size() / 6));
  ASSERT_TRUE(cross.ok());
  const auto feeds = Feeds();
  const int64_t V = model_->config().model_vocab_size;
  RowsKvCache rows_cache;
  ASSERT_TRUE(rows_cache.Reserve(3, 1023, ModelKvShape(m), /*first=*/4).ok());  // grows while fed
  RowsDecoder rows(m, &rows_cache);
  rows.SetSources(1);
  rows.SetSource(0, cross->GetTensorMutableData<void>());
  std::vector<KvCache> alone_cache(3);
  std::vector<std::unique_ptr<DecoderRunner>> alone;
  for (auto& c : alone_cache) {
    ASSERT_TRUE(c.Reserve(1023, ModelKvShape(m)).ok());
    alone.push_back(std::make_unique<DecoderRunner>(m, &c, cross->GetTensorMutableData<void>()));
  }
  for (size_t step = 0; step < 6; ++step) {
    std::vector<RowFeed> call;
    for (int32_t r = 0; r < 3; ++r) {
      if (step >= feeds[r].size()) continue;
      const auto& ids = feeds[static_cast<size_t>(r)][step];
      call.push_back(RowFeed{r, ids.data(), static_cast<int64_t>(ids.size()), 0});
      ASSERT_TRUE(alone[static_cast<size_t>(r)]->Feed(ids.data(), static_cast<int64_t>(ids.size())).ok());
    }
    const Status s = rows.Feed(call);
    ASSERT_TRUE(s.ok()) << s.ToString();
    for (const RowFeed& f : call) {
      const float* a = alone[static_cast<size_t>(f.slot)]->last_logits();
      ASSERT_EQ(0, std::memcmp(a, rows.logits(f.slot), static_cast<size_t>(V) * sizeof(float)))
          << "row " << f.slot << " feed " << step << " differs from the row alone";
    }
  }
  for (int32_t r = 0; r < 3; ++r) {
    const KvCache& c = alone_cache[static_cast<size_t>(r)];
    ASSERT_EQ(rows_cache.length(r), c.length());
    std::vector<float> a(static_cast<size_t>(c.length() * c.shape().position_values())), b(a.size());
    c.CopyTimeMajor(a.data());
    rows_cache.CopyTimeMajor(r, b.data());
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float))) << "row " << r << "'s cache";
  }
  EXPECT_GE(rows_cache.capacity(), 301);  // grew from 4
}

// What CandidateRows' feeds rely on (a forced run cut over several calls so no row is padded): with
// the ai.silk kernels a position's logits and cache are the same however its row's ids were cut
// into feeds. onnxruntime's GroupQueryAttention (the batch-1 fp32 cache) is not: its rows are
// fed whole, one after another.
TEST_P(RowsTest, APositionDoesNotDependOnHowItsRowWasCut) {
  if (!GetParam().rows_contract) GTEST_SKIP() << "batch-1 decoder: rows are fed whole";
  const Model::Impl& m = model_->impl();
  auto cross = RunEncoder(m, points_.data(), static_cast<int64_t>(points_.size() / 6));
  ASSERT_TRUE(cross.ok());
  std::mt19937 rng(5);
  std::vector<int32_t> ids(40);
  for (int32_t& x : ids) x = std::uniform_int_distribution<int32_t>(0, 10266)(rng);
  ids[0] = 10269;
  const std::vector<std::vector<int64_t>> cuts = {{40}, {1, 39}, {7, 1, 1, 31}, std::vector<int64_t>(40, 1)};
  const int64_t V = model_->config().model_vocab_size;
  std::vector<std::vector<float>> logits, caches;
  for (const auto& cut : cuts) {
    KvCache cache;
    ASSERT_TRUE(cache.Reserve(1023, ModelKvShape(m)).ok());
    DecoderRunner runner(m, &cache, cross->GetTensorMutableData<void>());
    int64_t at = 0;
    for (const int64_t n : cut) {
      ASSERT_TRUE(runner.Feed(ids.data() + at, n).ok());
      at += n;
    }
    logits.emplace_back(runner.last_logits(), runner.last_logits() + V);
    caches.emplace_back(static_cast<size_t>(cache.length() * cache.shape().position_values()));
    cache.CopyTimeMajor(caches.back().data());
  }
  for (size_t c = 1; c < cuts.size(); ++c) {
    EXPECT_EQ(0, std::memcmp(logits[0].data(), logits[c].data(), logits[0].size() * sizeof(float))) << "cut " << c;
    ASSERT_EQ(caches[0].size(), caches[c].size());
    EXPECT_EQ(0, std::memcmp(caches[0].data(), caches[c].data(), caches[0].size() * sizeof(float))) << "cut " << c;
  }
}

GenerateOptions Options(double temperature, int32_t candidates, int32_t rows) {
  GenerateOptions o;
  o.sampling.temperature = temperature;
  o.sampling.top_k = 50;
  o.sampling.seed = 7;
  o.max_tokens = 200;
  o.surface_tolerance = 3;
  o.candidates = candidates;
  o.rows = rows;
  return o;
}

TEST_P(RowsTest, CandidatesAreTheirRunsAlone) {
  for (const double temperature : {0.0, 0.9}) {
    const GenerateOptions o = Options(temperature, 5, 3);
    CandidateRows rows(*model_);
    ASSERT_TRUE(rows.Start(points_, o, 3, nullptr, {}).ok());
    std::map<int32_t, GenerateResult> got;
    while (!rows.done()) {
      const Status s = rows.Advance(1 << 20, false, {});
      ASSERT_TRUE(s.ok()) << s.ToString();
      for (auto& [i, r] : rows.TakeEnded()) got[i] = std::move(r);
    }
    ASSERT_EQ(got.size(), 5u);
    int64_t calls_alone = 0, fed = 0;
    for (const auto& [i, r] : got) {
      calls_alone += r.stats.model_calls;
      fed += r.stats.fed_positions;
    }
    // Contract v4: one decoder run serves every row waiting, and no row is padded (each feeds as
    // many ids as the row with the fewest pending); batch 1: one run per row and chunk.
    if (GetParam().rows_contract) {
      EXPECT_LT(rows.decoder_calls() * 2, calls_alone);
      EXPECT_EQ(rows.decoder_positions(), fed) << "positions computed for padding";
    } else {
      EXPECT_EQ(rows.decoder_calls(), calls_alone);
    }
    Generator alone(*model_);
    for (int32_t i = 0; i < 5; ++i) {
      GenerateOptions one = o;
      one.sampling.seed = CandidateSeed(o.sampling.seed, i);
      auto run = alone.Run(points_, one);
      ASSERT_TRUE(run.ok()) << run.status().ToString();
      EXPECT_EQ(got[i].tokens, run->tokens) << "candidate " << i << " at temperature " << temperature;
      EXPECT_EQ(got[i].mesh.faces, run->mesh.faces);
      EXPECT_EQ(got[i].stats.stop_reason, run->stats.stop_reason);
      // A row's forced run may be cut over several calls (contract v4): never fewer calls than alone.
      if (GetParam().rows_contract)
        EXPECT_GE(got[i].stats.model_calls, run->stats.model_calls);
      else
        EXPECT_EQ(got[i].stats.model_calls, run->stats.model_calls);
      EXPECT_EQ(got[i].stats.fed_positions, run->stats.fed_positions);
      EXPECT_GT(run->tokens.size(), 14u);
    }
    if (temperature > 0) {
      EXPECT_NE(got[0].tokens, got[1].tokens);  // the seeds differ
    }
  }
}

GenerationRequest Request(int32_t candidates, int32_t rows) {
  GenerationRequest r;
  r.seed = 3;
  r.temperature = 0.9;
  r.top_k = 50;
  r.max_tokens = 160;
  r.candidates = candidates;
  r.rows = rows;
  r.surface_tolerance = 2;
  return r;
}

SessionResult RunSession(GenerationSession* s, const GenerationRequest& r, int32_t max_ids, AdvanceUntil until) {
  return testing::RunSession(s, r, testing::SampleMeshInput(), max_ids, until);
}

TEST_P(RowsTest, SessionWithRowsChoosesAsOneAfterAnother) {
  GenerationSession session(*model_);
  const SessionResult one = RunSession(&session, Request(6, 1), 1 << 30, AdvanceUntil::kIds);
  EXPECT_EQ(one.generation.stats.rows, 1);
  const SessionResult four = RunSession(&session, Request(6, 4), 1 << 30, AdvanceUntil::kIds);
  // A batch-1 folder runs its candidates one after another whatever rows asks.
  EXPECT_EQ(four.generation.stats.rows, GetParam().rows_contract ? 4 : 1);
  testing::ExpectSameChoice(one, four, "rows 4");
  // Stepped by a few ids (logits kept across calls) and by layers.
  testing::ExpectSameChoice(one, RunSession(&session, Request(6, 4), 3, AdvanceUntil::kIds), "rows 4, 3 ids a call");
  testing::ExpectSameChoice(one, RunSession(&session, Request(6, 8), 50, AdvanceUntil::kLayer),
                            "rows 8 (6 used), by layer");
}

TEST_P(RowsTest, ACancelledSessionWithRowsFinishesWithTheCandidatesStarted) {
  GenerationSession session(*model_);
  int reports = 0;
  GenerateCallbacks cb;
  cb.progress = [&](const GenerateProgress&) { ++reports; };
  cb.cancel = [&] { return reports >= 120; };
  ASSERT_TRUE(session.Start(Request(6, 3), testing::SampleMeshInput(), cb).ok());
  Status st;
  while (!session.done() && st.ok()) st = session.Advance(1 << 20);
  EXPECT_EQ(st.code(), StatusCode::kCancelled);
  EXPECT_TRUE(session.done());
  auto out = session.Finish();
  ASSERT_TRUE(out.ok()) << out.status().ToString();
  EXPECT_EQ(out->generation.stats.stop_reason, StopReason::kCancelled);
  // The three rows started (one after another on a batch-1 folder: the first, cancelled at id 120).
  EXPECT_EQ(out->generation.stats.candidates.size(), GetParam().rows_contract ? 3u : 1u);
}

// The INT8 decoder (onnxruntime's DynamicQuantizeLinear: one activation scale for every row and
// position of a call) is contract v4 but its rows are not each their own: fed together, a row's
// logits move with the others'. So best of N runs its candidates one row at a time (RowsTogether),
// with the same choice as rows 1 and the report saying 1 row.
TEST(RowsInt8, AnInt8DecoderRunsBestOfNOneRowAtATime) {
  const auto model = Load({"tiny-rows", DecoderPrecision::kInt8, KvPrecision::kFp16, true});
  ASSERT_TRUE(model);
  const Model::Impl& m = model->impl();
  ASSERT_TRUE(m.rows_contract);
  EXPECT_FALSE(m.rows_together);
  const std::vector<float> points = testing::SamplePoints(*model);
  auto cross = RunEncoder(m, points.data(), static_cast<int64_t>(points.size() / 6));
  ASSERT_TRUE(cross.ok());
  RowsKvCache rows_cache;
  ASSERT_TRUE(rows_cache.Reserve(2, 1023, ModelKvShape(m)).ok());
  RowsDecoder rows(m, &rows_cache);
  rows.SetSources(1);
  rows.SetSource(0, cross->GetTensorMutableData<void>());
  const std::vector<int32_t> a = {10269, 4000, 12, 900}, b = {10269, 7, 10000, 3};
  ASSERT_TRUE(rows.Feed({RowFeed{0, a.data(), 4, 0}, RowFeed{1, b.data(), 4, 0}}).ok());
  KvCache alone_cache;
  ASSERT_TRUE(alone_cache.Reserve(1023, ModelKvShape(m)).ok());
  DecoderRunner alone(m, &alone_cache, cross->GetTensorMutableData<void>());
  ASSERT_TRUE(alone.Feed(a.data(), 4).ok());
  const size_t bytes = static_cast<size_t>(model->config().model_vocab_size) * sizeof(float);
  EXPECT_NE(0, std::memcmp(alone.last_logits(), rows.logits(0), bytes))
      << "INT8 rows are their own now: run them together";

  GenerationSession session(*model);
  const SessionResult one = RunSession(&session, Request(6, 1), 1 << 30, AdvanceUntil::kIds);
  const SessionResult four = RunSession(&session, Request(6, 4), 1 << 30, AdvanceUntil::kIds);
  EXPECT_EQ(four.generation.stats.rows, 1);
  testing::ExpectSameChoice(one, four, "INT8, rows 4");
}

// The step-wise view of every candidate: at most `rows` running at once, the best so far marked
// among the scored, each one's preview its completed layers while it runs and its mesh once built.
TEST_P(RowsTest, EveryCandidateIsShownWhileTheRowsRun) {
  GenerationSession session(*model_);
  ASSERT_TRUE(session.Start(Request(5, 2), testing::SampleMeshInput()).ok());
  int32_t most_running = 0, steps = 0;
  std::vector<int64_t> faces_seen(5, 0);
  while (!session.done()) {
    ASSERT_TRUE(session.Advance(40).ok());
    ++steps;
    const std::vector<CandidateView> views = session.Candidates();
    ASSERT_EQ(views.size(), 5u);
    int32_t running = 0, best = 0, scored = 0;
    for (const CandidateView& v : views) {
      running += v.state == CandidateView::State::kRunning;
      scored += v.state == CandidateView::State::kScored;
      best += v.best;
      auto p = session.PreviewCandidate(v.index);
      ASSERT_TRUE(p.ok()) << p.status().ToString();
      if (v.state == CandidateView::State::kWaiting) {
        EXPECT_TRUE(p->grid.faces.empty());
      }
      if (v.faces >= 0) {
        EXPECT_EQ(static_cast<int32_t>(p->grid.faces.size()), v.faces);
      }
      if (v.state == CandidateView::State::kRunning) {
        EXPECT_GE(static_cast<int64_t>(p->grid.faces.size()), faces_seen[static_cast<size_t>(v.index)]);  // grows
      }
      faces_seen[static_cast<size_t>(v.index)] = static_cast<int64_t>(p->grid.faces.size());
    }
    EXPECT_LE(running, 2);
    EXPECT_EQ(best, scored > 0 ? 1 : 0);
    most_running = std::max(most_running, running);
  }
  EXPECT_EQ(most_running, GetParam().rows_contract ? 2 : 1);
  EXPECT_GT(steps, 3);
  EXPECT_FALSE(session.PreviewCandidate(5).ok());
  int32_t marked = -1;
  for (const CandidateView& v : session.Candidates())
    if (v.best) marked = v.index;
  auto out = session.Finish();
  ASSERT_TRUE(out.ok());
  // Rows score each candidate as it ends; one after another, the last is scored by Finish.
  const int32_t chosen = out->generation.stats.chosen_candidate;
  if (GetParam().rows_contract)
    EXPECT_EQ(chosen, marked);
  else
    EXPECT_TRUE(chosen == marked || chosen == 4) << chosen << " " << marked;
}

INSTANTIATE_TEST_SUITE_P(Models, RowsTest, ::testing::ValuesIn(kVariants),
                         [](const auto& info) { return Name(info.param); });

// Issue 34's exactness on inputs ("Slow": not in the sanitizer run): the 14 golden meshes and 20 dev meshes, each
// candidate of best of 4 on 4 rows (greedy and sampled) against its plain run, with the ai.silk kernels (INT4 decoder,
// fp16 and int8 caches of the contract v4 folder).
class SlowRowsCorpusTest : public ::testing::TestWithParam<KvPrecision> {};

// The golden meshes (all 14) and every 8th of the 160 dev meshes, sorted.
std::vector<std::string> CorpusMeshes() {
  auto objs = [](const std::string& dir) {
    std::vector<std::string> v;
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".obj") v.push_back(e.path().string());
    std::sort(v.begin(), v.end());
    return v;
  };
  std::vector<std::string> out = objs(testing::SharedPath("spec/golden"));
  const std::vector<std::string> dev = objs(testing::SharedPath("corpus/dev"));
  for (size_t i = 0; i < dev.size(); i += 8) out.push_back(dev[i]);
  return out;
}

TEST_P(SlowRowsCorpusTest, EveryCandidateOnTheGoldenAndDevMeshesIsItsRunAlone) {
  auto model = Load(Variant{"tiny-rows", DecoderPrecision::kInt4, GetParam(), true});
  ASSERT_TRUE(model);
  const std::vector<std::string> meshes = CorpusMeshes();
  ASSERT_EQ(meshes.size(), 34u);  // 14 + 20
  Generator alone(*model);
  CandidateRows rows(*model);
  int64_t compared = 0;
  for (const std::string& path : meshes) {
    GenerationInput in;
    auto mesh = ReadMeshFile(path);
    ASSERT_TRUE(mesh.ok()) << path;
    in.mesh = std::move(*mesh);
    auto pts = PrepareModelPoints(in, ModelPreprocessing(model->config()), 5);
    ASSERT_TRUE(pts.ok()) << path << ": " << pts.status().ToString();
    for (const double temperature : {0.0, 1.0}) {
      GenerateOptions o = Options(temperature, 4, 4);
      o.max_tokens = 120;
      ASSERT_TRUE(rows.Start(pts->rows, o, 4, nullptr, {}).ok());
      std::map<int32_t, std::vector<int32_t>> got;
      while (!rows.done()) {
        ASSERT_TRUE(rows.Advance(1 << 20, false, {}).ok());
        for (auto& [i, r] : rows.TakeEnded()) got[i] = r.tokens;
      }
      for (int32_t i = 0; i < 4; ++i) {
        GenerateOptions one = o;
        one.sampling.seed = CandidateSeed(o.sampling.seed, i);
        auto run = alone.Run(pts->rows, one);
        ASSERT_TRUE(run.ok());
        EXPECT_EQ(got[i], run->tokens) << path << " candidate " << i << " temperature " << temperature;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, static_cast<int64_t>(meshes.size()) * 8);
}

INSTANTIATE_TEST_SUITE_P(Caches, SlowRowsCorpusTest, ::testing::Values(KvPrecision::kFp16, KvPrecision::kInt8),
                         [](const auto& info) { return std::string(KvPrecisionName(info.param)); });

}  // namespace
}  // namespace silk
