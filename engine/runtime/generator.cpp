// The generation loop: encoder once, then per id: grammar (forced? legal mask) -> decoder for
// the pending known ids -> sampling chain -> Accept. Stops at EOS, at the token cap (the
// grammar's length budget makes constrained sequences end with EOS inside it), at the face
// cap, or on cancel.
#include "runtime/generator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "decoder/grammar.h"
#include "runtime/decoder_runner.h"
#include "runtime/model_impl.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<std::pair<int32_t, int32_t>> MaskRanges(const TokenMask& m) {
  std::vector<std::pair<int32_t, int32_t>> r;
  for (int32_t id = m.Next(0); id >= 0; id = m.Next(id + 1)) {
    if (!r.empty() && r.back().second == id) r.back().second = id + 1;
    else r.push_back({id, id + 1});
  }
  return r;
}

// "N ids (last: a b c ...)" for internal-error messages.
std::string TailText(const std::vector<int32_t>& ids) {
  std::string s = std::to_string(ids.size()) + " ids (last:";
  for (size_t i = ids.size() > 24 ? ids.size() - 24 : 0; i < ids.size(); ++i) s += " " + std::to_string(ids[i]);
  return s + ")";
}

bool ClosesLayer(int32_t id) { return id == vocab::kUBegin || id == vocab::kEBegin; }

}  // namespace

StatusOr<GenerateResult> Generator::Run(const std::vector<float>& points, const GenerateOptions& options,
                                        const GenerateCallbacks& callbacks) {
  const Model::Impl& m = model_.impl();
  const ModelConfig& cfg = m.config;
  if (points.empty() || points.size() % 6 != 0)
    return InvalidArgument("generate: points must be a non-empty array of rows of 6 floats");
  const int32_t model_cap = cfg.dims.max_seq_len - 1;  // ids incl. EOS after BOS
  if (options.max_tokens < 0 || options.max_faces < 0) return InvalidArgument("generate: negative cap");
  const int32_t cap = options.max_tokens > 0 ? std::min(options.max_tokens, model_cap) : model_cap;
  if (cap < 2) return InvalidArgument("generate: max_tokens must be at least 2");
  const SamplingParams& sp = options.sampling;
  if (!std::isfinite(sp.temperature) || sp.temperature < 0 || sp.top_k < 0 || !(sp.top_p >= 0 && sp.top_p <= 1) ||
      !(sp.top_p_temperature >= 0 && std::isfinite(sp.top_p_temperature)))
    return InvalidArgument("generate: need temperature >= 0, top_k >= 0, top_p in [0, 1] and top_p_temperature >= 0");

  GenerateResult res;
  GenerationStats& st = res.stats;
  st.threads = m.threads;
  st.int8 = m.precision == DecoderPrecision::kInt8;
  st.decoder = DecoderPrecisionName(m.precision);
  const auto t_start = Clock::now();

  // Encoder: cross-attention K/V once per input.
  auto t0 = Clock::now();
  SILK_ASSIGN_OR_RETURN(Ort::Value cross, RunEncoder(m, points.data(), static_cast<int64_t>(points.size() / 6)));
  st.seconds.encoder = Since(t0);
  float* cross_data = cross.GetTensorMutableData<float>();

  // Cache: BOS + every id but the last (EOS is never fed).
  SILK_RETURN_IF_ERROR(cache_.Reserve(cap, ModelKvShape(cfg.dims)));
  st.kv_cache_bytes = cap * cfg.dims.kv_row_floats() * static_cast<int64_t>(sizeof(float));
  DecoderRunner runner(m, &cache_, cross_data, options.kv_in_place ? KvMode::kInPlace : KvMode::kCopy);

  GrammarOptions gopt;
  gopt.max_length = cap;
  Grammar grammar(gopt);
  Sampler sampler(options.sampling);
  std::vector<int32_t> pending = {cfg.bos_id};
  int32_t faces_at_close = -1;
  MeshBuildCache so_far_cache;  // --max-faces: closed components are built once
  bool illegal_seen = false;
  const auto t_loop = Clock::now();

  while (true) {
    if (callbacks.cancel && callbacks.cancel()) return Status(StatusCode::kCancelled, "generation cancelled");
    int32_t id = -1;
    bool forced = false;
    const TokenMask* mask = nullptr;
    if (!options.unconstrained) {
      t0 = Clock::now();
      id = grammar.Forced();
      mask = &grammar.LegalMask();
      st.seconds.grammar += Since(t0);
      if (mask->Empty()) {
        // Cannot happen if the grammar's liveness guarantee holds; stop with what is closed
        // rather than fail the whole run, and say so in the stats.
        st.stop_reason = "grammar_dead_end";
        st.dead_end = "no legal id after " + TailText(res.tokens);
        break;
      }
      forced = id >= 0;
    }
    if (!forced || !options.skip_forced) {
      t0 = Clock::now();
      SILK_RETURN_IF_ERROR(runner.Feed(pending.data(), static_cast<int64_t>(pending.size())));
      st.seconds.decoder += Since(t0);
      pending.clear();
    }
    if (!forced) {
      t0 = Clock::now();
      if (options.order == SampleOrder::kSampleThenCheck && mask) {
        id = sampler.Sample(runner.last_logits(), nullptr);
        if (!mask->Test(id)) {
          ++st.resampled;
          id = sampler.Sample(runner.last_logits(), mask);
        }
      } else {
        id = sampler.Sample(runner.last_logits(), mask);
      }
      st.seconds.sampling += Since(t0);
      ++st.sampled_tokens;
    } else {
      ++st.forced_tokens;
    }
    if (options.record_trace) {
      TraceStep step;
      step.id = id;
      step.forced = forced;
      if (!forced && mask) step.legal = MaskRanges(*mask);
      res.trace.push_back(std::move(step));
    }

    t0 = Clock::now();
    if (!options.unconstrained) {
      Rejection r = grammar.Accept(id);
      if (!r.ok())
        return InternalError("generate: id " + std::to_string(id) + " was rejected after " + TailText(res.tokens) + ": " +
                             r.message);
    } else if (!illegal_seen) {
      Rejection r = grammar.Accept(id);
      if (!r.ok()) {
        illegal_seen = true;
        st.illegal_at = static_cast<int64_t>(res.tokens.size());
        st.illegal_reason = r.message;
      }
    }
    st.seconds.grammar += Since(t0);
    res.tokens.push_back(id);

    if (id == vocab::k_eos_id) {
      st.stop_reason = "eos";
      break;
    }
    if (static_cast<int32_t>(res.tokens.size()) >= cap) {
      st.stop_reason = "max_tokens";
      break;
    }
    pending.push_back(id);
    if (options.max_faces > 0 && !illegal_seen && ClosesLayer(id)) {
      t0 = Clock::now();
      auto so_far = BuildMeshSoFar(grammar, MeshBuildOptions{}, nullptr, &so_far_cache);
      st.seconds.build_mesh += Since(t0);
      if (so_far.ok()) faces_at_close = static_cast<int32_t>(so_far->faces.size());
      if (faces_at_close >= options.max_faces) {
        st.stop_reason = "max_faces";
        break;
      }
    }
    if (callbacks.progress) {
      GenerateProgress p;
      p.tokens = static_cast<int64_t>(res.tokens.size());
      p.max_tokens = cap;
      p.components = static_cast<int32_t>(grammar.stream().components.size());
      p.faces = faces_at_close;
      p.seconds = Since(t_start);
      callbacks.progress(p);
    }
  }
  const double loop_seconds = Since(t_loop);
  st.tokens = static_cast<int64_t>(res.tokens.size());
  st.model_calls = runner.calls();
  st.fed_positions = cache_.length();
  st.tokens_per_second = loop_seconds > 0 ? st.tokens / loop_seconds : 0;
  st.generation_seconds = Since(t_start);

  // Mesh: the whole sequence when it ended legally, else what the grammar closed so far.
  t0 = Clock::now();
  MeshBuildOptions bopt;
  bopt.holes = options.holes;
  const bool complete = !options.unconstrained ? st.stop_reason == "eos" || st.stop_reason == "max_tokens"
                                               : (!illegal_seen && grammar.Ended());
  if (complete) {
    SILK_ASSIGN_OR_RETURN(res.mesh, BuildMesh(grammar.stream(), bopt, &res.report));
  } else {
    SILK_ASSIGN_OR_RETURN(res.mesh, BuildMeshSoFar(grammar, bopt, &res.report));
  }
  st.seconds.build_mesh += Since(t0);
  st.faces = static_cast<int32_t>(res.mesh.faces.size());
  st.vertices = static_cast<int32_t>(res.mesh.positions.size());
  st.components = res.mesh.components;
  st.holes_found = static_cast<int32_t>(res.report.holes.size());
  for (const HoleReport& h : res.report.holes) st.holes_repaired += h.repaired ? 1 : 0;
  st.faces_added = res.report.faces_added;
  st.fan_gaps_closed = res.report.fan_gaps_closed;
  st.vertices_split = res.report.vertices_split;
  st.window_findings = static_cast<int32_t>(res.report.window_findings.size());
  return res;
}

}  // namespace silk
