// Repair measured (spec §12.2): single 1-bits cleared in the self-layer (S window bit, X value)
// or between-layer (B window bit, row re-encoded) tokens of closed golden meshes; share of
// corrupted streams whose decoded mesh is watertight with hole policy off vs repair.
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "io/token_text.h"
#include "tokenizer/between_layer_cases.h"
#include "tokenizer/between_layer_decoder.h"
#include "tokenizer/between_layer_encoder.h"
#include "tokenizer/token_writer.h"

using namespace silk;

namespace {

struct Tally { int total = 0, accepted = 0, tight_off = 0, tight_repair = 0; };

void Measure(const LayeredStream& s, Tally* t) {
  const std::vector<int32_t> ids = WriteTokenStream(s);
  GrammarOptions go;
  go.max_length = 0;
  go.window_rule = WindowRule::kUnion;
  Grammar g(go);
  ++t->total;
  for (int32_t id : ids)
    if (!g.Accept(id).ok()) return;
  if (!g.CanEnd()) return;
  ++t->accepted;
  MeshBuildOptions off, rep;
  rep.holes = HolePolicy::kRepair;
  auto a = BuildMeshSoFar(g, off, nullptr);
  auto b = BuildMeshSoFar(g, rep, nullptr);
  if (a.ok() && IsWatertight(*a)) ++t->tight_off;
  if (b.ok() && IsWatertight(*b)) ++t->tight_repair;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "../shared/spec/golden";
  std::map<std::string, Tally> tallies;
  for (const char* name : {"cube", "tetrahedron", "octahedron", "icosphere2", "torus", "torus_12x8", "torus_24x6",
                           "cylinder_capped"}) {
    auto ids = ReadTokenText(dir + "/" + name + ".tokens.txt");
    if (!ids.ok()) {
      std::fprintf(stderr, "%s\n", ids.status().ToString().c_str());
      return 1;
    }
    GrammarOptions go;
    go.max_length = 0;
    Grammar g(go);
    for (int32_t id : *ids) (void)g.Accept(id);
    const LayeredStream base = g.stream();
    for (size_t c = 0; c < base.components.size(); ++c)
      for (size_t l = 1; l < base.components[c].layers.size(); ++l) {
        const auto& layer = base.components[c].layers[l];
        const int32_t prev_n = static_cast<int32_t>(base.components[c].layers[l - 1].vertices.size());
        for (size_t v = 0; v < layer.vertices.size(); ++v) {
          const auto& vx = layer.vertices[v];
          for (int bit = 0; bit < 8; ++bit)
            if ((vx.window >> bit) & 1) {
              LayeredStream s = base;
              s.components[c].layers[l].vertices[v].window &= ~(1 << bit);
              Measure(s, &tallies["S window bit"]);
            }
          for (size_t x = 0; x < vx.extras.size(); ++x) {
            LayeredStream s = base;
            auto& ex = s.components[c].layers[l].vertices[v].extras;
            ex.erase(ex.begin() + static_cast<long>(x));
            Measure(s, &tallies["X value"]);
          }
          if (l < 2) continue;  // layer-1 rows are the single root bit
          StreamLayer one;
          one.vertices.push_back(vx);
          auto pairs = DecodeBetweenLayer(one, prev_n);
          if (!pairs.ok() || pairs->size() < 2) continue;
          for (size_t drop = 0; drop < pairs->size(); ++drop) {
            std::vector<int32_t> cols;
            for (size_t k = 0; k < pairs->size(); ++k)
              if (k != drop) cols.push_back((*pairs)[k].second);
            LayeredStream s = base;
            auto& bt = s.components[c].layers[l].vertices[v].between;
            bt.clear();
            EncodeBetweenLayerRow(prev_n, cols, &bt);
            Measure(s, &tallies["B column"]);
          }
        }
      }
  }
  std::printf("%-14s %7s %9s %12s %15s\n", "corruption", "streams", "accepted", "tight(off)", "tight(repair)");
  for (const auto& [k, t] : tallies)
    std::printf("%-14s %7d %9d %5d (%4.1f%%) %7d (%4.1f%%)\n", k.c_str(), t.total, t.accepted, t.tight_off,
                100.0 * t.tight_off / std::max(1, t.total), t.tight_repair, 100.0 * t.tight_repair / std::max(1, t.total));
  return 0;
}
