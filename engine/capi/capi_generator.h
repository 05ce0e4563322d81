// The generation handles behind silk.h: silk_model shares its Model with every generator made
// from it (destroy order is free), and silk_generator carries one step-wise generation, its
// settings and a busy flag that turns concurrent use into SILK_ERR_BUSY.
#pragma once
#if defined(SILK_HAVE_RUNTIME)
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "capi/capi_internal.h"
#include "mesh/normalize.h"
#include "runtime/generate_pipeline.h"
#include "runtime/model.h"

struct silk_model {
  std::shared_ptr<silk::Model> model;
};

// What the report needs to say about the last generation besides its stats (the settings as
// given; the resolved sampling values are in GenerationStats::sampling).
struct GenerationSettings {
  std::string input_name;
  std::string preprocessing;  // "silk", "official" or "raw"
  bool point_cloud = false, raw = false;
  int32_t input_vertices = 0, input_faces = 0, points = 0;
  silk_generate_params params{};
  silk::GenerateOptions options;  // resolved (model.json defaults applied)
};

struct silk_generator {
  explicit silk_generator(std::shared_ptr<silk::Model> m) : model(std::move(m)), generator(*model) {}
  std::shared_ptr<silk::Model> model;  // keeps the model alive as long as the generator
  silk::Generator generator;
  std::atomic<bool> busy{false};
  std::atomic<bool> cancel_requested{false};
  GenerationSettings settings;
  silk::NormalizeTransform transform;  // model frame -> input frame (identity for raw points)
  std::vector<float> points;           // the encoder's input (kept for the trace)
  double prepare_seconds = 0;
  bool has_result = false;              // a finished generation (for the report)
  silk::GenerateResult result;          // tokens, stats, trace of the last finished generation
};

namespace silk::capi {

// Holds a generator's busy flag for one call; ok() is false when another thread holds it.
class BusyLock {
 public:
  explicit BusyLock(silk_generator* g) : g_(g), ok_(!g->busy.exchange(true)) {}
  ~BusyLock() {
    if (ok_) g_->busy.store(false);
  }
  bool ok() const { return ok_; }

 private:
  silk_generator* g_;
  bool ok_;
};

// GenerationStats -> silk_generate_stats (the C view of the one stats struct).
void FillStats(const GenerationStats& s, silk_generate_stats* out);
int32_t StopCode(const std::string& reason);
// The report JSON (settings, input, figures; trace: points and every id's legal set).
std::string ReportJson(const silk_generator& g, bool trace);

}  // namespace silk::capi
#endif
