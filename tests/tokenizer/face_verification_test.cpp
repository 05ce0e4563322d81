// Face verification on the dev corpus: the official processed faces (minus unencodable ones)
// replay the encoder's layering per component; the recovered faces should score no worse.
// Reports how many components verify exactly, for the truth and for the decoder. The truth
// is mapped by coordinates, so coincident components and unencodable faces make its score > 0.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "face_compare.h"
#include "support/test_paths.h"
#include "tokenizer/face_recovery.h"
#include "tokenizer/face_verification.h"
#include "tokenizer/layer_adjacency.h"
#include "tokenizer/token_reader.h"

namespace silk {
namespace {

std::vector<std::string> OkNames() {
  std::ifstream in(testing::SharedPath("spec/golden-dev/INDEX.tsv"));
  std::vector<std::string> names;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string name, status;
    std::getline(ss, name, '\t');
    std::getline(ss, status, '\t');
    if (status == "ok") names.push_back(name);
  }
  return names;
}

std::tuple<int32_t, int32_t, int32_t> T(const QVec& q) { return {q.x, q.y, q.z}; }

TEST(GoldenDevVerifySlow, TruthReplaysAndRecoveryScoresNoWorse) {
  int comps = 0, truth_exact = 0, ours_exact = 0, worse = 0, truth_score = 0, ours_score = 0;
  for (const auto& name : OkNames()) {
    const std::string base = testing::SharedPath("spec/golden-dev/" + name);
    auto stream = ReadTokens(testing::ReadIds(base + ".tokens.txt"));
    ASSERT_TRUE(stream.ok());
    auto processed = testing::ReadCoordFaces(base + ".processed.txt");
    auto unencodable = testing::ReadCoordFaces(base + ".unencodable.txt");
    for (size_t ci = 0; ci < stream->components.size(); ++ci) {
      const StreamComponent& comp = stream->components[ci];
      ComponentLayers layers;
      int32_t prev = 0;
      for (size_t l = 0; l < comp.layers.size(); ++l) {
        std::vector<QVec> pos;
        for (const auto& v : comp.layers[l].vertices) pos.push_back(v.pos);
        if (l > 0) layers.adjacency.push_back(*DecodeLayerAdjacency(comp.layers[l], prev));
        prev = static_cast<int32_t>(pos.size());
        layers.layer_positions.push_back(pos);
      }
      auto g = BuildComponentGraph(layers);
      ASSERT_TRUE(g.ok());
      std::map<std::tuple<int32_t, int32_t, int32_t>, int32_t> id;
      std::map<std::tuple<int32_t, int32_t, int32_t>, int32_t> dup;
      for (int32_t v = 0; v < g->vertex_count; ++v) {
        ++dup[T(g->positions[v])];
        id[T(g->positions[v])] = v;
      }
      std::vector<std::array<int32_t, 3>> truth;
      for (const auto& f : processed) {
        bool bad = false;
        for (const auto& u : unencodable) bad = bad || u == f;
        std::array<int32_t, 3> t{};
        for (int k = 0; k < 3 && !bad; ++k) {
          auto it = id.find(T(f[k]));
          if (it == id.end() || dup[T(f[k])] > 1) bad = true;
          else t[k] = it->second;
        }
        if (!bad && g->EdgeOf(t[0], t[1]) >= 0 && g->EdgeOf(t[1], t[2]) >= 0 && g->EdgeOf(t[0], t[2]) >= 0)
          truth.push_back(t);
      }
      FaceRecoveryStats st;
      auto ours = RecoverFacesOfGraph(*g, &st);
      ASSERT_TRUE(ours.ok());
      const int ts = VerifyComponentFaces(*g, truth).Score();
      const int os = VerifyComponentFaces(*g, *ours).Score();
      ++comps;
      truth_exact += ts == 0;
      ours_exact += os == 0;
      truth_score += ts;
      ours_score += os;
      if (os > ts) {
        ++worse;
        std::printf("  %s comp %zu: truth score %d, recovered score %d (%d evaluations%s)\n", name.c_str(), ci, ts,
                    os, st.search_evaluations, st.search_budget_exhausted ? ", budget exhausted" : "");
      }
    }
  }
  std::printf("golden-dev verify: %d components; truth replays exactly in %d (defects %d), recovery in %d "
              "(defects %d); recovery worse than truth in %d\n",
              comps, truth_exact, truth_score, ours_exact, ours_score, worse);
  // Measured (docs/decoder.md): 8,997 components replay exactly; the search ends above
  // the truth's score in 4 components (a repair needs two simultaneous changes). Regression
  // bounds, not the goal (worse = 0).
  EXPECT_GE(ours_exact, 8997);
  EXPECT_LE(worse, 4);
}

}  // namespace
}  // namespace silk
