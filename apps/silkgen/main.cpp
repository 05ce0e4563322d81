// SPDX-License-Identifier: MIT
// silkgen: point cloud or mesh in, generated Mesh Silksong mesh out (GLB/OBJ/PLY), with the
// grammar-constrained runtime. A client of the public API alone (silk.hpp over silk.h): the
// same generation, output and JSON report every binding gets. Exit codes: 0 ok, 1 failure, 2 usage.
#include <CLI/CLI.hpp>

#include <cctype>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "../common/app_errors.h"
#include "../common/app_files.h"
#include "../common/file_roles.h"
#include "../common/interrupt.h"
#include "../common/utf8_args.h"
#include "batch_options.h"
#include "batch_run.h"
#include "exit_codes.h"
#include "model_list.h"
#include "progress_bar.h"
#include "silk/silk.hpp"

namespace {

using silkgen::kExitFail, silkgen::kExitOk, silkgen::kExitUsage;

int Fail(silk_status kind, const std::string& message, int rc = kExitFail) {
  silkapp::PrintError("silkgen", kind, message);
  return rc;
}

int Fail(const silk_cpp::Error& e) {
  silkapp::PrintError("silkgen", e);
  return e.status() == SILK_ERR_CANCELLED && silkapp::InterruptSignal() ? 128 + silkapp::InterruptSignal() : kExitFail;
}

// Output extension check before any work ("" if fine).
std::string CheckOutputFormat(const std::string& path) {
  std::string p = path;
  for (char& c : p) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* ext : {".glb", ".obj", ".ply"})
    if (p.size() >= 4 && p.compare(p.size() - 4, 4, ext) == 0) return "";
  return path + ": unknown output format (use .glb, .obj or .ply)";
}

bool EndsWithPly(const std::string& path) {
  std::string p = path;
  for (char& c : p) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return p.size() >= 4 && p.compare(p.size() - 4, 4, ".ply") == 0;
}

// Writes text through libsilk's atomic writer, so a failed run leaves no partial file.
void WriteTextFile(const std::string& path, const std::string& text) { silk_cpp::WriteFile(path, text); }

// The encoder's points (rows of x y z nx ny nz) as an ascii PLY point cloud, exact doubles.
std::string PointsPly(const std::vector<double>& rows) {
  std::string text =
      "ply\nformat ascii 1.0\ncomment silkgen --save-points: the encoder's points, input frame\n"
      "element vertex " +
      std::to_string(rows.size() / 6) + "\n";
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) text += std::string("property double ") + p + "\n";
  text += "end_header\n";
  char buf[32];
  for (size_t i = 0; i < rows.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g", rows[i]);
    text += buf;
    text += i % 6 == 5 ? '\n' : ' ';
  }
  return text;
}

struct Args {
  std::string input, output, model_dir, seed_text = "0", repair = silk_hole_policy_name(SILK_HOLES_OFF), stats_path,
                                        tokens_path, trace_path, save_points;
  int threads = 0, max_tokens = 0, max_faces = 0, n_points = 0;
  // Sampling, pre-processing and decoder precision default to model.json's; these sentinels
  // (SILK_MODEL_VALUE / empty) mean "not given"; a given value is checked by libsilk (CheckSettings).
  double temperature = SILK_MODEL_VALUE, top_p = SILK_MODEL_VALUE, top_p_temperature = SILK_MODEL_VALUE;
  int top_k = SILK_MODEL_VALUE;
  int surface_tolerance = SILK_DEFAULT_SURFACE_TOLERANCE, candidates = SILK_MODEL_VALUE, rows = SILK_MODEL_VALUE;
  std::string decoder, kv_precision, preprocessing, orient = silk_orientation_name(SILK_DEFAULT_ORIENT);
  std::string face_guidance;                 // empty: the model's (model.json sampling.face_guidance)
  double face_tolerance = SILK_MODEL_VALUE;  // the model's
  bool list_models = false, int8 = false, part_colors = false, quiet = false, raw_points = false;
  silkgen::BatchArgs batch;
};

// A setting's valid values from libsilk's range table (silk_param_range), for --help: " [0..100]",
// " [0, 14 or more]"; "" in a libsilk without generation.
std::string Valid(const char* name) {
  double lo = 0, hi = 0;
  int32_t zero_too = 0;
  if (silk_param_range(name, &lo, &hi, &zero_too) != SILK_OK) return "";
  char text[64];
  if (hi >= INT32_MAX)
    std::snprintf(text, sizeof text, " [%s%.10g or more]", zero_too ? "0, " : "", lo);
  else
    std::snprintf(text, sizeof text, " [%s%.10g..%.10g]", zero_too ? "0, " : "", lo, hi);
  return text;
}

// Input, output and model: what silkgen reads and writes.
void AddFileOptions(CLI::App& app, Args& a) {
  app.add_option("input", a.input,
                 "A point cloud (PLY without faces, XYZ/PTS; normals estimated when it has none), or a "
                 "mesh: PLY OBJ STL OFF glTF GLB PMD (or --batch)")
      ->check(silkapp::ExistingFile());
  app.add_option("-o,--output", a.output,
                 "Output mesh: .glb (one node per part), .obj or .ply (optional with --tokens)");
  app.add_option("--model", a.model_dir,
                 "Model folder (model.json, encoder.onnx, decoder.onnx), or the name of a model in the "
                 "models folder (--list-models; a path always wins); default: the bundled model");
  app.add_flag("--list-models", a.list_models,
               "List the models --model takes by name (name, architecture, size, decoders, "
               "KV caches, folder) and exit");
}

// The sampler chain: seed, temperature, truncation, guidance, best of N.
void AddSamplingOptions(CLI::App& app, Args& a) {
  app.add_option("--seed", a.seed_text, "Random seed (integer) or 'random'")->capture_default_str();
  app.add_option("--threads", a.threads, "onnxruntime threads (0 = physical cores)" + Valid("threads"))
      ->capture_default_str();
  app.add_option("--temperature", a.temperature,
                 "Sampling temperature (0 = greedy); default: model.json's" + Valid("temperature"));
  app.add_option("--top-k", a.top_k,
                 "Keep the k most likely legal ids (0 = off); default: model.json's" + Valid("top_k"));
  app.add_option("--top-p", a.top_p,
                 "Nucleus: keep the smallest set with this much probability (1 = off); default: "
                 "model.json's" +
                     Valid("top_p"));
  app.add_option("--top-p-temperature", a.top_p_temperature,
                 "Compute top-p at this temperature on the top-k logits (official chain; 0 = at --temperature); "
                 "default: model.json's" +
                     Valid("top_p_temperature"));
  app.add_option("--max-tokens", a.max_tokens,
                 "Cap on generated ids incl. EOS (0 = the model's limit)" + Valid("max_tokens"))
      ->capture_default_str();
  app.add_option(
         "--max-faces", a.max_faces,
         "Hard cap on the output's faces: stop at the first layer end with at least this many, keep at most this many "
         "(a valid subset of that layer; 0 = off)" +
             Valid("max_faces"))
      ->capture_default_str();
  app.add_option("--repair", a.repair, "Holes in the result: off, report, or repair (close small ones)")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_hole_policy_name, SILK_HOLES_OFF)))
      ->capture_default_str();
  app.add_option("--surface-tolerance", a.surface_tolerance,
                 "Surface guidance: new vertices only on grid cells within CELLS (of 128) of an input point's cell, "
                 "nearest legal cells when none is (0 = off)" +
                     Valid("surface_tolerance"))
      ->capture_default_str()
      ->type_name("CELLS");
  app.add_option("--candidates", a.candidates,
                 "Best of N: N generations with seeds derived from --seed, the one closest to the input (Chamfer "
                 "distance to the encoder's points) written; every score goes into --stats (default: the model's "
                 "N, model.json sampling.candidates; 1 when it names none)" +
                     Valid("candidates"))
      ->type_name("N");
  app.add_option("--rows", a.rows,
                 "Best of N: how many of the candidates are decoded together, at most (one decoder call reads "
                 "every weight once for all of them); each candidate's ids are those it gets alone, so only the "
                 "time depends on it; 1 = one after another (default: the model's, model.json sampling.rows; "
                 "else 8)" +
                     Valid("rows"))
      ->type_name("R");
  app.add_option("--orient", a.orient,
                 "Which side of each part faces out: input (reverse every part whose winding disagrees with the "
                 "input's normals) or tokens (the winding the ids carry, as silktok decode gives it)")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_orientation_name, SILK_ORIENT_TOKENS)))
      ->capture_default_str();
  app.add_option("--face-guidance", a.face_guidance,
                 "Face guidance: off, hard (between-layer ids whose faces stray from the input's surface are removed; "
                 "the best-scoring kept when none passes) or soft (their logits lowered); default: the model's "
                 "(model.json sampling.face_guidance), else libsilk's (docs/runtime.md)")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_face_guidance_name, SILK_FACE_GUIDANCE_OFF)));
  app.add_option("--face-tolerance", a.face_tolerance,
                 "Face guidance: how far (cells of 128) a face's corners, edge midpoints and centroid may lie from the "
                 "input's points; default: the model's, else libsilk's" +
                     Valid("face_tolerance"))
      ->type_name("CELLS");
}

// Side outputs and how the model runs (precision, points, pre-processing).
void AddRunOptions(CLI::App& app, Args& a) {
  app.add_option("--stats", a.stats_path, "Write run figures as JSON");
  app.add_option("--save-points", a.save_points,
                 "Write the points the encoder saw, with their normals (estimated ones for a cloud without), in the "
                 "input's frame, as an ascii PLY point cloud")
      ->type_name("FILE.ply");
  silk_vocab_info vocab = silk_cpp::Sized<silk_vocab_info>();
  silk_vocab_get_info(&vocab);  // the ids come from libsilk's vocabulary, not a constant here
  app.add_option(
      "--tokens", a.tokens_path,
      "Write the generated ids, one per line (EOS " + std::to_string(vocab.eos_id) + " last when one was generated)");
  app.add_option("--points", a.n_points, "Encoder points to sample (0 = the model's n_points)" + Valid("point_count"));
  app.add_option("--decoder", a.decoder,
                 "Decoder precision: fp32, int8 or int4; default (also when not given): model.json's default_decoder")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_decoder_precision_name, SILK_DECODER_DEFAULT)));
  app.add_flag("--int8", a.int8, "Deprecated (removed in 2.0): --decoder int8");
  app.add_option("--kv-precision", a.kv_precision,
                 "Self-attention K/V cache: fp32, fp16 or int8; default (also when not given): the model's "
                 "(model.json files.default_kv_precision)")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_kv_precision_name, SILK_KV_DEFAULT)));
  app.add_option("--preprocessing", a.preprocessing, "Point pre-processing: silk or official; default: model.json's")
      ->check(CLI::IsMember(silk_cpp::EnumNames(silk_preprocess_kind_name, SILK_PREPROCESS_SILK)));
  app.add_flag("--raw-points", a.raw_points,
               "The input is the encoder's point cloud, used exactly as given (x y z nx ny nz PLY with the model's "
               "point count; no normalisation, resampling or rounding); the output stays in the model's frame");
  app.add_flag("--part-colors", a.part_colors, "GLB: a distinct COLOR_0 per part");
  app.add_flag("-q,--quiet", a.quiet, "No settings, progress or summary on stderr");
}

void AddOptions(CLI::App& app, Args& a) {
  AddFileOptions(app, a);
  AddSamplingOptions(app, a);
  AddRunOptions(app, a);
  // The reference check's trace (tests/models/reference_loop.py), not needed for normal use.
  app.add_option("--trace", a.trace_path, "Write points + every id with its legal set (reference check)")->group("");
  silkgen::AddBatchOptions(app, a.batch, Valid("parallel"));
}

// The numeric settings given on the command line, each checked by libsilk's one range table
// (silk_param_check) before any work: a usage error naming the flag, with libsilk's message.
int CheckSettings(const CLI::App& app, const Args& a) {
  const std::tuple<const char*, const char*, double> given[] = {
      {"--threads", "threads", a.threads},
      {"--temperature", "temperature", a.temperature},
      {"--top-k", "top_k", a.top_k},
      {"--top-p", "top_p", a.top_p},
      {"--top-p-temperature", "top_p_temperature", a.top_p_temperature},
      {"--max-tokens", "max_tokens", a.max_tokens},
      {"--max-faces", "max_faces", a.max_faces},
      {"--surface-tolerance", "surface_tolerance", a.surface_tolerance},
      {"--candidates", "candidates", a.candidates},
      {"--rows", "rows", a.rows},
      {"--face-tolerance", "face_tolerance", a.face_tolerance},
      {"--points", "point_count", a.n_points},
      {"--parallel", "parallel", a.batch.parallel}};
  for (const auto& [flag, name, value] : given) {
    if (app.count(flag) == 0) continue;
    const silk_status s = silk_param_check(name, value);
    if (s != SILK_OK)
      return Fail(s, std::string(flag) + ": " + silk_last_error(),
                  s == SILK_ERR_INVALID_ARGUMENT ? kExitUsage : kExitFail);
  }
  return kExitOk;
}

// --seed: an unsigned integer or "random"; false if neither.
bool ParseSeed(const std::string& text, uint64_t* seed) {
  if (text == "random") {
    std::random_device rd;
    *seed = (static_cast<uint64_t>(rd()) << 32) ^ rd();
    return true;
  }
  try {
    size_t used = 0;
    *seed = std::stoull(text, &used, 10);
    return used == text.size() && text[0] != '-';
  } catch (const std::exception&) {
    return false;
  }
}

// An enum option's value (its name checked by the option's IsMember); `unset` when not given.
int32_t OptionValue(silk_status (*from_name)(const char*, int32_t*), const std::string& name, int32_t unset) {
  return name.empty() ? unset : silk_cpp::EnumValue(from_name, name);
}

silk_generate_params ToParams(const Args& a, uint64_t seed) {
  silk_generate_params p = silk_generate_default_params();
  p.seed = seed;
  p.temperature = a.temperature;
  p.top_k = a.top_k;
  p.top_p = a.top_p;
  p.top_p_temperature = a.top_p_temperature;
  p.preprocessing = OptionValue(silk_preprocess_kind_from_name, a.preprocessing, SILK_MODEL_VALUE);
  p.raw_points = a.raw_points ? 1 : 0;
  p.max_tokens = a.max_tokens;
  p.max_faces = a.max_faces;
  p.holes = silk_cpp::EnumValue(silk_hole_policy_from_name, a.repair);
  p.point_count = a.n_points;
  p.surface_tolerance = a.surface_tolerance;
  p.candidates = a.candidates;
  p.rows = a.rows;
  p.orient = silk_cpp::EnumValue(silk_orientation_from_name, a.orient);
  p.face_guidance = OptionValue(silk_face_guidance_from_name, a.face_guidance, SILK_MODEL_VALUE);
  p.face_tolerance = a.face_tolerance;
  p.report_flags = a.trace_path.empty() ? 0 : SILK_GENERATE_RECORD_TRACE;
  return p;
}

silk_model_params ToModelParams(const Args& a) {
  silk_model_params mo = silk_model_default_params();
  mo.threads = a.threads;
  mo.decoder =
      a.int8 ? SILK_DECODER_INT8 : OptionValue(silk_decoder_precision_from_name, a.decoder, SILK_DECODER_DEFAULT);
  mo.kv_precision = OptionValue(silk_kv_precision_from_name, a.kv_precision, SILK_KV_DEFAULT);
  return mo;
}

silk_save_params ToSaveParams(const Args& a) {
  silk_save_params sp = silk_save_default_params();
  sp.part_colors = a.part_colors ? 1 : 0;
  return sp;
}

int Run(const Args& a, uint64_t seed) {
  silk_cpp::Model model = silk_cpp::Model::Load(a.model_dir, ToModelParams(a));
  silk_cpp::Mesh input = silk_cpp::Mesh::Load(a.input);
  const silk_model_info info = model.info();
  silk_generate_params p = ToParams(a, seed);
  if (!a.quiet) {
    // Sampling values not given on the command line are the model's (model.json "sampling").
    auto given = [](double v) { return v >= 0 ? std::to_string(v).substr(0, 6) : std::string("model"); };
    std::fprintf(
        stderr,
        "silkgen %s\n  input   %s (%s, %zu vertices, %zu faces)\n  output  %s\n  model   %s (%s, %d threads, "
        "%s decoder, %s KV)\n  seed %llu  temperature %s  top-k %s  top-p %s  max-tokens %d  max-faces %d  "
        "repair %s\n"
        "  points  %s\n  surface tolerance %d  candidates %s  rows %s  orient %s  face guidance %s (tolerance %s)\n",
        silk_version(), a.input.c_str(), input.is_point_cloud() ? "point cloud" : "mesh", input.vertex_count(),
        input.triangle_count(), a.output.empty() ? "(none)" : a.output.c_str(), a.model_dir.c_str(), info.config,
        info.threads, silk_decoder_precision_name(info.decoder), silk_kv_precision_name(info.kv_precision),
        static_cast<unsigned long long>(seed), given(a.temperature).c_str(),
        a.top_k >= 0 ? std::to_string(a.top_k).c_str() : "model", given(a.top_p).c_str(), a.max_tokens, a.max_faces,
        a.repair.c_str(),
        a.raw_points              ? "raw (used as given, model frame)"
        : a.preprocessing.empty() ? "the model's pre-processing"
                                  : a.preprocessing.c_str(),
        a.surface_tolerance, a.candidates >= 1 ? std::to_string(a.candidates).c_str() : "model",
        a.rows >= 1 ? std::to_string(a.rows).c_str() : "model", a.orient.c_str(),
        a.face_guidance.empty() ? "model" : a.face_guidance.c_str(), given(a.face_tolerance).c_str());
  }
  silkgen::ProgressBar bar(!a.quiet);
  p.progress = [](const silk_generate_progress* g, void* user) {
    static_cast<silkgen::ProgressBar*>(user)->Update(*g);
  };
  p.cancel = [](void*) -> int32_t { return silkapp::InterruptSignal() != 0 ? 1 : 0; };
  p.user_data = &bar;
  silk_cpp::Generator generator(model);
  silk_generate_input in = silk_cpp::Sized<silk_generate_input>();
  in.mesh = input.get();
  silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
  std::vector<int32_t> ids;
  silk_cpp::Mesh result = generator.Generate(in, p, &st, &ids);
  bar.Finish();

  if (!a.output.empty()) result.Save(a.output, ToSaveParams(a));
  if (!a.tokens_path.empty()) silk_cpp::Tokens::FromIds(ids).Save(a.tokens_path);
  if (!a.save_points.empty()) WriteTextFile(a.save_points, PointsPly(generator.Points()));
  if (!a.trace_path.empty()) WriteTextFile(a.trace_path, generator.ReportJson(true));
  if (!a.stats_path.empty()) WriteTextFile(a.stats_path, generator.ReportJson(false));
  if (!a.quiet)
    std::fprintf(stderr,
                 "silkgen: %lld tokens (%s, %.0f%% forced) -> %d faces, %d part(s); %.1f tok/s, %.2f s total; "
                 "edge-manifold %s, vertex-manifold %s, oriented %s, watertight %s\n",
                 static_cast<long long>(st.tokens), silk_stop_reason_name(st.stop_reason),
                 st.tokens ? 100.0 * st.forced_tokens / st.tokens : 0.0, st.faces, st.components, st.tokens_per_second,
                 st.seconds_total, st.edge_manifold ? "yes" : "no", st.vertex_manifold ? "yes" : "no",
                 st.consistently_oriented ? "yes" : "no", st.watertight ? "yes" : "no");
  if (!a.quiet && st.parts_flipped > 0)
    std::fprintf(stderr,
                 "silkgen: %d surface patch(es) reversed to face the input's normals (--orient tokens keeps the ids' "
                 "winding)\n",
                 st.parts_flipped);
  if (!a.quiet && (st.candidates > 1 || st.guided_tokens > 0))
    std::fprintf(stderr,
                 "silkgen: candidate %d of %d written (Chamfer %.4f); guidance: %lld vertex ids, %lld fallbacks\n",
                 st.chosen_candidate + 1, st.candidates, st.score, static_cast<long long>(st.guided_tokens),
                 static_cast<long long>(st.guidance_fallbacks));
  if (!a.quiet && st.face_guided_tokens > 0)
    std::fprintf(stderr,
                 "silkgen: face guidance: %lld between-layer ids, %lld fallbacks (no legal id's faces on the input)\n",
                 static_cast<long long>(st.face_guided_tokens), static_cast<long long>(st.face_fallbacks));
  return kExitOk;
}

// --seed parsed and the bundled model found when --model is not given (kExitOk or the exit status).
int SeedAndModel(Args& a, uint64_t* seed) {
  if (!ParseSeed(a.seed_text, seed)) {
    return Fail(SILK_ERR_INVALID_ARGUMENT, "--seed: '" + a.seed_text + "' is neither an unsigned integer nor 'random'",
                kExitUsage);
  }
  try {
    a.model_dir = silk_cpp::FindModel(a.model_dir);  // "" = the bundled model; a name = the models folder's
  } catch (const silk_cpp::Error& e) {
    return Fail(e.status(), e.message() + "; pass --model DIR or NAME (silkgen --list-models)");
  }
  return kExitOk;
}

// Settings that can be checked before any work: the output names (format, what the file system
// holds) and the rule that no output is the input or another output (common/file_roles.h).
int CheckOutputs(const Args& a) {
  if (!a.output.empty())
    if (std::string e = CheckOutputFormat(a.output); !e.empty()) return Fail(SILK_ERR_INVALID_ARGUMENT, e);
  if (!a.save_points.empty() && !EndsWithPly(a.save_points))
    return Fail(SILK_ERR_INVALID_ARGUMENT,
                a.save_points + ": --save-points writes a PLY point cloud (use a .ply name)");
  silkapp::FileRoles roles;
  roles.Reads(a.input, "the input");
  const std::pair<const char*, const std::string*> outputs[] = {{"-o", &a.output},
                                                                {"--tokens", &a.tokens_path},
                                                                {"--stats", &a.stats_path},
                                                                {"--save-points", &a.save_points},
                                                                {"--trace", &a.trace_path}};
  for (const auto& [option, path] : outputs) {
    if (path->empty()) continue;
    roles.Writes(*path, option);
    try {
      silk_cpp::CheckOutputPath(*path);
    } catch (const silk_cpp::Error& e) {
      return Fail(e.status(), option + std::string(" ") + e.message());
    }
  }
  if (std::string e = roles.Check(); !e.empty()) return Fail(SILK_ERR_INVALID_ARGUMENT, e);
  return kExitOk;
}

// silkgen --batch: the single run's settings for every input (batch_run.h); per-input side files are refused.
int Batch(Args& a) {
  if (!a.input.empty() || a.output.empty() || !a.tokens_path.empty() || !a.stats_path.empty() ||
      !a.trace_path.empty() || !a.save_points.empty()) {
    return Fail(SILK_ERR_INVALID_ARGUMENT,
                "--batch LIST_OR_DIR takes -o OUTDIR and no input file, --tokens, --stats, "
                "--trace or --save-points (the report holds each input's figures)",
                kExitUsage);
  }
  silkgen::BatchSettings s;
  if (int rc = SeedAndModel(a, &s.seed); rc != kExitOk) return rc;
  s.model_dir = a.model_dir;
  s.output_dir = a.output;
  s.model = ToModelParams(a);
  s.generate = ToParams(a, s.seed);
  s.save = ToSaveParams(a);
  s.quiet = a.quiet;
  return silkgen::RunBatch(a.batch, s);
}

}  // namespace

int main(int argc, char** argv) {
  silkapp::UseUtf8Arguments(argc, argv);  // Windows: UTF-8, not the ANSI code page
  CLI::App app{"silkgen — generate a mesh from a point cloud or a mesh (Mesh Silksong, grammar-constrained)"};
  app.set_version_flag("--version", silk_version());
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);  // later options win
  Args a;
  AddOptions(app, a);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  if (a.int8)  // deprecated (silk.h: silk_model_info.int8 and this option go in 2.0); also with -q
    std::fputs("silkgen: note: --int8 is deprecated and removed in 2.0; use --decoder int8\n", stderr);
  try {
    a.batch.shard_given = app.count("--shard") > 0;
    a.batch.report_given = app.count("--report") > 0;
    if (a.list_models) {
      std::fputs(silkgen::ModelListText(silk_cpp::ModelsListJson()).c_str(), stdout);
      return kExitOk;
    }
    if (int rc = CheckSettings(app, a); rc != kExitOk) return rc;
    if (app.count("--batch")) return Batch(a);
  } catch (const silk_cpp::Error& e) {
    return Fail(e);
  }
  for (const char* only : {"--format", "--shard", "--report", "--parallel", "--overwrite"})
    if (app.count(only)) return Fail(SILK_ERR_INVALID_ARGUMENT, std::string(only) + " is a --batch option", kExitUsage);
  if (a.input.empty())
    return Fail(SILK_ERR_INVALID_ARGUMENT, "give an input file (or --batch LIST_OR_DIR); --help lists the options",
                kExitUsage);
  if (a.output.empty() && a.tokens_path.empty())
    return Fail(SILK_ERR_INVALID_ARGUMENT, "give -o/--output (a mesh) or --tokens (the ids), or both", kExitUsage);
  if (int rc = CheckOutputs(a); rc != kExitOk) return rc;
  uint64_t seed = 0;
  if (int rc = SeedAndModel(a, &seed); rc != kExitOk) return rc;
  silkapp::HandleInterrupts(silkapp::OnInterrupt::kCancel);
  try {
    return Run(a, seed);
  } catch (const silk_cpp::Error& e) {
    return Fail(e);
  }
}
