// SPDX-License-Identifier: MIT
// Named refusals of the tokenizer: every input the reference rejects (token_format.md §14.A) is
// refused with one of these reasons, as a Status of code kRefused, never an exception.
#pragma once
#include <string>

#include "core/status.h"

namespace silk {

enum class Refusal {
  kNotTriangles,              // "only support triangles now"
  kEdgeGraphLimit,            // [NM] edge graph edges exceed limit (incident list > 50)
  kStillDisconnectedFan,      // [NM] still meet 1v2cc situation
  kTooManyNonManifoldVerts,   // [NM] NM_verts exceed limit (> 300)
  kNonManifoldWrong,          // non-manifold wrong: PARTITION groups do not cover the faces
  kPostNotManifold,           // [NM] post not manifold
  kMeetNonManifold,           // meet non-manifold: an edge with >= 3 faces after splitting
  kMobius,                    // mobius cycle topology (non-orientable)
  kVertexSharedByComponents,  // pre process non-manifold wrong
  kTooManyFaces,              // too many faces_p (> 12000)
  kBoundaryVertex,            // nonmanifold, pls checking preprocess
  kLayerCountLimit,           // reach layer limit 200
  kNoFaces,                   // no face survived cleanup (max() arg is an empty sequence)
  kLayerSizeLimit,            // [Encoder] max lv (> 200 vertices in a layer)
  kAllComponentsDropped,      // every component < 3 faces (ZeroDivisionError)
};

// Stable machine-readable name, e.g. "mobius".
const char* RefusalName(Refusal r);
// Status{kRefused, "<name>: <detail>"}.
Status Refuse(Refusal r, const std::string& detail = {});
// Parses the name back out of a refusal Status; false if s is not a refusal.
bool RefusalFromStatus(const Status& s, Refusal* out);

}  // namespace silk
