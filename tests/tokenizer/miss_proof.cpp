// SPDX-License-Identifier: MIT
// Missed-face listing and token-equivalence proof per component; see miss_proof.h.
#include "miss_proof.h"

#include <map>
#include <tuple>

#include "token_equivalence.h"
#include "truth_mapping.h"

namespace silk::testing {
namespace {

using Coord = std::tuple<int32_t, int32_t, int32_t>;
using FaceKey = std::array<Coord, 3>;

Coord C(const QVec& q) { return {q.x, q.y, q.z}; }
// Same corners in the same cyclic order = same key.
FaceKey Canon(const QVec& a, const QVec& b, const QVec& c) {
  FaceKey k{C(a), C(b), C(c)};
  int m = 0;
  for (int i = 1; i < 3; ++i)
    if (k[i] < k[m]) m = i;
  return {k[m], k[(m + 1) % 3], k[(m + 2) % 3]};
}

}  // namespace

std::vector<CoordFace> RepresentableFaces(const std::vector<CoordFace>& processed,
                                          const std::vector<CoordFace>& unencodable) {
  std::set<FaceKey> excluded;
  for (const auto& f : unencodable) excluded.insert(Canon(f[0], f[1], f[2]));
  std::vector<CoordFace> out;
  for (const auto& f : processed)
    if (!excluded.count(Canon(f[0], f[1], f[2]))) out.push_back(f);
  return out;
}

std::vector<MissedFace> MissedFaces(const std::vector<CoordFace>& decoded, const std::vector<CoordFace>& target) {
  std::set<FaceKey> got;
  for (const auto& f : decoded) got.insert(Canon(f[0], f[1], f[2]));
  std::vector<MissedFace> out;
  for (const auto& f : target) {
    if (got.count(Canon(f[0], f[1], f[2]))) continue;
    out.push_back({f, got.count(Canon(f[0], f[2], f[1])) > 0});
  }
  return out;
}

std::vector<char> ComponentsReencoding(const TokenizerDecodedMesh& mesh, const LayeredStream& stream,
                                       const std::vector<CoordFace>& order_reference) {
  const size_t n = static_cast<size_t>(mesh.components);
  std::vector<int32_t> base(n + 1, 0);
  for (int32_t c : mesh.vertex_component) ++base[static_cast<size_t>(c) + 1];
  for (size_t c = 0; c < n; ++c) base[c + 1] += base[c];
  std::vector<std::vector<std::array<int32_t, 3>>> faces(n);
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const int32_t c = mesh.face_component[i], b = base[static_cast<size_t>(c)];
    faces[static_cast<size_t>(c)].push_back({mesh.faces[i][0] - b, mesh.faces[i][1] - b, mesh.faces[i][2] - b});
  }
  std::vector<char> out(n, 0);
  for (size_t c = 0; c < n && c < stream.components.size(); ++c) {
    std::vector<QVec> pos(mesh.positions.begin() + base[c], mesh.positions.begin() + base[c + 1]);
    out[c] = ComponentReencodesTo(pos, faces[c], order_reference, stream.components[c]);
  }
  return out;
}

std::set<int32_t> ComponentsAtCorners(const TokenizerDecodedMesh& mesh, const CoordFace& f) {
  std::set<int32_t> at[3];
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    for (int k = 0; k < 3; ++k)
      if (mesh.positions[v] == f[k]) at[k].insert(mesh.vertex_component[v]);
  std::set<int32_t> out;
  for (int32_t c : at[0])
    if (at[1].count(c) && at[2].count(c)) out.insert(c);
  return out;
}

bool MissIsProvenAmbiguous(const TokenizerDecodedMesh& mesh, const std::vector<char>& reencoding, const CoordFace& f) {
  const std::set<int32_t> cs = ComponentsAtCorners(mesh, f);
  bool proven = !cs.empty();
  for (int32_t c : cs) proven = proven && reencoding[static_cast<size_t>(c)];
  return proven;
}

AugmentedReencoding ComponentsReencodingWithUnencodable(const TokenizerDecodedMesh& mesh, const LayeredStream& stream,
                                                        const std::vector<CoordFace>& processed,
                                                        const std::vector<CoordFace>& unencodable,
                                                        const std::vector<CoordFace>& order_reference) {
  const size_t n = static_cast<size_t>(mesh.components);
  AugmentedReencoding out{std::vector<char>(n, 0), std::vector<char>(n, 0), std::vector<char>(n, 0)};
  if (unencodable.empty()) return out;
  // Component vertex ranges and our faces in component-local ids (as ComponentsReencoding).
  std::vector<int32_t> base(n + 1, 0);
  for (int32_t c : mesh.vertex_component) ++base[static_cast<size_t>(c) + 1];
  for (size_t c = 0; c < n; ++c) base[c + 1] += base[c];
  std::vector<std::vector<std::array<int32_t, 3>>> ours(n);
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const int32_t c = mesh.face_component[i], b = base[static_cast<size_t>(c)];
    ours[static_cast<size_t>(c)].push_back({mesh.faces[i][0] - b, mesh.faces[i][1] - b, mesh.faces[i][2] - b});
  }
  for (size_t c = 0; c < n && c < stream.components.size(); ++c) {
    std::map<Coord, int> count;  // grid coordinate -> vertices of this component there
    for (int32_t v = base[c]; v < base[c + 1]; ++v) ++count[C(mesh.positions[static_cast<size_t>(v)])];
    std::vector<CoordFace> touching;
    bool ambiguous = false;
    for (const auto& f : unencodable) {
      bool touches = false;
      for (const auto& q : f) {
        auto it = count.find(C(q));
        touches = touches || it != count.end();
        ambiguous = ambiguous || (it != count.end() && it->second > 1);
      }
      if (touches) touching.push_back(f);
    }
    if (touching.empty() || ambiguous) continue;
    auto g = BuildComponentGraph(LayersOfComponent(stream.components[c]));
    if (!g.ok()) continue;
    // Map the touching faces by grid coordinate (each corner unique in the component, checked
    // above). Not TruthOnGraph: that also requires the three edges in the graph, and the edges
    // of unencodable faces are typically exactly the ones the tokens do not carry.
    std::map<Coord, int32_t> id;
    for (int32_t v = base[c]; v < base[c + 1]; ++v) id[C(mesh.positions[static_cast<size_t>(v)])] = v - base[c];
    std::vector<std::array<int32_t, 3>> extra;
    for (const auto& f : touching) {
      std::array<int32_t, 3> t{};
      bool whole = true;
      for (int k = 0; k < 3 && whole; ++k) {
        auto it = id.find(C(f[k]));
        whole = it != id.end();
        if (whole) t[k] = it->second;
      }
      if (!whole) break;  // a corner outside this component: ambiguous, skip it
      extra.push_back(t);
    }
    if (extra.size() != touching.size()) continue;
    out.checked[c] = 1;
    const std::vector<QVec> pos(mesh.positions.begin() + base[c], mesh.positions.begin() + base[c + 1]);
    auto with_extra = [&](std::vector<std::array<int32_t, 3>> faces) {
      faces.insert(faces.end(), extra.begin(), extra.end());
      return ComponentReencodesTo(pos, faces, order_reference, stream.components[c]);
    };
    // Soundness: the official faces of this component (coordinate-mapped, unencodable ones
    // excluded and re-added above) must give the input tokens, else the method says nothing here.
    out.truth_equal[c] = with_extra(TruthOnGraph(*g, processed, unencodable));
    out.ours_equal[c] = with_extra(ours[c]);
  }
  return out;
}

}  // namespace silk::testing
