// SPDX-License-Identifier: MIT
// Repair measured (token_format.md §12.2): single 1-bits cleared in the self-layer (S window bit, X value)
// or between-layer (B window bit, row re-encoded) tokens of closed meshes — the closed goldens
// and generated UV spheres, tori and capped cylinders of several sizes; share of corrupted
// streams whose decoded mesh is watertight with hole policy off vs repair, per corruption kind
// and per shape family.
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "decoder/mesh_builder.h"
#include "io/tokens/token_text.h"
#include "mesh/normalize.h"
#include "tokenizer/tokenizer.h"
#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/adjacency/between_layer_decoder.h"
#include "tokenizer/adjacency/between_layer_encoder.h"
#include "tokenizer/packing/token_writer.h"

using namespace silk;

namespace {

struct Tally {
  int total = 0, accepted = 0, tight_off = 0, tight_repair = 0;
};

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

constexpr double kPi = 3.14159265358979323846;

// Closed UV sphere: rings x segments quads plus two pole fans.
IoMesh Sphere(int rings, int segs) {
  IoMesh m;
  m.positions.push_back({0, 1, 0});
  for (int r = 1; r < rings; ++r)
    for (int k = 0; k < segs; ++k) {
      const double th = kPi * r / rings, ph = 2 * kPi * k / segs;
      m.positions.push_back({std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)});
    }
  m.positions.push_back({0, -1, 0});
  const int south = static_cast<int>(m.positions.size()) - 1;
  auto at = [&](int r, int k) { return 1 + (r - 1) * segs + (k % segs); };
  for (int k = 0; k < segs; ++k) m.triangles.push_back({0, at(1, k + 1), at(1, k)});
  for (int r = 1; r + 1 < rings; ++r)
    for (int k = 0; k < segs; ++k) {
      m.triangles.push_back({at(r, k), at(r, k + 1), at(r + 1, k + 1)});
      m.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r + 1, k)});
    }
  for (int k = 0; k < segs; ++k) m.triangles.push_back({south, at(rings - 1, k), at(rings - 1, k + 1)});
  return m;
}

// Torus with major radius 1, minor radius `minor`.
IoMesh Torus(int nu, int nv, double minor) {
  IoMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
      m.positions.push_back(
          {(1 + minor * std::cos(v)) * std::cos(u), minor * std::sin(v), (1 + minor * std::cos(v)) * std::sin(u)});
    }
  auto at = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// Capped cylinder: `rows` rings of `segs` vertices, fan caps around two centre vertices.
IoMesh Cylinder(int segs, int rows) {
  IoMesh m;
  for (int r = 0; r < rows; ++r)
    for (int k = 0; k < segs; ++k) {
      const double a = 2 * kPi * k / segs;
      m.positions.push_back({std::cos(a), 2.0 * r / (rows - 1) - 1.0, std::sin(a)});
    }
  const int bottom = static_cast<int>(m.positions.size());
  m.positions.push_back({0, -1, 0});
  m.positions.push_back({0, 1, 0});
  auto at = [&](int r, int k) { return r * segs + (k % segs); };
  for (int r = 0; r + 1 < rows; ++r)
    for (int k = 0; k < segs; ++k) {
      m.triangles.push_back({at(r, k), at(r + 1, k + 1), at(r, k + 1)});
      m.triangles.push_back({at(r, k), at(r + 1, k), at(r + 1, k + 1)});
    }
  for (int k = 0; k < segs; ++k) {
    m.triangles.push_back({bottom, at(0, k), at(0, k + 1)});
    m.triangles.push_back({bottom + 1, at(rows - 1, k + 1), at(rows - 1, k)});
  }
  return m;
}

// Every single-token corruption of one base stream (a window bit cleared, an extra dropped, a
// between-layer column dropped), each measured into the corruption's tally and its family's.
void CorruptAndMeasure(const std::string& family, const LayeredStream& base,
                       std::map<std::string, Tally>* tallies_out) {
  std::map<std::string, Tally>& tallies = *tallies_out;
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
            Measure(s, &tallies[family + " / S window bit"]);
          }
        for (size_t x = 0; x < vx.extras.size(); ++x) {
          LayeredStream s = base;
          auto& ex = s.components[c].layers[l].vertices[v].extras;
          ex.erase(ex.begin() + static_cast<long>(x));
          Measure(s, &tallies["X value"]);
          Measure(s, &tallies[family + " / X value"]);
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
          Measure(s, &tallies[family + " / B column"]);
        }
      }
    }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "../shared/spec/golden";
  std::map<std::string, Tally> tallies;
  // (family, stream) pairs: the closed goldens as official token files, then generated shapes
  // encoded by the tokenizer.
  std::vector<std::pair<std::string, LayeredStream>> bases;
  for (const char* name :
       {"cube", "tetrahedron", "octahedron", "icosphere2", "torus", "torus_12x8", "torus_24x6", "cylinder_capped"}) {
    auto ids = ReadTokenText(dir + "/" + name + ".tokens.txt");
    if (!ids.ok()) {
      std::fprintf(stderr, "%s\n", ids.status().ToString().c_str());
      return 1;
    }
    GrammarOptions go;
    go.max_length = 0;
    Grammar g(go);
    for (int32_t id : *ids) (void)g.Accept(id);
    bases.emplace_back("golden", g.stream());
  }
  std::vector<std::pair<std::string, IoMesh>> shapes;
  for (int n : {6, 10, 16}) shapes.emplace_back("sphere", Sphere(n, 2 * n));
  for (int n : {8, 12, 20}) shapes.emplace_back("torus", Torus(2 * n, n, 0.35));
  for (int n : {6, 12, 24}) shapes.emplace_back("cylinder", Cylinder(n, n / 2 + 2));
  for (const auto& [family, mesh] : shapes) {
    auto norm = NormalizeMesh(mesh);
    if (!norm.ok()) return 1;
    auto enc = EncodeMesh(*norm);
    if (!enc.ok()) {
      std::fprintf(stderr, "%s: %s\n", family.c_str(), enc.status().ToString().c_str());
      return 1;
    }
    bases.emplace_back(family, enc->stream);
  }
  for (const auto& [family, base] : bases) CorruptAndMeasure(family, base, &tallies);
  std::printf("%-26s %7s %9s %12s %15s\n", "corruption", "streams", "accepted", "tight(off)", "tight(repair)");
  for (const auto& [k, t] : tallies)
    std::printf("%-26s %7d %9d %5d (%4.1f%%) %7d (%4.1f%%)\n", k.c_str(), t.total, t.accepted, t.tight_off,
                100.0 * t.tight_off / std::max(1, t.total), t.tight_repair,
                100.0 * t.tight_repair / std::max(1, t.total));
  return 0;
}
