// SPDX-License-Identifier: MIT
// The C API as a plug-in author uses it (silk.h only): destroy order, impossible limits,
// concurrent misuse, thread bounds, cancel/progress contract, size queries, enum checks,
// the log callback, parallel == sequential, and a soak that keeps the RSS flat.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "silk/silk.h"
#include "support/capi_generate.h"
#include "silk/silk.hpp"
#include "support/capi_counts.h"
#include "support/test_paths.h"

namespace {

namespace fs = std::filesystem;

std::string TinyModel() { return silk::testing::SourcePath("tests/models/tiny"); }

class CapiGeneration : public silk::testing::TinyModelTest {
 protected:
  // Ids of one generation on `g` (empty on failure).
  std::vector<int32_t> Ids(silk_generator* g, uint64_t seed, silk_status* status = nullptr) {
    silk_generate_params p = Params(seed);
    silk_mesh* out = nullptr;
    silk_tokens* t = nullptr;
    const silk_status s = silk::testing::GenerateFromMesh(g, mesh_, &p, &out, &t, nullptr);
    if (status) *status = s;
    std::vector<int32_t> ids(t ? silk::testing::TokenCount(t) : 0);
    if (!ids.empty()) silk_tokens_copy(t, ids.data(), ids.size(), nullptr);
    silk_tokens_destroy(t);
    silk_mesh_destroy(out);
    return ids;
  }
};

TEST_F(CapiGeneration, GeneratorKeepsItsModelAlive) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  const std::vector<int32_t> before = Ids(g, 5);
  silk_model_destroy(model_);  // garbage collectors and unloading destroy in any order
  model_ = nullptr;
  silk_status s = SILK_ERR_INTERNAL;
  const std::vector<int32_t> after = Ids(g, 5, &s);
  EXPECT_EQ(s, SILK_OK) << silk_last_error();
  EXPECT_EQ(after, before);
  silk_generator_destroy(g);
}

TEST_F(CapiGeneration, MaxTokensBelowTheSmallestMeshIsRefused) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  for (int32_t cap : {1, 2, 13}) {
    silk_generate_params p = Params(1, cap);
    silk_mesh* out = nullptr;
    EXPECT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT) << cap;
    EXPECT_NE(std::string(silk_last_error()).find("max_tokens"), std::string::npos) << silk_last_error();
    EXPECT_EQ(out, nullptr);
  }
  silk_generate_params p = Params(1, 14);
  silk_mesh* out = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  EXPECT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, &st), SILK_OK) << silk_last_error();
  EXPECT_LE(st.tokens, 14);
  silk_mesh_destroy(out);
  silk_generator_destroy(g);
}

// A copy of the tiny model in a temporary folder named after `tag`, its model.json text edited.
fs::path TinyModelCopy(const std::string& tag, const std::function<void(std::string&)>& edit) {
  const fs::path dir = fs::temp_directory_path() / ("silk_" + tag + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* f : {"encoder.onnx", "decoder.onnx"})
    fs::copy_file(fs::path(TinyModel()) / f, dir / f, fs::copy_options::overwrite_existing);
  std::ifstream in(fs::path(TinyModel()) / "model.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  edit(json);
  std::ofstream(dir / "model.json") << json;
  return dir;
}

TEST(CapiModel, MaxSeqLenTooSmallIsRefused) {
  if (!silk_generation_available()) GTEST_SKIP();
  const fs::path dir = TinyModelCopy("small_seq", [](std::string& json) {
    const size_t at = json.find("\"max_seq_len\"");
    ASSERT_NE(at, std::string::npos);
    const size_t colon = json.find(':', at), end = json.find_first_of(",}", colon);
    json.replace(colon + 1, end - colon - 1, " 10");
  });
  silk_model* m = nullptr;
  EXPECT_EQ(silk_model_load(dir.string().c_str(), nullptr, &m), SILK_ERR_PARSE);
  EXPECT_NE(std::string(silk_last_error()).find("max_seq_len 10"), std::string::npos) << silk_last_error();
  EXPECT_EQ(m, nullptr);
  fs::remove_all(dir);
}

TEST_F(CapiGeneration, ConcurrentUseOfOneGeneratorSaysBusy) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  struct Probe {
    silk_generator* g;
    silk_mesh* mesh;
    std::atomic<int> busy{0};
    std::string message;
  } probe{g, mesh_, {0}, {}};
  silk_generate_params p = Params(3);
  p.user_data = &probe;
  p.progress = [](const silk_generate_progress* pr, void* user) {
    auto* b = static_cast<Probe*>(user);
    if (pr->tokens != 5) return;
    std::thread other([b] {  // a second thread uses the generator while this call runs
      silk_generate_params q = silk_generate_default_params();
      silk_mesh* out = nullptr;
      if (silk::testing::GenerateFromMesh(b->g, b->mesh, &q, &out, nullptr, nullptr) == SILK_ERR_BUSY) {
        b->busy = 1;
        b->message = silk_last_error();
      }
      int32_t done = 0;
      if (silk_generator_advance(b->g, 1, SILK_ADVANCE_IDS, &done) == SILK_ERR_BUSY) b->busy += 1;
    });
    other.join();
  };
  silk_mesh* out = nullptr;
  EXPECT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, nullptr), SILK_OK) << silk_last_error();
  EXPECT_EQ(probe.busy.load(), 2);
  EXPECT_NE(probe.message.find("generator busy"), std::string::npos) << probe.message;
  silk_mesh_destroy(out);
  silk_generator_destroy(g);
}

TEST(CapiModel, ThreadsAreBoundedAndOnePoolIsShared) {
  if (!silk_generation_available()) GTEST_SKIP();
  silk_model_params o = silk_model_default_params();
  o.threads = 1000;
  silk_model* m = nullptr;
  EXPECT_EQ(silk_model_load(TinyModel().c_str(), &o, &m), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(silk_last_error()).find("threads 1000"), std::string::npos) << silk_last_error();
  o.threads = 2;
  silk_model *a = nullptr, *b = nullptr;
  ASSERT_EQ(silk_model_load(TinyModel().c_str(), &o, &a), SILK_OK) << silk_last_error();
  o.threads = 1;  // the pool exists already: its size stays
  ASSERT_EQ(silk_model_load(TinyModel().c_str(), &o, &b), SILK_OK) << silk_last_error();
  silk_model_info ia = silk_cpp::Sized<silk_model_info>(), ib = ia;
  ASSERT_EQ(silk_model_get_info(a, &ia), SILK_OK);
  ASSERT_EQ(silk_model_get_info(b, &ib), SILK_OK);
  // The pool was sized by this process's first load (2 here when this test runs alone, as
  // ctest runs it); the second request does not resize it.
  EXPECT_GE(ia.threads, 1);
  EXPECT_EQ(ib.threads, ia.threads);
  silk_model_destroy(a);
  silk_model_destroy(b);
}

// silk_model_params.kv_precision: every precision the tiny model carries loads and is reported;
// a value past the enum is refused naming the field.
TEST(CapiModel, KvPrecisionIsChosenAndReported) {
  if (!silk_generation_available()) GTEST_SKIP();
  for (silk_kv_precision kv : {SILK_KV_FP32, SILK_KV_FP16, SILK_KV_INT8}) {
    silk_model_params o = silk_model_default_params();
    o.kv_precision = kv;
    silk_model* m = nullptr;
    ASSERT_EQ(silk_model_load(TinyModel().c_str(), &o, &m), SILK_OK) << silk_last_error();
    silk_model_info info = silk_cpp::Sized<silk_model_info>();
    ASSERT_EQ(silk_model_get_info(m, &info), SILK_OK);
    EXPECT_EQ(info.kv_precision, kv);
    silk_model_destroy(m);
  }
  silk_model_params o = silk_model_default_params();
  o.kv_precision = SILK_KV_INT8 + 1;
  silk_model* m = nullptr;
  EXPECT_EQ(silk_model_load(TinyModel().c_str(), &o, &m), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(silk_last_error()).find("kv_precision"), std::string::npos) << silk_last_error();
  EXPECT_EQ(m, nullptr);
}

struct CancelProbe {
  int polls = 0, cancel_at = 0, progress_calls = 0;
  silk_generate_progress last{};
};

TEST_F(CapiGeneration, CancelIsPolledBeforeSamplingAndTheEncoder) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  // Poll 1: on the call; 2-4: pre-processing (before normalising, the first surface sample,
  // after sampling); 5: before the encoder; 6: before the first id.
  for (int at : {1, 2, 3, 4, 5, 6}) {
    CancelProbe c;
    c.cancel_at = at;
    silk_generate_params p = Params(2);
    p.user_data = &c;
    p.cancel = [](void* u) -> int32_t {
      auto* c = static_cast<CancelProbe*>(u);
      return ++c->polls >= c->cancel_at ? 1 : 0;
    };
    p.progress = [](const silk_generate_progress*, void* u) { ++static_cast<CancelProbe*>(u)->progress_calls; };
    silk_mesh* out = nullptr;
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    st.tokens = 99;
    EXPECT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, &st), SILK_ERR_CANCELLED) << at;
    EXPECT_EQ(c.polls, at);
    EXPECT_EQ(c.progress_calls, 0);
    EXPECT_EQ(st.tokens, 0);
    EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);
    EXPECT_EQ(out, nullptr);
  }
  silk_generator_destroy(g);
}

// Issue 12: silk_generator_cancel from another thread interrupts an encoder run in progress.
// 2^20 points all go to the encoder (seconds uncancelled with the tiny model on a 2-core VM). The
// params' cancel callback (polled, never stopping here) tells the canceller when the last poll
// before the encoder has passed (a point cloud: the call, two pre-processing steps, the
// encoder's); 100 ms later it cancels. The call must end with the encoder run unfinished
// (seconds_encoder is only set when it completes) and stop reason CANCELLED. No wall-clock
// assertion: the measured latency is printed (docs/runtime.md).
TEST_F(CapiGeneration, CancelFromAnotherThreadInterruptsTheEncoderRun) {
  const size_t n = size_t{1} << 20;
  const std::vector<double> pts = silk::testing::FibonacciSphere(n);
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  silk_generate_params p = Params(3);
  p.point_count = static_cast<int32_t>(n);
  std::atomic<int> polls{0};
  p.user_data = &polls;
  p.cancel = [](void* u) -> int32_t {
    ++*static_cast<std::atomic<int>*>(u);
    return 0;
  };
  std::chrono::steady_clock::time_point cancelled_at;
  std::thread canceller([&] {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);  // never hang
    while (polls.load() < 4 && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    cancelled_at = std::chrono::steady_clock::now();
    silk_generator_cancel(g);
  });
  silk_mesh* out = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  const silk_status s = silk::testing::GenerateFromPoints(g, pts.data(), n, &p, &out, nullptr, &st);
  const auto returned_at = std::chrono::steady_clock::now();
  const std::string message = silk_last_error();
  canceller.join();
  EXPECT_EQ(s, SILK_ERR_CANCELLED) << message;
  EXPECT_EQ(out, nullptr);
  EXPECT_EQ(polls.load(), 4) << "polls before the encoder changed; update the canceller's trigger";
  EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);
  EXPECT_EQ(st.tokens, 0);
  EXPECT_EQ(st.seconds_encoder, 0) << "the encoder ran to its end: the cancel did not interrupt it";
  EXPECT_NE(message.find("encoder"), std::string::npos) << message;
  std::printf("[ cancel ] 2^20 points: returned %.1f ms after silk_generator_cancel (%s)\n",
              std::chrono::duration<double, std::milli>(returned_at - cancelled_at).count(), message.c_str());
  // The generator is usable again afterwards (the terminate flag does not leak into the next run).
  silk_status again = SILK_OK;
  EXPECT_FALSE(Ids(g, 2, &again).empty());
  EXPECT_EQ(again, SILK_OK) << silk_last_error();
  silk_generator_destroy(g);
}

// Issue 35: with a million encoder points, what follows the last id takes seconds: the parts
// turned to the input's normals (a query per face, each up to all points) and the scoring
// (indexing the points, a query per point). silk_generator_cancel from another thread 30 ms and
// 300 ms after the last id must end the call within ~10 ms of work (main at 35a6440: 45-77 s on a
// loaded 2-core VM); the bound asserted is loose (2 s: a shared, loaded or sanitized machine; ASan
// at load 12 measured 0.5 s), the latency is printed.
TEST_F(CapiGeneration, CancelDuringOrientationAndScoringOfAMillionPointsReturnsPromptly) {
  const size_t n = size_t{1} << 20;
  const std::vector<double> pts = silk::testing::FibonacciSphere(n);
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  for (int delay_ms : {30, 300}) {
    silk_generate_params p = Params(3, 40);
    p.point_count = static_cast<int32_t>(n);
    p.candidates = 1;
    std::atomic<bool> last_id{false};
    p.user_data = &last_id;
    p.progress = [](const silk_generate_progress* pr, void* u) {
      if (pr->tokens == pr->max_tokens) static_cast<std::atomic<bool>*>(u)->store(true);
    };
    std::chrono::steady_clock::time_point cancelled_at;
    std::thread canceller([&] {
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);  // never hang
      while (!last_id.load() && std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      cancelled_at = std::chrono::steady_clock::now();
      silk_generator_cancel(g);
    });
    silk_mesh* out = nullptr;
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    const silk_status s = silk::testing::GenerateFromPoints(g, pts.data(), n, &p, &out, nullptr, &st);
    const auto returned_at = std::chrono::steady_clock::now();
    const std::string message = silk_last_error();
    canceller.join();
    ASSERT_TRUE(last_id.load()) << "the generation did not reach its last id: " << message;
    EXPECT_EQ(s, SILK_ERR_CANCELLED) << message;
    EXPECT_EQ(out, nullptr);
    EXPECT_TRUE(message.find("scoring") != std::string::npos || message.find("orientation") != std::string::npos)
        << message;
    EXPECT_EQ(st.candidates, 1);
    const double ms = std::chrono::duration<double, std::milli>(returned_at - cancelled_at).count();
    EXPECT_LT(ms, 2000) << "the cancel waited for the orientation or scoring to end";
    std::printf("[ cancel ] 2^20 points, %d ms after the last id: returned %.1f ms after silk_generator_cancel (%s)\n",
                delay_ms, ms, message.c_str());
  }
  silk_generator_destroy(g);
}

// Issue 35: the params' cancel callback is polled while the last candidate is scored and its
// parts oriented (it was not: a callback that asks to stop after the last id got a mesh, exit OK).
TEST_F(CapiGeneration, CancelCallbackIsPolledDuringOrientationAndScoring) {
  for (int32_t orient : {SILK_ORIENT_TOKENS, SILK_ORIENT_INPUT}) {
    silk_generator* g = nullptr;
    ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
    struct Probe {
      bool last_id = false;
      int polls_after = 0;
    } probe;
    silk_generate_params p = Params(3);
    p.orient = orient;
    p.user_data = &probe;
    p.progress = [](const silk_generate_progress* pr, void* u) {
      if (pr->tokens == pr->max_tokens) static_cast<Probe*>(u)->last_id = true;
    };
    p.cancel = [](void* u) -> int32_t {
      auto* probe = static_cast<Probe*>(u);
      if (probe->last_id) ++probe->polls_after;
      return probe->last_id ? 1 : 0;
    };
    silk_mesh* out = nullptr;
    const silk_status s = silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, nullptr);
    EXPECT_TRUE(probe.last_id);
    EXPECT_EQ(s, SILK_ERR_CANCELLED) << silk_last_error();
    EXPECT_GE(probe.polls_after, 1);
    const char* during = orient == SILK_ORIENT_INPUT ? "orientation" : "scoring";  // orientation comes first
    EXPECT_NE(std::string(silk_last_error()).find(during), std::string::npos) << silk_last_error();
    EXPECT_EQ(out, nullptr);
    silk_mesh_destroy(out);
    silk_generator_destroy(g);
  }
}

TEST_F(CapiGeneration, StatsAfterCancelAndProgressReachesTheEnd) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  CancelProbe c;
  c.cancel_at = 6 + 20;  // 20 ids in (polls before the first id: call, 3 in pre-processing, encoder, id 1)
  silk_generate_params p = Params(2);
  p.user_data = &c;
  p.cancel = [](void* u) -> int32_t {
    auto* c = static_cast<CancelProbe*>(u);
    return ++c->polls >= c->cancel_at ? 1 : 0;
  };
  p.progress = [](const silk_generate_progress* pr, void* u) {
    auto* c = static_cast<CancelProbe*>(u);
    ++c->progress_calls;
    c->last = *pr;
  };
  silk_mesh* out = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  EXPECT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, &st), SILK_ERR_CANCELLED);
  EXPECT_EQ(st.tokens, 20);
  EXPECT_EQ(st.forced_tokens + st.sampled_tokens, 20);
  EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);

  // Uncancelled: the last id gets its progress call, at 100 %.
  CancelProbe d;
  silk_generate_params q = Params(2);
  q.user_data = &d;
  q.progress = p.progress;
  ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &q, &out, nullptr, &st), SILK_OK) << silk_last_error();
  EXPECT_EQ(d.progress_calls, st.tokens);
  EXPECT_EQ(d.last.tokens, st.tokens);
  EXPECT_EQ(d.last.max_tokens, d.last.tokens);
  silk_mesh_destroy(out);
  silk_generator_destroy(g);
}

// The size-query rule of every copy function: tests/capi/capi_rules_test.cpp.

TEST(CapiMisuse, OutOfRangeEnumsAndFlagsAreRejected) {
  silk_mesh* m = nullptr;
  ASSERT_EQ(silk_mesh_load(silk::testing::SourcePath("samples/torus_knot.obj").c_str(), nullptr, &m), SILK_OK);
  silk_encode_params ep = silk_encode_default_params();
  ep.normalize = 2;
  silk_tokens* t = nullptr;
  EXPECT_EQ(silk_mesh_encode(m, &ep, &t, nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(silk_last_error()).find("normalize 2"), std::string::npos) << silk_last_error();
  ASSERT_EQ(silk_mesh_encode(m, nullptr, &t, nullptr), SILK_OK);
  silk_decode_params dp = silk_decode_default_params();
  dp.grid_coordinates = 3;
  silk_mesh* d = nullptr;
  EXPECT_EQ(silk_tokens_decode(t, &dp, &d, nullptr), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(silk_last_error()).find("grid_coordinates 3"), std::string::npos) << silk_last_error();
  silk_save_params sp = silk_save_default_params();
  sp.part_colors = 5;
  EXPECT_EQ(silk_mesh_save(m, "unused.glb", &sp), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(silk_last_error()).find("part_colors 5"), std::string::npos) << silk_last_error();
  silk_tokens_destroy(t);
  if (silk_generation_available()) {
    silk_model_params o = silk_model_default_params();
    o.decoder = 7;
    silk_model* model = nullptr;
    EXPECT_EQ(silk_model_load(TinyModel().c_str(), &o, &model), SILK_ERR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(silk_last_error()).find("decoder 7"), std::string::npos) << silk_last_error();
    ASSERT_EQ(silk_model_load(TinyModel().c_str(), nullptr, &model), SILK_OK) << silk_last_error();
    silk_generator* g = nullptr;
    ASSERT_EQ(silk_generator_create(model, &g), SILK_OK);
    struct Case {
      const char* what;
      void (*set)(silk_generate_params*);
    };
    const Case cases[] = {{"holes", [](silk_generate_params* p) { p->holes = 7; }},
                          // 1.0-1.3's measurement switches: refused, named, never silently ignored
                          {"unconstrained", [](silk_generate_params* p) { p->reserved[0] = 1; }},
                          {"debug_flags", [](silk_generate_params* p) { p->reserved[1] = 2; }},
                          {"report_flags", [](silk_generate_params* p) { p->report_flags = 2; }},
                          {"surface_tolerance -1", [](silk_generate_params* p) { p->surface_tolerance = -1; }},
                          {"surface_tolerance 128", [](silk_generate_params* p) { p->surface_tolerance = 128; }},
                          {"candidates 0", [](silk_generate_params* p) { p->candidates = 0; }},
                          {"candidates 65", [](silk_generate_params* p) { p->candidates = 65; }},
                          {"orient", [](silk_generate_params* p) { p->orient = 2; }},
                          {"face_guidance", [](silk_generate_params* p) { p->face_guidance = 3; }},
                          {"face_tolerance 0.25", [](silk_generate_params* p) { p->face_tolerance = 0.25; }},
                          {"face_tolerance -2", [](silk_generate_params* p) { p->face_tolerance = -2; }}};
    for (const Case& c : cases) {
      silk_generate_params p = silk_generate_default_params();
      c.set(&p);
      silk_mesh* out = nullptr;
      EXPECT_EQ(silk::testing::GenerateFromMesh(g, m, &p, &out, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT) << c.what;
      EXPECT_NE(std::string(silk_last_error()).find(c.what), std::string::npos) << silk_last_error();
    }
    int32_t done = 0;
    EXPECT_EQ(silk_generator_advance(g, 1, 5, &done), SILK_ERR_INVALID_ARGUMENT);
    silk_generator_destroy(g);
    silk_model_destroy(model);
  }
  silk_mesh_destroy(m);
}

// A params edit and the words ("field value") the refusal of it must name.
struct ParamsCase {
  const char* what;
  void (*set)(silk_generate_params*);
};

// Each edit of the default params (max_tokens 60) is refused before any work, naming `what`.
template <size_t N>
void ExpectRefusedByName(silk_generator* g, silk_mesh* m, const ParamsCase (&bad)[N]) {
  for (const ParamsCase& c : bad) {
    silk_generate_params p = silk_generate_default_params();
    p.max_tokens = 60;
    c.set(&p);
    silk_mesh* out = nullptr;
    EXPECT_EQ(silk::testing::GenerateFromMesh(g, m, &p, &out, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT) << c.what;
    EXPECT_NE(std::string(silk_last_error()).find(c.what), std::string::npos) << c.what << ": " << silk_last_error();
    EXPECT_EQ(out, nullptr);
    silk_mesh_destroy(out);
  }
}

// Issue 20, finding 3: SILK_MODEL_VALUE (-1) is the one "the model's value"; any other NaN,
// infinite or negative sampling value, and an out-of-range flag, is refused, naming the field
// and its value (before, NaN and every negative silently became the model's value).
TEST(CapiMisuse, SamplingValuesOtherThanTheModelSentinelAreRefused) {
  if (!silk_generation_available()) GTEST_SKIP();
  silk_mesh* m = nullptr;
  ASSERT_EQ(silk_mesh_load(silk::testing::SourcePath("samples/torus_knot.obj").c_str(), nullptr, &m), SILK_OK);
  silk_model* model = nullptr;
  ASSERT_EQ(silk_model_load(TinyModel().c_str(), nullptr, &model), SILK_OK) << silk_last_error();
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model, &g), SILK_OK);
  const ParamsCase bad[] = {
      {"temperature nan", [](silk_generate_params* p) { p->temperature = std::nan(""); }},
      {"temperature -2", [](silk_generate_params* p) { p->temperature = -2; }},
      {"temperature -0.5", [](silk_generate_params* p) { p->temperature = -0.5; }},
      {"temperature -inf", [](silk_generate_params* p) { p->temperature = -INFINITY; }},
      {"temperature inf", [](silk_generate_params* p) { p->temperature = INFINITY; }},
      {"top_p nan", [](silk_generate_params* p) { p->top_p = std::nan(""); }},
      {"top_p -3", [](silk_generate_params* p) { p->top_p = -3; }},
      {"top_p 1.5", [](silk_generate_params* p) { p->top_p = 1.5; }},
      {"top_p_temperature nan", [](silk_generate_params* p) { p->top_p_temperature = std::nan(""); }},
      {"top_p_temperature -0.25", [](silk_generate_params* p) { p->top_p_temperature = -0.25; }},
      {"top_k -2", [](silk_generate_params* p) { p->top_k = -2; }},
      {"candidates -2", [](silk_generate_params* p) { p->candidates = -2; }},
      {"preprocessing -2", [](silk_generate_params* p) { p->preprocessing = -2; }},
      {"max_tokens -5", [](silk_generate_params* p) { p->max_tokens = -5; }},
      {"max_faces -1", [](silk_generate_params* p) { p->max_faces = -1; }},
      {"point_count -3", [](silk_generate_params* p) { p->point_count = -3; }},
      {"reserved[0] is 2", [](silk_generate_params* p) { p->reserved[0] = 2; }},
      {"raw_points -1", [](silk_generate_params* p) { p->raw_points = -1; }},
      {"holes 3", [](silk_generate_params* p) { p->holes = 3; }},
      {"orient -1", [](silk_generate_params* p) { p->orient = -1; }}};
  ExpectRefusedByName(g, m, bad);
  // The sentinel and the documented ranges' ends still run.
  const ParamsCase good[] = {
      {"sentinel",
       [](silk_generate_params* p) {
         p->temperature = p->top_p = p->top_p_temperature = SILK_MODEL_VALUE;
         p->top_k = p->candidates = p->preprocessing = SILK_MODEL_VALUE;
       }},
      {"zeros", [](silk_generate_params* p) { p->temperature = p->top_p = p->top_p_temperature = 0; }},
      {"top_p 1", [](silk_generate_params* p) { p->top_p = 1; }}};
  for (const ParamsCase& c : good) {
    silk_generate_params p = silk_generate_default_params();
    p.max_tokens = 60;
    c.set(&p);
    silk_mesh* out = nullptr;
    EXPECT_EQ(silk::testing::GenerateFromMesh(g, m, &p, &out, nullptr, nullptr), SILK_OK)
        << c.what << ": " << silk_last_error();
    silk_mesh_destroy(out);
  }
  silk_generate_params d = silk_generate_default_params();
  EXPECT_EQ(d.temperature, SILK_MODEL_VALUE);
  EXPECT_EQ(d.top_k, SILK_MODEL_VALUE);
  EXPECT_EQ(d.top_p, SILK_MODEL_VALUE);
  EXPECT_EQ(d.top_p_temperature, SILK_MODEL_VALUE);
  EXPECT_EQ(d.preprocessing, SILK_MODEL_VALUE);
  EXPECT_EQ(d.candidates, SILK_MODEL_VALUE);
  silk_generator_destroy(g);
  silk_model_destroy(model);
  silk_mesh_destroy(m);
}

// Issue 32: the generation settings' ranges are one table (runtime/sampling/generation_ranges.h):
// past each upper end the generation is refused with a message naming the setting, the value and
// the range, the message silk_param_check gives (silkgen's answer too).
TEST_F(CapiGeneration, ValuesPastTheRangeTableAreRefusedWithTheRange) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  const ParamsCase bad[] = {{"temperature 150", [](silk_generate_params* p) { p->temperature = 150; }},
                            {"top_k 10270", [](silk_generate_params* p) { p->top_k = 10270; }},
                            {"top_p_temperature 101", [](silk_generate_params* p) { p->top_p_temperature = 101; }},
                            {"candidates 65", [](silk_generate_params* p) { p->candidates = 65; }},
                            {"surface_tolerance 128", [](silk_generate_params* p) { p->surface_tolerance = 128; }},
                            {"face_tolerance 65", [](silk_generate_params* p) { p->face_tolerance = 65; }},
                            {"face_tolerance 0.2", [](silk_generate_params* p) { p->face_tolerance = 0.2; }},
                            {"max_tokens 13", [](silk_generate_params* p) { p->max_tokens = 13; }},
                            {"point_count 1048577", [](silk_generate_params* p) { p->point_count = (1 << 20) + 1; }}};
  ExpectRefusedByName(g, mesh_, bad);
  // The generation's message is silk_param_check's (one rule, one text), naming the range.
  silk_generate_params hot = silk_generate_default_params();
  hot.temperature = 150;
  silk_mesh* none = nullptr;
  ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &hot, &none, nullptr, nullptr), SILK_ERR_INVALID_ARGUMENT);
  const std::string generate_message = silk_last_error();
  ASSERT_EQ(silk_param_check("temperature", 150), SILK_ERR_INVALID_ARGUMENT);
  EXPECT_NE(generate_message.find(silk_last_error()), std::string::npos) << generate_message;
  EXPECT_NE(generate_message.find("[0, 100]"), std::string::npos) << generate_message;
  silk_generator_destroy(g);
}

// Issue 20, finding 3: silk_points_prepare refuses an out-of-range flag or kind.
TEST(CapiMisuse, PreparePointsRefusesOutOfRangeFlags) {
  silk_mesh* m = nullptr;
  ASSERT_EQ(silk_mesh_load(silk::testing::SourcePath("samples/torus_knot.obj").c_str(), nullptr, &m), SILK_OK);
  struct Case {
    const char* what;
    void (*set)(silk_preprocess_params*);
  };
  const Case bad[] = {{"round_float16 2", [](silk_preprocess_params* p) { p->round_float16 = 2; }},
                      {"round_float16 -1", [](silk_preprocess_params* p) { p->round_float16 = -1; }},
                      {"kind 2", [](silk_preprocess_params* p) { p->kind = 2; }},
                      {"normalize_bound nan", [](silk_preprocess_params* p) { p->normalize_bound = std::nan(""); }}};
  for (const Case& c : bad) {
    silk_preprocess_params p = silk_preprocess_default_params(SILK_PREPROCESS_OFFICIAL);
    p.point_count = 64;
    c.set(&p);
    size_t rows = 0;
    EXPECT_EQ(silk_points_prepare(m, nullptr, 0, &p, 1, nullptr, 0, &rows, nullptr), SILK_ERR_INVALID_ARGUMENT)
        << c.what;
    EXPECT_NE(std::string(silk_last_error()).find(c.what), std::string::npos) << c.what << ": " << silk_last_error();
  }
  for (int32_t flag : {0, 1}) {
    silk_preprocess_params p = silk_preprocess_default_params(SILK_PREPROCESS_OFFICIAL);
    p.point_count = 64;
    p.round_float16 = flag;
    size_t rows = 0;
    std::vector<float> out(6 * 64);
    EXPECT_EQ(silk_points_prepare(m, nullptr, 0, &p, 1, out.data(), out.size(), &rows, nullptr), SILK_OK)
        << silk_last_error();
  }
  silk_mesh_destroy(m);
}

// Issue 20, finding 6: max_faces is a hard cap. The generation stops at the first layer end
// with >= max_faces faces and returns at most max_faces of them, still edge- and
// vertex-manifold and consistently oriented (before, max_faces 20 could return 447 faces).
void ExpectCappedAndValid(const char* model_dir, std::initializer_list<int32_t> caps) {
  silk_model* model = nullptr;
  ASSERT_EQ(silk_model_load(model_dir, nullptr, &model), SILK_OK) << silk_last_error();
  silk_mesh* input = nullptr;
  ASSERT_EQ(silk_mesh_load(silk::testing::SourcePath("samples/torus_knot.obj").c_str(), nullptr, &input), SILK_OK);
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model, &g), SILK_OK);
  for (int32_t cap : caps) {
    int capped_runs = 0;
    for (uint64_t seed = 0; seed < 3; ++seed) {
      silk_generate_params p = silk_generate_default_params();
      p.seed = seed;
      p.candidates = 1;
      p.max_faces = cap;
      silk_mesh* out = nullptr;
      silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
      ASSERT_EQ(silk::testing::GenerateFromMesh(g, input, &p, &out, nullptr, &st), SILK_OK) << silk_last_error();
      const std::string at = std::string(model_dir) + " cap " + std::to_string(cap) + " seed " + std::to_string(seed);
      EXPECT_LE(silk::testing::TriangleCount(out), static_cast<size_t>(cap)) << at;
      EXPECT_EQ(st.faces, static_cast<int32_t>(silk::testing::TriangleCount(out))) << at;
      EXPECT_EQ(st.edge_manifold, 1) << at;
      EXPECT_EQ(st.vertex_manifold, 1) << at;
      EXPECT_EQ(st.consistently_oriented, 1) << at;
      if (st.stop_reason == SILK_STOP_MAX_FACES) {
        ++capped_runs;
        EXPECT_GE(st.faces, 1) << at;
      }
      silk_mesh_destroy(out);
    }
    EXPECT_GE(capped_runs, 1) << model_dir << " cap " << cap << ": no run reached the cap";
  }
  silk_generator_destroy(g);
  silk_mesh_destroy(input);
  silk_model_destroy(model);
}

TEST(CapiMaxFaces, IsAHardCapWithAValidMeshTinyModel) {
  if (!silk_generation_available()) GTEST_SKIP();
  ExpectCappedAndValid(TinyModel().c_str(), {1, 5, 20, 100});
}

TEST(CapiMaxFaces, IsAHardCapWithAValidMeshBundledModel) {
  if (!silk_generation_available()) GTEST_SKIP();
  ExpectCappedAndValid(silk::testing::SourcePath("models/default").c_str(), {1, 20, 100});
}

TEST(CapiLog, TheCallbackFires) {
  struct Sink {
    std::vector<std::pair<silk_log_level, std::string>> lines;
  } sink;
  silk_log_set_callback(
      [](silk_log_level level, const char* message, void* user) {
        static_cast<Sink*>(user)->lines.push_back({level, message});
      },
      &sink);
  silk_mesh* m = nullptr;
  EXPECT_NE(silk_mesh_load("/nonexistent/silk_missing.obj", nullptr, &m), SILK_OK);
  if (silk_generation_available()) {
    silk_model* model = nullptr;
    ASSERT_EQ(silk_model_load(TinyModel().c_str(), nullptr, &model), SILK_OK);
    silk_model_destroy(model);
  }
  silk_log_set_callback(nullptr, nullptr);
  ASSERT_FALSE(sink.lines.empty());
  EXPECT_EQ(sink.lines[0].first, SILK_LOG_ERROR);
  EXPECT_NE(sink.lines[0].second.find("silk_missing.obj"), std::string::npos) << sink.lines[0].second;
  if (silk_generation_available()) {
    bool info = false;
    for (const auto& [level, text] : sink.lines)
      info |= level == SILK_LOG_INFO && text.find("loaded model") != std::string::npos;
    EXPECT_TRUE(info);
  }
}

TEST_F(CapiGeneration, TwoGeneratorsOnParallelThreadsMatchSequentialRuns) {
  silk_generator *a = nullptr, *b = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &a), SILK_OK);
  ASSERT_EQ(silk_generator_create(model_, &b), SILK_OK);
  const std::vector<int32_t> s1 = Ids(a, 11), s2 = Ids(a, 12);
  ASSERT_FALSE(s1.empty());
  ASSERT_NE(s1, s2);
  std::vector<int32_t> p1, p2;
  for (int round = 0; round < 3; ++round) {
    std::thread t1([&] { p1 = Ids(a, 11); });
    std::thread t2([&] { p2 = Ids(b, 12); });
    t1.join();
    t2.join();
    EXPECT_EQ(p1, s1) << round;
    EXPECT_EQ(p2, s2) << round;
  }
  silk_generator_destroy(a);
  silk_generator_destroy(b);
}

long RssKb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// RSS flatness is a property of the normal build: ASan's quarantine keeps freed blocks resident
// (up to 256 MiB by default), so there RSS grows without a leak; LeakSanitizer checks that build.
#if defined(__SANITIZE_ADDRESS__)
#define SILK_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SILK_TEST_UNDER_ASAN 1
#endif
#endif

TEST_F(CapiGeneration, FiftyGenerationsKeepTheRssFlat) {
#ifdef SILK_TEST_UNDER_ASAN
  GTEST_SKIP() << "RSS is not a leak measure under ASan (quarantine); LeakSanitizer covers this build";
#endif
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  for (int i = 0; i < 10; ++i) Ids(g, i);  // warm-up: arenas and caches reach their size
  // RSS after every generation; a window's maximum on each side, because the allocator maps and
  // returns whole chunks as it goes (the tiny model swings by 8 MiB between two generations):
  // a leak raises the late window's maximum, a chunk mapped at the last moment does not.
  constexpr int kRuns = 50, kWindow = 10;
  std::vector<long> rss;
  for (int i = 0; i < kRuns; ++i) {
    silk_generator* fresh = nullptr;  // every other run with a fresh generator
    if (i % 2) {
      ASSERT_EQ(silk_generator_create(model_, &fresh), SILK_OK);
    }
    EXPECT_FALSE(Ids(fresh ? fresh : g, 100 + i).empty());
    silk_generator_destroy(fresh);
    rss.push_back(RssKb());
  }
  ASSERT_GT(rss.front(), 0) << "VmRSS not readable from /proc/self/status";
  const long start = *std::max_element(rss.begin(), rss.begin() + kWindow);
  const long end = *std::max_element(rss.end() - kWindow, rss.end());
  std::printf("soak: %d generations, RSS max of the first %d %ld kB, of the last %d %ld kB (%+ld kB)\n", kRuns, kWindow,
              start, kWindow, end, end - start);
  EXPECT_LT(end - start, 16 * 1024);
  silk_generator_destroy(g);
}

TEST_F(CapiGeneration, StepWiseMatchesOneCallAndGrowsByLayers) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  const std::vector<int32_t> whole = Ids(g, 9);
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = mesh_;
  silk_generate_params p = Params(9);
  ASSERT_EQ(silk_generator_start(g, &in, &p), SILK_OK) << silk_last_error();
  int32_t done = 0;
  size_t last_faces = 0;
  int steps = 0, growths = 0;
  while (!done) {
    ASSERT_EQ(silk_generator_advance(g, 1000, SILK_ADVANCE_LAYER, &done), SILK_OK) << silk_last_error();
    silk_mesh* so_far = nullptr;
    ASSERT_EQ(silk_generator_get_mesh(g, &so_far), SILK_OK) << silk_last_error();
    const size_t faces = silk::testing::TriangleCount(so_far);
    EXPECT_GE(faces, last_faces);
    growths += faces > last_faces;
    last_faces = faces;
    silk_mesh_destroy(so_far);
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    ASSERT_EQ(silk_generator_get_stats(g, &st), SILK_OK);
    EXPECT_EQ(st.stop_reason == SILK_STOP_NONE, done == 0);
    ++steps;
  }
  EXPECT_GT(growths, 1);
  silk_mesh* out = nullptr;
  silk_tokens* t = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  ASSERT_EQ(silk_generator_finish(g, &out, &t, &st), SILK_OK) << silk_last_error();
  std::vector<int32_t> ids(silk::testing::TokenCount(t));
  silk_tokens_copy(t, ids.data(), ids.size(), nullptr);
  EXPECT_EQ(ids, whole);
  EXPECT_EQ(static_cast<size_t>(st.faces), silk::testing::TriangleCount(out));
  silk_tokens_destroy(t);
  silk_mesh_destroy(out);

  // Cancel from "another thread" mid-way: finish returns the completed layers.
  ASSERT_EQ(silk_generator_start(g, &in, &p), SILK_OK);
  ASSERT_EQ(silk_generator_advance(g, 30, SILK_ADVANCE_IDS, &done), SILK_OK);
  silk_generator_cancel(g);
  EXPECT_EQ(silk_generator_advance(g, 30, SILK_ADVANCE_IDS, &done), SILK_ERR_CANCELLED);
  ASSERT_EQ(silk_generator_finish(g, &out, nullptr, &st), SILK_OK) << silk_last_error();
  EXPECT_EQ(st.stop_reason, SILK_STOP_CANCELLED);
  EXPECT_EQ(st.tokens, 30);
  silk_mesh_destroy(out);
  silk_generator_destroy(g);
}

TEST_F(CapiGeneration, RawPointsReproduceTheTracedEncoderInput) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  silk_generate_params p = Params(4);
  p.report_flags = SILK_GENERATE_RECORD_TRACE;
  silk_mesh* out = nullptr;
  silk_tokens* t = nullptr;
  ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, &t, nullptr), SILK_OK) << silk_last_error();
  std::vector<int32_t> want(silk::testing::TokenCount(t));
  silk_tokens_copy(t, want.data(), want.size(), nullptr);
  silk_tokens_destroy(t);
  silk_mesh_destroy(out);
  std::string json;
  ASSERT_EQ(silk::testing::GeneratorReport(g, 1, &json), SILK_OK) << silk_last_error();
  // The trace's "points": the encoder input (model frame), 9 significant digits = float32 exact.
  const size_t at = json.find("\"points\":[");
  ASSERT_NE(at, std::string::npos);
  std::vector<double> points;
  const char* c = json.c_str() + at + 9;  // at the [; each number follows [ or ,
  while (*c != ']') {
    char* end = nullptr;
    points.push_back(std::strtod(c + 1, &end));
    c = end;
  }
  ASSERT_EQ(points.size() % 6, 0u);
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.points = points.data();
  in.point_rows = points.size() / 6;
  silk_generate_params q = Params(4);
  q.raw_points = 1;
  ASSERT_EQ(silk_generator_run(g, &in, &q, &out, &t, nullptr), SILK_OK) << silk_last_error();
  std::vector<int32_t> got(silk::testing::TokenCount(t));
  silk_tokens_copy(t, got.data(), got.size(), nullptr);
  EXPECT_EQ(got, want);
  silk_tokens_destroy(t);
  silk_mesh_destroy(out);
  silk_generator_destroy(g);
}

// Best of N through the C API: the stats and the report agree, the returned mesh's score is
// the lowest; N = 1, one-call and step-wise, gives the plain run's ids (the step-wise API with
// N > 1: generator_best_of_n_test.cpp).
TEST_F(CapiGeneration, CandidatesReportEveryScoreAndReturnTheLowest) {
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(model_, &g), SILK_OK);
  silk_generate_params p = Params(5, 200);
  p.candidates = 3;
  p.surface_tolerance = 2;
  silk_mesh* out = nullptr;
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &p, &out, nullptr, &st), SILK_OK) << silk_last_error();
  EXPECT_EQ(st.candidates, 3);
  ASSERT_TRUE(st.chosen_candidate >= 0 && st.chosen_candidate < 3);
  EXPECT_GT(st.guided_tokens, 0);
  EXPECT_EQ(static_cast<size_t>(st.faces), silk::testing::TriangleCount(out));
  silk_mesh_destroy(out);
  std::string json;
  ASSERT_EQ(silk::testing::GeneratorReport(g, 0, &json), SILK_OK);
  // Every "score" of the report's candidate list; the chosen one's is the stats' score and the minimum.
  std::vector<double> scores;
  for (size_t at = json.find("\"score\": "); at != std::string::npos; at = json.find("\"score\": ", at + 1))
    scores.push_back(std::strtod(json.c_str() + at + 9, nullptr));
  ASSERT_EQ(scores.size(), 3u) << json;
  EXPECT_NEAR(scores[static_cast<size_t>(st.chosen_candidate)], st.score, 1e-9 * (1 + st.score));
  for (double s : scores) EXPECT_LE(st.score, s + 1e-12);
  EXPECT_NE(json.find("\"chosen_candidate\": " + std::to_string(st.chosen_candidate)), std::string::npos);

  // N = 1, one-call and step-wise: the plain run.
  silk_generate_params one = Params(5, 200);
  one.candidates = 1;
  silk_tokens* t1 = nullptr;
  ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh_, &one, &out, &t1, &st), SILK_OK);
  silk_mesh_destroy(out);
  EXPECT_EQ(st.candidates, 1);
  EXPECT_EQ(st.chosen_candidate, 0);
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = mesh_;
  ASSERT_EQ(silk_generator_start(g, &in, &one), SILK_OK);
  int32_t done = 0;
  ASSERT_EQ(silk_generator_advance(g, 100000, SILK_ADVANCE_IDS, &done), SILK_OK);
  silk_tokens* t2 = nullptr;
  ASSERT_EQ(silk_generator_finish(g, &out, &t2, &st), SILK_OK);
  silk_mesh_destroy(out);
  EXPECT_EQ(st.candidates, 1);
  ASSERT_EQ(silk::testing::TokenCount(t1), silk::testing::TokenCount(t2));
  std::vector<int32_t> a(silk::testing::TokenCount(t1)), b(a.size());
  silk_tokens_copy(t1, a.data(), a.size(), nullptr);
  silk_tokens_copy(t2, b.data(), b.size(), nullptr);
  EXPECT_EQ(a, b);
  silk_tokens_destroy(t1);
  silk_tokens_destroy(t2);
  silk_generator_destroy(g);
}

// candidates = SILK_MODEL_VALUE (the default) runs the model's N; an explicit N overrides
// it, and the report's settings give the N that ran.
TEST(CapiModel, DefaultCandidatesAreTheModels) {
  if (!silk_generation_available()) GTEST_SKIP();
  EXPECT_EQ(silk_generate_default_params().candidates, SILK_MODEL_VALUE);
  // The tiny model with its own best of N (sampling.candidates 3).
  const fs::path dir = TinyModelCopy("model_n", [](std::string& json) {
    EXPECT_EQ(json.find("\"sampling\""), std::string::npos) << "the tiny model names no sampling defaults";
    json.insert(json.find('{') + 1, "\n  \"sampling\": {\"candidates\": 3},");
  });
  silk_model_params o = silk_model_default_params();
  o.threads = 1;
  silk_model* m = nullptr;
  ASSERT_EQ(silk_model_load(dir.string().c_str(), &o, &m), SILK_OK) << silk_last_error();
  silk_mesh* mesh = nullptr;
  ASSERT_EQ(silk_mesh_load(silk::testing::SourcePath("samples/torus_knot.obj").c_str(), nullptr, &mesh), SILK_OK);
  silk_generator* g = nullptr;
  ASSERT_EQ(silk_generator_create(m, &g), SILK_OK);
  for (int32_t asked : {SILK_MODEL_VALUE, 1, 2}) {
    silk_generate_params p = silk_generate_default_params();
    p.max_tokens = 120;
    p.candidates = asked;
    silk_mesh* out = nullptr;
    silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
    ASSERT_EQ(silk::testing::GenerateFromMesh(g, mesh, &p, &out, nullptr, &st), SILK_OK) << silk_last_error();
    silk_mesh_destroy(out);
    const int32_t want = asked == SILK_MODEL_VALUE ? 3 : asked;
    EXPECT_EQ(st.candidates, want) << "asked " << asked;
    std::string json;
    ASSERT_EQ(silk::testing::GeneratorReport(g, 0, &json), SILK_OK);
    EXPECT_NE(json.find("\"candidates\": " + std::to_string(want) + ","), std::string::npos) << json.substr(0, 900);
  }
  silk_generator_destroy(g);
  silk_mesh_destroy(mesh);
  silk_model_destroy(m);
  fs::remove_all(dir);
}

}  // namespace
