// SPDX-License-Identifier: MIT
// generate_unconstrained: one generation without the grammar mask, the official network's own
// loop (no public option does this: capi/capi_measurement.h), for the comparisons that need it:
// the official fixture's greedy ids (tests/tools/official_fixture_check.py), the imported network
// against Python's onnxruntime loop (export/tests), grammar on vs off (scripts/eval_dev_generation.sh).
// Everything else as silkgen: public API, the same report JSON (its "grammar" names the first id
// the grammar rejects; the mesh is the legal prefix).
//
//   generate_unconstrained INPUT [--model DIR] [--raw-points] [--seed S] [--temperature T]
//       [--max-tokens N] [--decoder fp32|int8|int4] [--kv-precision fp32|fp16|int8] [--threads N]
//       [--tokens FILE] [-o MESH] [--stats FILE]
#include <CLI/CLI.hpp>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "capi/capi_measurement.h"
#include "silk/silk.hpp"

namespace {

struct Args {
  std::string input, model, decoder, kv, tokens, output, stats;
  bool raw_points = false;
  uint64_t seed = 0;
  double temperature = SILK_MODEL_VALUE;
  int max_tokens = 0, threads = 0;
};

void AddOptions(CLI::App& app, Args& a) {
  app.add_option("input", a.input, "Mesh or point cloud (silkgen's formats)")->required();
  app.add_option("--model", a.model, "Model folder or name; default: the bundled model");
  app.add_flag("--raw-points", a.raw_points, "The input is the encoder's points as given (model frame)");
  app.add_option("--seed", a.seed, "Seed");
  app.add_option("--temperature", a.temperature, "0 = greedy; default: the model's")->check(CLI::Range(0.0, 100.0));
  app.add_option("--max-tokens", a.max_tokens, "Cap incl. EOS (0 = the model's)")->check(CLI::Range(0, 10240));
  app.add_option("--decoder", a.decoder, "fp32, int8 or int4")->check(CLI::IsMember({"fp32", "int8", "int4"}));
  app.add_option("--kv-precision", a.kv, "fp32, fp16 or int8")->check(CLI::IsMember({"fp32", "fp16", "int8"}));
  app.add_option("--threads", a.threads, "onnxruntime threads (0 = physical cores)")->check(CLI::Range(0, 1024));
  app.add_option("--tokens", a.tokens, "Write the ids, one per line");
  app.add_option("-o,--output", a.output, "Write the mesh (the legal prefix)");
  app.add_option("--stats", a.stats, "Write the report JSON");
}

// --decoder / --kv-precision (CLI11 checked the names) as silk_model_params.
silk_model_params ModelParams(const Args& a) {
  const std::map<std::string, int32_t> decoders = {{"", SILK_DECODER_DEFAULT},
                                                   {"fp32", SILK_DECODER_FP32},
                                                   {"int8", SILK_DECODER_INT8},
                                                   {"int4", SILK_DECODER_INT4}};
  const std::map<std::string, int32_t> caches = {
      {"", SILK_KV_DEFAULT}, {"fp32", SILK_KV_FP32}, {"fp16", SILK_KV_FP16}, {"int8", SILK_KV_INT8}};
  silk_model_params mo = silk_model_default_params();
  mo.threads = a.threads;
  mo.decoder = decoders.at(a.decoder);
  mo.kv_precision = caches.at(a.kv);
  return mo;
}

void Run(const Args& a) {
  silk_cpp::Model model = silk_cpp::Model::Load(a.model, ModelParams(a));
  silk_cpp::Mesh input = silk_cpp::Mesh::Load(a.input);
  silk_cpp::Generator generator(model);
  silk_cpp::Check(silk::capi::SetUnconstrained(generator.get(), true));
  silk_generate_params p = silk_generate_default_params();
  p.seed = a.seed;
  p.temperature = a.temperature;
  p.max_tokens = a.max_tokens;
  p.raw_points = a.raw_points ? 1 : 0;
  std::vector<int32_t> ids;
  silk_cpp::Mesh result = generator.Generate(input, p, nullptr, &ids);
  if (!a.tokens.empty()) silk_cpp::Tokens::FromIds(ids).Save(a.tokens);
  if (!a.output.empty()) result.Save(a.output);
  if (!a.stats.empty()) {
    const std::string json = generator.ReportJson(false);
    silk_cpp::Check(silk_file_write(a.stats.c_str(), json.data(), json.size()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"One generation without the grammar mask (measurement; see the file's comment)"};
  Args a;
  AddOptions(app, a);
  CLI11_PARSE(app, argc, argv);
  try {
    Run(a);
  } catch (const silk_cpp::Error& e) {
    std::fprintf(stderr, "generate_unconstrained: %s\n", e.what());
    return 1;
  }
  return 0;
}
