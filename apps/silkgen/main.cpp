// silkgen: point cloud or mesh in, generated Mesh Silksong mesh out (GLB/OBJ/PLY), with the
// grammar-constrained runtime (engine/runtime). Exit codes: 0 ok, 1 failure, 2 usage.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <random>
#include <string>

#include "io/atomic_file.h"
#include "io/token_text.h"
#include "model_locate.h"
#include "output_writer.h"
#include "progress_bar.h"
#include "report_json.h"
#include "runtime/cpu_info.h"
#include "runtime/generate_pipeline.h"
#include "runtime/model.h"

namespace {

constexpr int kExitOk = 0, kExitFail = 1, kExitUsage = 2;

int Fail(const std::string& message) {
  std::fprintf(stderr, "silkgen: %s\n", message.c_str());
  return kExitFail;
}

int Fail(const silk::Status& s) { return Fail(s.message()); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"silkgen — generate a mesh from a point cloud or a mesh (Mesh Silksong, grammar-constrained)"};
  app.set_version_flag("--version", SILK_VERSION_STRING);
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);  // later options win
  std::string input, output, model_dir, seed_text = "0", repair = "off", stats_path, tokens_path, trace_path;
  int threads = 0, max_tokens = 0, max_faces = 0, n_points = 0;
  // Sampling, pre-processing and decoder precision default to model.json's; these sentinels
  // (negative / empty) mean "not given".
  double temperature = -1, top_p = -1, top_p_temperature = -1;
  int top_k = -1;
  std::string decoder, preprocessing;
  bool unconstrained = false, int8 = false, part_colors = false, quiet = false, raw_points = false;
  bool no_skip_forced = false, kv_copy = false, sample_then_check = false;

  app.add_option("input", input, "Point-cloud PLY with normals (nx ny nz), or a mesh: PLY OBJ STL OFF glTF GLB")
      ->required()->check(CLI::ExistingFile);
  app.add_option("-o,--output", output, "Output mesh: .glb (one node per part), .obj or .ply (optional with --tokens)");
  app.add_option("--model", model_dir, "Model folder (model.json, encoder.onnx, decoder.onnx); default: the bundled model");
  app.add_option("--seed", seed_text, "Random seed (integer) or 'random'")->capture_default_str();
  app.add_option("--threads", threads, "onnxruntime threads (0 = physical cores)")->check(CLI::Range(0, 1024))
      ->capture_default_str();
  app.add_option("--temperature", temperature, "Sampling temperature (0 = greedy); default: model.json's")
      ->check(CLI::Range(0.0, 100.0));
  app.add_option("--top-k", top_k, "Keep the k most likely legal ids (0 = off); default: model.json's")
      ->check(CLI::Range(0, 10269));
  app.add_option("--top-p", top_p, "Nucleus: keep the smallest set with this much probability (1 = off); default: "
                 "model.json's")->check(CLI::Range(0.0, 1.0));
  app.add_option("--top-p-temperature", top_p_temperature,
                 "Compute top-p at this temperature on the top-k logits (official chain; 0 = at --temperature); "
                 "default: model.json's")->check(CLI::Range(0.0, 100.0));
  app.add_option("--max-tokens", max_tokens, "Cap on generated ids incl. EOS (0 = the model's limit)")
      ->check(CLI::Range(0, 10240))->capture_default_str();
  app.add_option("--max-faces", max_faces, "Stop at the first layer end with at least this many faces (0 = off)")
      ->check(CLI::Range(0, 1000000))->capture_default_str();
  app.add_option("--repair", repair, "Holes in the result: off, report, or repair (close small ones)")
      ->check(CLI::IsMember({"off", "report", "repair"}))->capture_default_str();
  app.add_flag("--unconstrained", unconstrained, "Sample without the grammar mask (the mesh is the legal prefix)");
  app.add_option("--stats", stats_path, "Write run figures as JSON");
  app.add_option("--tokens", tokens_path, "Write the generated ids, one per line (EOS 10267 last when one was generated)");
  app.add_option("--points", n_points, "Encoder points to sample (0 = the model's n_points)")->check(CLI::Range(0, 1 << 20));
  app.add_option("--decoder", decoder, "Decoder precision: fp32, int8 or int4; default: model.json's default_decoder")
      ->check(CLI::IsMember({"fp32", "int8", "int4"}));
  app.add_flag("--int8", int8, "Same as --decoder int8");
  app.add_option("--preprocessing", preprocessing, "Point pre-processing: silk or official; default: model.json's")
      ->check(CLI::IsMember({"silk", "official"}));
  app.add_flag("--raw-points", raw_points,
               "The input is the encoder's point cloud, used exactly as given (x y z nx ny nz PLY with the model's "
               "point count; no normalisation, resampling or rounding); the output stays in the model's frame");
  app.add_flag("--part-colors", part_colors, "GLB: a distinct COLOR_0 per part");
  app.add_flag("-q,--quiet", quiet, "No settings, progress or summary on stderr");
  // Measurement switches (docs/runtime.md), not needed for normal use.
  app.add_option("--trace", trace_path, "Write points + every id with its legal set (reference check)")->group("");
  app.add_flag("--no-skip-forced", no_skip_forced, "Run the model for forced ids too")->group("");
  app.add_flag("--kv-copy", kv_copy, "Naive KV cache handling (copy per step)")->group("");
  app.add_flag("--sample-then-check", sample_then_check, "Sample unmasked, fall back to the mask")->group("");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  const auto t_start = std::chrono::steady_clock::now();

  // Settings that can be checked before any work.
  if (output.empty() && tokens_path.empty()) {
    std::fprintf(stderr, "silkgen: give -o/--output (a mesh) or --tokens (the ids), or both\n");
    return kExitUsage;
  }
  if (!output.empty())
    if (std::string e = silkgen::CheckOutputPath(output); !e.empty()) return Fail(e);
  uint64_t seed = 0;
  if (seed_text == "random") {
    std::random_device rd;
    seed = (static_cast<uint64_t>(rd()) << 32) ^ rd();
  } else {
    try {
      size_t used = 0;
      seed = std::stoull(seed_text, &used, 10);
      if (used != seed_text.size() || seed_text[0] == '-') throw std::invalid_argument("seed");
    } catch (const std::exception&) {
      std::fprintf(stderr, "silkgen: --seed: '%s' is neither an unsigned integer nor 'random'\n", seed_text.c_str());
      return kExitUsage;
    }
  }
  if (model_dir.empty()) {
    model_dir = silkgen::DefaultModelDir();
    if (model_dir.empty()) {
      std::string tried;
      for (const std::string& c : silkgen::DefaultModelCandidates()) tried += "\n  " + c;
      return Fail("no bundled model found; pass --model DIR (looked in:" + tried + ")");
    }
  }

  silk::ModelLoadOptions lo;
  lo.threads = threads;
  if (int8) decoder = "int8";
  if (!decoder.empty())
    lo.decoder = decoder == "int4" ? silk::DecoderPrecision::kInt4
                 : decoder == "int8" ? silk::DecoderPrecision::kInt8 : silk::DecoderPrecision::kFp32;
  auto model = silk::Model::Load(model_dir, lo);
  if (!model.ok()) return Fail(model.status());
  auto in = silk::LoadGenerationInput(input);
  if (!in.ok()) return Fail(in.status());

  silkgen::RunSettings rs;
  rs.input = input;
  rs.output = output;
  rs.model_dir = model_dir;
  rs.model_config = (*model)->config().config_name;
  rs.point_cloud = in->point_cloud;
  rs.input_vertices = static_cast<int32_t>(in->mesh.positions.size());
  rs.input_faces = static_cast<int32_t>(in->mesh.triangles.size());
  rs.points = n_points > 0 ? n_points : (*model)->config().dims.n_points;
  silk::GenerateOptions& go = rs.options;
  const silk::ModelConfig& mc = (*model)->config();
  go.sampling = mc.sampling;
  go.sampling.seed = seed;
  if (temperature >= 0) go.sampling.temperature = temperature;
  if (top_k >= 0) go.sampling.top_k = top_k;
  if (top_p >= 0) go.sampling.top_p = top_p;
  if (top_p_temperature >= 0) go.sampling.top_p_temperature = top_p_temperature;
  silk::PreprocessingParams prep = silk::ModelPreprocessing(mc, n_points);
  if (!preprocessing.empty() && preprocessing != silk::PreprocessingKindName(prep.kind))
    prep = preprocessing == "official" ? silk::OfficialPreprocessing(prep.n_points)
                                       : silk::SilkPreprocessing(prep.normalize_bound, prep.n_points);
  rs.preprocessing = raw_points ? "raw" : silk::PreprocessingKindName(prep.kind);
  go.max_tokens = max_tokens;
  go.max_faces = max_faces;
  go.holes = repair == "repair" ? silk::HolePolicy::kRepair
             : repair == "report" ? silk::HolePolicy::kReport : silk::HolePolicy::kOff;
  go.unconstrained = unconstrained;
  go.skip_forced = !no_skip_forced;
  go.kv_in_place = !kv_copy;
  go.order = sample_then_check ? silk::SampleOrder::kSampleThenCheck : silk::SampleOrder::kMaskFirst;
  go.record_trace = !trace_path.empty();

  if (!quiet) {
    std::fprintf(stderr,
                 "silkgen %s\n  input   %s (%s, %d vertices, %d faces)\n  output  %s\n  model   %s (%s, %d threads%s)\n"
                 "  seed %llu  temperature %g  top-k %d  top-p %g (at temperature %g)  max-tokens %d  max-faces %d  "
                 "repair %s%s\n  points  %d, %s\n",
                 SILK_VERSION_STRING, input.c_str(), in->point_cloud ? "point cloud" : "mesh", rs.input_vertices,
                 rs.input_faces, output.empty() ? "(none)" : output.c_str(), model_dir.c_str(), rs.model_config.c_str(),
                 (*model)->threads(), (*model)->precision() == silk::DecoderPrecision::kFp32 ? "" :
                 (*model)->precision() == silk::DecoderPrecision::kInt8 ? ", INT8" : ", INT4",
                 static_cast<unsigned long long>(seed), go.sampling.temperature, go.sampling.top_k, go.sampling.top_p,
                 go.sampling.top_p_temperature > 0 ? go.sampling.top_p_temperature : go.sampling.temperature,
                 max_tokens, max_faces, repair.c_str(), unconstrained ? "  UNCONSTRAINED" : "", rs.points,
                 raw_points ? "raw (used as given, model frame)" : silk::PreprocessingKindName(prep.kind));
  }

  silkgen::ProgressBar bar(!quiet);
  silk::GenerateCallbacks cb;
  cb.progress = [&bar](const silk::GenerateProgress& p) { bar.Update(p); };
  silk::Generator generator(**model);
  // The trace needs the exact encoder input, so the points are prepared here once.
  auto t_prep = std::chrono::steady_clock::now();
  auto pts = raw_points ? silk::RawModelPoints(*in, rs.points) : silk::PrepareModelPoints(*in, prep, seed);
  if (!pts.ok()) return Fail(pts.status().WithContext(input + ": "));
  const double prep_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_prep).count();
  auto gen = generator.Run(pts->rows, go, cb);
  bar.Finish();
  if (!gen.ok()) return Fail(gen.status());
  silk::PipelineResult result;
  result.generation = std::move(*gen);
  result.output = silk::ToInputFrame(result.generation.mesh, pts->transform);
  silk::GenerationStats& st = result.generation.stats;
  st.seconds.load_input = prep_seconds;
  silk::FillVerdicts(result.output, &st);

  auto t_write = std::chrono::steady_clock::now();
  if (!output.empty())
    if (silk::Status s = silkgen::WriteGeneratedMesh(output, result.output, part_colors); !s.ok()) return Fail(s);
  if (!tokens_path.empty())
    if (silk::Status s = silk::WriteFileAtomically(tokens_path, silk::FormatTokenText(result.generation.tokens)); !s.ok())
      return Fail(s);
  if (!trace_path.empty())
    if (silk::Status s = silk::WriteFileAtomically(trace_path, silkgen::TraceJson(rs, pts->rows, result.generation));
        !s.ok())
      return Fail(s);
  st.seconds.write_output = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_write).count();
  st.seconds.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  if (!stats_path.empty())
    if (silk::Status s = silk::WriteFileAtomically(stats_path, silkgen::StatsJson(rs, result)); !s.ok()) return Fail(s);

  if (!quiet)
    std::fprintf(stderr,
                 "silkgen: %lld tokens (%s, %.0f%% forced) -> %d faces, %d part(s); %.1f tok/s, %.2f s total; "
                 "edge-manifold %s, vertex-manifold %s, oriented %s, watertight %s\n",
                 static_cast<long long>(st.tokens), st.stop_reason.c_str(), 100.0 * st.forced_share(), st.faces,
                 st.components, st.tokens_per_second, st.seconds.total, st.edge_manifold ? "yes" : "no",
                 st.vertex_manifold ? "yes" : "no", st.consistently_oriented ? "yes" : "no",
                 st.watertight ? "yes" : "no");
  return kExitOk;
}
