// SPDX-License-Identifier: MIT
// DecodeTokens: ids -> LayeredStream (token_reader) -> per component, the shared assembly
// (component_mesh: adjacency, face recovery) -> one mesh in reading order. Faithful: nothing is
// split or filled (the decoder's BuildMesh adds the hole and vertex-fan rules on the same path).
#include <string>

#include "tokenizer/component_mesh.h"
#include "tokenizer/packing/token_reader.h"
#include "tokenizer/tokenizer.h"

namespace silk {

StatusOr<TokenizerDecodedMesh> DecodeTokens(const std::vector<int32_t>& ids, const DecodeOptions& options) {
  if (options.official_faces) {
    return Unsupported("the official decoder's face rule (token_format.md §10.3) is not implemented");
  }
  SILK_ASSIGN_OR_RETURN(LayeredStream stream, ReadTokens(ids));
  TokenizerDecodedMesh mesh;
  for (size_t ci = 0; ci < stream.components.size(); ++ci) {
    auto cm = AssembleComponentMesh(stream.components[ci]);
    if (!cm.ok()) return cm.status().WithContext("component " + std::to_string(ci) + ", ");
    AppendComponentMesh(*cm, static_cast<int32_t>(ci), &mesh);
  }
  mesh.components = static_cast<int32_t>(stream.components.size());
  return mesh;
}

}  // namespace silk
