// SPDX-License-Identifier: MIT
// Shared fixtures of the runtime tests: the committed tiny model (tests/models/tiny) and
// encoder points sampled from the repository's sample mesh.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "io/mesh_reader.h"
#include "runtime/generation_input.h"
#include "runtime/model/model.h"
#include "support/test_paths.h"

namespace silk::testing {

inline std::string TinyModelDir() { return SourcePath("tests/models/tiny"); }

inline std::unique_ptr<Model> LoadTinyModel(int threads = 1, KvPrecision kv = KvPrecision::kFp32) {
  ModelLoadOptions o;
  o.threads = threads;
  o.kv = kv;
  auto m = Model::Load(TinyModelDir(), o);
  if (!m.ok()) return nullptr;
  return std::move(*m);
}

inline GenerationInput SampleMeshInput() {
  GenerationInput in;
  auto m = ReadMeshFile(SourcePath("samples/torus_knot.obj"));
  if (m.ok()) in.mesh = std::move(*m);
  return in;
}

inline std::vector<float> SamplePoints(const Model& model, uint64_t seed = 1) {
  auto p = PrepareModelPoints(SampleMeshInput(), ModelPreprocessing(model.config()), seed);
  return p.ok() ? p->rows : std::vector<float>{};
}

}  // namespace silk::testing
