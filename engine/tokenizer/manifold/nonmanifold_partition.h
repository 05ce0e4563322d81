// SPDX-License-Identifier: MIT
// PARTITION(v) of token_format.md §3.4: splits the faces around one non-manifold vertex into fans
// (cycles, chains and single faces) exactly as the reference's NM_process_one does.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "core/strong_id.h"
#include "tokenizer/manifold/union_find.h"

namespace silk {

// faces: current faces as raw vertex ids; incident: list_v (token_format.md §3.4 step 1, duplicates
// allowed); face_cc / uf: the pass-B face components (SELECT_CYCLE rule 1).
// On success `groups` holds every face of v exactly once; group 0 keeps v.
Status PartitionNonManifoldFan(const std::vector<std::array<int32_t, 3>>& faces, int32_t v,
                               const std::vector<int32_t>& incident, const std::vector<int32_t>& face_cc, UnionFind& uf,
                               std::vector<std::vector<FaceId>>* groups);

}  // namespace silk
