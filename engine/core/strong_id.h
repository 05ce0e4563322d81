// SPDX-License-Identifier: MIT
// Strong index types: a vertex id, a face id and a layer-local position cannot be mixed up
// by accident where they meet (non-manifold splitting, layering, decoding).
#pragma once
#include <cstdint>
#include <functional>

namespace silk {

template <typename Tag>
struct StrongId {
  int32_t v = -1;
  constexpr StrongId() = default;
  constexpr explicit StrongId(int32_t x) : v(x) {}
  constexpr bool valid() const { return v >= 0; }
  constexpr int32_t get() const { return v; }
  friend constexpr bool operator==(StrongId a, StrongId b) { return a.v == b.v; }
  friend constexpr bool operator!=(StrongId a, StrongId b) { return a.v != b.v; }
  friend constexpr bool operator<(StrongId a, StrongId b) { return a.v < b.v; }
  friend constexpr bool operator>(StrongId a, StrongId b) { return a.v > b.v; }
  friend constexpr bool operator<=(StrongId a, StrongId b) { return a.v <= b.v; }
};

struct VertexTag {};
struct FaceTag {};
struct ComponentTag {};
using VertexId = StrongId<VertexTag>;  // processed vertex index (token_format.md §2.3, §3.6)
using FaceId = StrongId<FaceTag>;      // processed face index (token_format.md §2.4)
using ComponentId = StrongId<ComponentTag>;

}  // namespace silk

template <typename Tag>
struct std::hash<silk::StrongId<Tag>> {
  size_t operator()(silk::StrongId<Tag> id) const noexcept { return std::hash<int32_t>()(id.v); }
};
