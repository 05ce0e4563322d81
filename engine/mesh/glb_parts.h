// SPDX-License-Identifier: MIT
// A generated mesh as GLB parts: triangles grouped by their component, vertices re-indexed per
// part, smooth normals per part (parts do not smooth across each other), optional distinct
// colours. Shared by silk_mesh_save (.glb) and so by silkgen and every binding.
#pragma once
#include <cstdint>
#include <vector>

#include "io/gltf/glb_writer.h"
#include "io/io_mesh.h"

namespace silk {

// `triangle_component`: part index per triangle (missing entries count as part 0).
std::vector<GlbPart> SplitGlbParts(const IoMesh& mesh, const std::vector<int32_t>& triangle_component, bool colors);

}  // namespace silk
