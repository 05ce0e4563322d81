// SPDX-License-Identifier: MIT
// GLB header and chunk parsing (little-endian u32 fields), all lengths bounds-checked.
#include "io/gltf/glb_container.h"

#include <cstdint>

#include "io/read_error.h"

namespace silk {

namespace {
uint32_t U32(std::string_view d, size_t off) {
  const auto* p = reinterpret_cast<const uint8_t*>(d.data()) + off;
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}
constexpr uint32_t kJsonChunk = 0x4E4F534A;
constexpr uint32_t kBinChunk = 0x004E4942;
}  // namespace

StatusOr<GlbChunks> ParseGlbContainer(std::string_view data, const std::string& name) {
  if (data.size() < 4 || data.substr(0, 4) != "glTF") return ParseErrorIn(name, "not a GLB file (no 'glTF' magic)");
  if (data.size() < 20) return ParseErrorIn(name, "GLB file shorter than its 20-byte header");
  const uint32_t version = U32(data, 4);
  if (version != 2) return Unsupported(name + ": GLB version " + std::to_string(version) + " (only 2 is supported)");
  const uint64_t length = U32(data, 8);
  if (length > data.size())
    return ParseErrorIn(
        name, "GLB header says " + std::to_string(length) + " bytes but the file has " + std::to_string(data.size()));
  if (length < 20) return ParseErrorIn(name, "GLB header length " + std::to_string(length) + " is too small");
  const uint64_t json_len = U32(data, 12);
  if (U32(data, 16) != kJsonChunk) return ParseErrorIn(name, "first GLB chunk is not JSON");
  if (json_len == 0 || 20 + json_len > length)
    return ParseErrorIn(name, "GLB JSON chunk length " + std::to_string(json_len) + " runs past the end");
  GlbChunks chunks;
  chunks.json = data.substr(20, json_len);
  const uint64_t off = 20 + json_len;
  if (off % 4 != 0) return ParseErrorIn(name, "GLB JSON chunk is not padded to a 4-byte boundary");
  if (off == length) return chunks;  // no BIN chunk
  if (off + 12 > length) return ParseErrorIn(name, "GLB data after the JSON chunk is too short for a BIN chunk");
  const uint64_t bin_len = U32(data, off);
  if (U32(data, off + 4) != kBinChunk) return ParseErrorIn(name, "second GLB chunk is not BIN");
  if (bin_len < 4 || bin_len % 4 != 0)
    return ParseErrorIn(name, "GLB BIN chunk length " + std::to_string(bin_len) + " is not a positive multiple of 4");
  if (off + 8 + bin_len > length)
    return ParseErrorIn(name, "GLB BIN chunk length " + std::to_string(bin_len) + " runs past the end");
  chunks.bin = data.substr(off + 8, bin_len);
  return chunks;
}

}  // namespace silk
