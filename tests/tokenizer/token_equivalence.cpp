// SPDX-License-Identifier: MIT
// Token-equivalence check for decoded face sets (see token_equivalence.h).
#include "token_equivalence.h"

#include <algorithm>
#include <map>
#include <tuple>

#include "tokenizer/processed_encoder.h"
#include "tokenizer/packing/token_writer.h"

namespace silk::testing {
namespace {
using Key = std::array<std::tuple<int32_t, int32_t, int32_t>, 3>;
Key Unordered(const CoordFace& f) {
  Key k{std::make_tuple(f[0].x, f[0].y, f[0].z), std::make_tuple(f[1].x, f[1].y, f[1].z),
        std::make_tuple(f[2].x, f[2].y, f[2].z)};
  std::sort(k.begin(), k.end());
  return k;
}
}  // namespace

std::vector<size_t> OrderLike(const std::vector<CoordFace>& faces, const std::vector<CoordFace>& reference) {
  std::map<Key, size_t> rank;
  for (size_t i = 0; i < reference.size(); ++i) rank.emplace(Unordered(reference[i]), i);
  std::vector<std::pair<size_t, size_t>> order;
  for (size_t i = 0; i < faces.size(); ++i) {
    auto it = rank.find(Unordered(faces[i]));
    order.push_back({it == rank.end() ? reference.size() + i : it->second, i});
  }
  std::sort(order.begin(), order.end());
  std::vector<size_t> out;
  for (const auto& o : order) out.push_back(o.second);
  return out;
}

bool ComponentReencodesTo(const std::vector<QVec>& positions, const std::vector<std::array<int32_t, 3>>& faces,
                          const std::vector<CoordFace>& order_reference, const StreamComponent& want) {
  std::vector<CoordFace> coords;
  for (const auto& f : faces) coords.push_back({positions[f[0]], positions[f[1]], positions[f[2]]});
  TokenizerProcessedMesh mesh;
  mesh.positions = positions;
  mesh.input_vertex_count = static_cast<int32_t>(positions.size());
  for (size_t i : OrderLike(coords, order_reference)) {
    const auto& f = faces[i];
    mesh.faces.push_back({VertexId(f[0]), VertexId(f[1]), VertexId(f[2])});
  }
  auto stream = EncodeProcessedMesh(std::move(mesh));
  if (!stream.ok() || stream->components.size() != 1) return false;
  LayeredStream a, b;
  a.components.push_back(stream->components[0]);
  b.components.push_back(want);
  return WriteTokenStream(a) == WriteTokenStream(b);
}

}  // namespace silk::testing
