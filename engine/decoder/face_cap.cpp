// SPDX-License-Identifier: MIT
// The face cap on a built mesh (face_cap.h): a valid subset of at most max_faces faces.
#include "decoder/face_cap.h"

#include <algorithm>
#include <array>
#include <vector>

namespace silk {

namespace {

bool Contains(const std::vector<int32_t>& v, int32_t x) { return std::find(v.begin(), v.end(), x) != v.end(); }

// Indices of the faces kept: a face joins when, for each corner, the corner has no face yet or
// the face shares an edge with the corner's fan (its link gains an edge touching the link, so
// the link stays connected: one fan).
std::vector<size_t> KeptFaces(const TokenizerDecodedMesh& mesh, size_t max_faces) {
  std::vector<std::vector<int32_t>> link(mesh.positions.size());
  std::vector<size_t> kept;
  for (size_t i = 0; i < mesh.faces.size() && kept.size() < max_faces; ++i) {
    const auto& f = mesh.faces[i];
    bool joins = true;
    for (int k = 0; k < 3 && joins; ++k) {
      const std::vector<int32_t>& l = link[f[k]];
      joins = l.empty() || Contains(l, f[(k + 1) % 3]) || Contains(l, f[(k + 2) % 3]);
    }
    if (!joins) continue;
    for (int k = 0; k < 3; ++k)
      for (int j : {1, 2})
        if (!Contains(link[f[k]], f[(k + j) % 3])) link[f[k]].push_back(f[(k + j) % 3]);
    kept.push_back(i);
  }
  return kept;
}

}  // namespace

TokenizerDecodedMesh CapFaces(const TokenizerDecodedMesh& mesh, int32_t max_faces) {
  if (max_faces <= 0 || mesh.faces.size() <= static_cast<size_t>(max_faces)) return mesh;
  const std::vector<size_t> kept = KeptFaces(mesh, static_cast<size_t>(max_faces));
  std::vector<int32_t> vertex_of(mesh.positions.size(), -1);
  std::vector<int32_t> component_of(static_cast<size_t>(std::max(mesh.components, 0)), -1);
  for (size_t i : kept) {
    for (int32_t v : mesh.faces[i]) vertex_of[v] = 0;
    if (mesh.face_component[i] >= 0) component_of[mesh.face_component[i]] = 0;
  }
  TokenizerDecodedMesh out;
  for (int32_t& c : component_of)
    if (c == 0) c = out.components++;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (vertex_of[v] < 0) continue;
    vertex_of[v] = static_cast<int32_t>(out.positions.size());
    out.positions.push_back(mesh.positions[v]);
    const int32_t c = v < mesh.vertex_component.size() ? mesh.vertex_component[v] : -1;
    out.vertex_component.push_back(c >= 0 ? component_of[c] : -1);
  }
  for (size_t i : kept) {
    const auto& f = mesh.faces[i];
    out.faces.push_back({vertex_of[f[0]], vertex_of[f[1]], vertex_of[f[2]]});
    out.face_component.push_back(mesh.face_component[i] >= 0 ? component_of[mesh.face_component[i]] : -1);
  }
  return out;
}

}  // namespace silk
