// SPDX-License-Identifier: MIT
// Names of tokenizer refusals (token_format.md §14.A; the reference's messages are beside the enum).
#include "tokenizer/refusal.h"

#include <cstring>

namespace silk {
namespace {
struct Entry {
  Refusal r;
  const char* name;
};
constexpr Entry kEntries[] = {
    {Refusal::kNotTriangles, "not-triangles"},
    {Refusal::kEdgeGraphLimit, "nm-edge-graph-limit"},
    {Refusal::kStillDisconnectedFan, "nm-disconnected-fan"},
    {Refusal::kTooManyNonManifoldVerts, "nm-vertex-limit"},
    {Refusal::kNonManifoldWrong, "nm-partition-failed"},
    {Refusal::kPostNotManifold, "nm-post-not-manifold"},
    {Refusal::kMeetNonManifold, "non-manifold-edge"},
    {Refusal::kMobius, "mobius"},
    {Refusal::kVertexSharedByComponents, "vertex-shared-by-components"},
    {Refusal::kTooManyFaces, "face-limit"},
    {Refusal::kBoundaryVertex, "bad-boundary-vertex"},
    {Refusal::kLayerCountLimit, "layer-count-limit"},
    {Refusal::kNoFaces, "no-faces"},
    {Refusal::kLayerSizeLimit, "layer-size-limit"},
    {Refusal::kAllComponentsDropped, "all-components-dropped"},
};
}  // namespace

const char* RefusalName(Refusal r) {
  for (const auto& e : kEntries)
    if (e.r == r) return e.name;
  return "unknown";
}
Status Refuse(Refusal r, const std::string& detail) {
  std::string m = RefusalName(r);
  if (!detail.empty()) m += ": " + detail;
  return Status(StatusCode::kRefused, m);
}
bool RefusalFromStatus(const Status& s, Refusal* out) {
  if (s.code() != StatusCode::kRefused) return false;
  for (const auto& e : kEntries) {
    const size_t n = std::strlen(e.name);
    if (s.message().compare(0, n, e.name) == 0 && (s.message().size() == n || s.message()[n] == ':')) {
      if (out) *out = e.r;
      return true;
    }
  }
  return false;
}

}  // namespace silk
