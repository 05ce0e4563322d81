// SPDX-License-Identifier: MIT
// Node traversal with explicit stack, TRS/matrix composition in double precision.
#include "io/gltf/gltf_scene_walk.h"

#include <cmath>

#include "io/read_error.h"

namespace silk {

namespace {

using Mat4 = std::array<double, 16>;  // column-major: m[col * 4 + row]

Mat4 Identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Mat4 Mul(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int rr = 0; rr < 4; ++rr) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + rr] * b[c * 4 + k];
      r[c * 4 + rr] = s;
    }
  return r;
}

StatusOr<Mat4> LocalMatrix(const tinygltf::Node& n, int index, const std::string& name) {
  const std::string who = "node " + std::to_string(index);
  auto finite = [](const std::vector<double>& v) {
    for (double x : v)
      if (!std::isfinite(x)) return false;
    return true;
  };
  if (!n.matrix.empty()) {
    if (n.matrix.size() != 16) return ParseErrorIn(name, who + ": matrix does not have 16 values");
    if (!finite(n.matrix)) return ParseErrorIn(name, who + ": non-finite matrix value");
    Mat4 m;
    for (int i = 0; i < 16; ++i) m[i] = n.matrix[i];
    return m;
  }
  Mat4 t = Identity(), r = Identity(), s = Identity();
  if (!n.translation.empty()) {
    if (n.translation.size() != 3 || !finite(n.translation))
      return ParseErrorIn(name, who + ": translation must be 3 finite values");
    t[12] = n.translation[0];
    t[13] = n.translation[1];
    t[14] = n.translation[2];
  }
  if (!n.rotation.empty()) {
    if (n.rotation.size() != 4 || !finite(n.rotation))
      return ParseErrorIn(name, who + ": rotation must be 4 finite values");
    const double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
    r[0] = 1 - 2 * (y * y + z * z);
    r[1] = 2 * (x * y + z * w);
    r[2] = 2 * (x * z - y * w);
    r[4] = 2 * (x * y - z * w);
    r[5] = 1 - 2 * (x * x + z * z);
    r[6] = 2 * (y * z + x * w);
    r[8] = 2 * (x * z + y * w);
    r[9] = 2 * (y * z - x * w);
    r[10] = 1 - 2 * (x * x + y * y);
  }
  if (!n.scale.empty()) {
    if (n.scale.size() != 3 || !finite(n.scale)) return ParseErrorIn(name, who + ": scale must be 3 finite values");
    s[0] = n.scale[0];
    s[5] = n.scale[1];
    s[10] = n.scale[2];
  }
  return Mul(t, Mul(r, s));
}

bool IsIdentity(const Mat4& m) { return m == Identity(); }

}  // namespace

StatusOr<std::vector<GltfMeshInstance>> CollectGltfMeshInstances(const tinygltf::Model& model,
                                                                 const std::string& name) {
  const int nnodes = static_cast<int>(model.nodes.size());
  std::vector<int> roots;
  if (model.defaultScene >= 0 || !model.scenes.empty()) {
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (s >= static_cast<int>(model.scenes.size()))
      return ParseErrorIn(name, "default scene " + std::to_string(s) + " does not exist");
    roots = model.scenes[s].nodes;
  } else {
    std::vector<bool> is_child(nnodes, false);
    for (const tinygltf::Node& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && c < nnodes) is_child[c] = true;
    for (int i = 0; i < nnodes; ++i)
      if (!is_child[i]) roots.push_back(i);
  }

  struct Item {
    int node;
    int parent;
    Mat4 parent_matrix;
  };
  std::vector<Item> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, -1, Identity()});
  std::vector<bool> visited(nnodes, false);
  std::vector<GltfMeshInstance> out;
  while (!stack.empty()) {
    Item item = stack.back();
    stack.pop_back();
    const std::string parent = item.parent < 0 ? "scene" : "node " + std::to_string(item.parent);
    if (item.node < 0 || item.node >= nnodes)
      return ParseErrorIn(name, parent + " refers to node " + std::to_string(item.node) + ", which does not exist (" +
                                    std::to_string(nnodes) + " nodes)");
    if (visited[item.node])
      return ParseErrorIn(name, "node graph is not a tree: node " + std::to_string(item.node) +
                                    " is reached twice (from " + parent + "; cycle or shared child)");
    visited[item.node] = true;
    const tinygltf::Node& n = model.nodes[item.node];
    SILK_ASSIGN_OR_RETURN(Mat4 local, LocalMatrix(n, item.node, name));
    Mat4 world = IsIdentity(local)                ? item.parent_matrix
                 : IsIdentity(item.parent_matrix) ? local
                                                  : Mul(item.parent_matrix, local);
    if (n.mesh >= 0) {
      if (n.mesh >= static_cast<int>(model.meshes.size()))
        return ParseErrorIn(name, "node " + std::to_string(item.node) + " refers to mesh " + std::to_string(n.mesh) +
                                      ", which does not exist");
      out.push_back({n.mesh, item.node, world});
    }
    for (auto it = n.children.rbegin(); it != n.children.rend(); ++it) stack.push_back({*it, item.node, world});
  }
  return out;
}

}  // namespace silk
