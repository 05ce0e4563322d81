// SPDX-License-Identifier: MIT
// Face comparison helper for the decoder tests (see face_compare.h).
#include "face_compare.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace silk::testing {
namespace {

using Key = std::array<int32_t, 9>;
std::array<int32_t, 3> T(const QVec& q) { return {q.x, q.y, q.z}; }

Key Flat(const CoordFace& f) {
  Key k{};
  for (int i = 0; i < 3; ++i) {
    k[3 * i] = f[i].x;
    k[3 * i + 1] = f[i].y;
    k[3 * i + 2] = f[i].z;
  }
  return k;
}
// Rotation with the smallest (x, y, z) corner first: the canonical oriented form.
Key Oriented(const CoordFace& f) {
  int m = 0;
  for (int i = 1; i < 3; ++i) {
    if (T(f[i]) < T(f[m])) m = i;
  }
  return Flat({f[m], f[(m + 1) % 3], f[(m + 2) % 3]});
}
Key Reversed(const CoordFace& f) { return Oriented({f[0], f[2], f[1]}); }
using EdgeKey = std::pair<std::array<int32_t, 3>, std::array<int32_t, 3>>;
EdgeKey Edge(const QVec& a, const QVec& b) {
  auto x = T(a), y = T(b);
  if (y < x) std::swap(x, y);
  return {x, y};
}

}  // namespace

std::vector<int32_t> ReadIds(const std::string& path) {
  std::ifstream in(path);
  std::vector<int32_t> ids;
  int64_t v;
  while (in >> v) ids.push_back(static_cast<int32_t>(v));
  return ids;
}

std::vector<CoordFace> ReadCoordFaces(const std::string& path) {
  std::ifstream in(path);
  std::vector<CoordFace> faces;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    CoordFace f;
    if (ls >> f[0].x >> f[0].y >> f[0].z >> f[1].x >> f[1].y >> f[1].z >> f[2].x >> f[2].y >> f[2].z) {
      faces.push_back(f);
    }
  }
  return faces;
}

std::vector<CoordFace> FacesAsCoords(const TokenizerDecodedMesh& mesh) {
  std::vector<CoordFace> out;
  for (const auto& f : mesh.faces) out.push_back({mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]});
  return out;
}

FaceComparison CompareFaces(const std::vector<CoordFace>& decoded, const std::vector<CoordFace>& target) {
  FaceComparison r;
  std::set<Key> want, got, got_rev;
  std::map<EdgeKey, int> target_edge_faces;
  for (const auto& f : target) {
    want.insert(Oriented(f));
    for (int i = 0; i < 3; ++i) ++target_edge_faces[Edge(f[i], f[(i + 1) % 3])];
  }
  r.target = static_cast<int64_t>(want.size());
  for (const auto& f : decoded) {
    got.insert(Oriented(f));
    got_rev.insert(Reversed(f));
  }
  for (const Key& k : want) {
    if (got.count(k))
      ++r.recovered;
    else if (got_rev.count(k))
      ++r.reversed;
    else
      ++r.missing;
  }
  std::set<Key> want_rev;
  for (const auto& f : target) want_rev.insert(Reversed(f));
  for (const auto& f : decoded) {
    const Key k = Oriented(f);
    if (want.count(k) || want_rev.count(k)) continue;
    bool hole = true;
    for (int i = 0; i < 3; ++i) {
      auto it = target_edge_faces.find(Edge(f[i], f[(i + 1) % 3]));
      if (it == target_edge_faces.end() || it->second != 1) hole = false;
    }
    if (hole)
      ++r.extra_hole;
    else
      ++r.extra_other;
  }
  return r;
}

std::string CheckManifoldOriented(const TokenizerDecodedMesh& mesh) {
  std::map<std::pair<int32_t, int32_t>, int> undirected, directed;
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const auto& f = mesh.faces[i];
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) return "face " + std::to_string(i) + " is degenerate";
    for (int k = 0; k < 3; ++k) {
      const int32_t a = f[k], b = f[(k + 1) % 3];
      if (++directed[{a, b}] > 1) {
        return "directed edge " + std::to_string(a) + "->" + std::to_string(b) + " used twice";
      }
      if (++undirected[{std::min(a, b), std::max(a, b)}] > 2) {
        return "edge " + std::to_string(a) + "-" + std::to_string(b) + " has 3 faces";
      }
    }
  }
  return "";
}

}  // namespace silk::testing
