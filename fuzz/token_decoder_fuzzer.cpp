// SPDX-License-Identifier: MIT
// libFuzzer target for the tokens -> mesh direction: arbitrary id arrays must never crash,
// hang or allocate without bound in ReadTokenStream / DecodeTokens.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tokenizer/tokenizer.h"

namespace {

// Byte b < 0xF0 maps to a class-aware id so structured streams are reachable; 0xF0..0xFF
// starts a raw little-endian int32 (any value, including out-of-range ids).
std::vector<int32_t> IdsOf(const uint8_t* data, size_t size) {
  std::vector<int32_t> ids;
  static constexpr int32_t kBases[] = {0, 1, 2, 3, 203, 459, 5659, 6171};
  static constexpr int32_t kSpans[] = {1, 1, 1, 200, 256, 5200, 512, 4096};
  for (size_t i = 0; i < size;) {
    const uint8_t b = data[i++];
    if (b >= 0xF0 && i + 4 <= size) {
      int32_t v =
          static_cast<int32_t>(static_cast<uint32_t>(data[i]) | static_cast<uint32_t>(data[i + 1]) << 8 |
                               static_cast<uint32_t>(data[i + 2]) << 16 | static_cast<uint32_t>(data[i + 3]) << 24);
      i += 4;
      ids.push_back(v);
      continue;
    }
    const int cls = b & 7;
    int32_t off = b >> 3;
    if (kSpans[cls] > 32 && i < size) off = (off << 8 | data[i++]) % kSpans[cls];
    ids.push_back(kBases[cls] + off % kSpans[cls]);
  }
  return ids;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (1u << 20)) return 0;
  const std::vector<int32_t> ids = IdsOf(data, size);
  auto stream = silk::ReadTokenStream(ids);
  auto mesh = silk::DecodeTokens(ids);
  // The decoder must agree with the reader on what is a well-formed stream.
  if (stream.ok() != mesh.ok() && mesh.status().code() == silk::StatusCode::kParseError) __builtin_trap();
  if (mesh.ok()) {
    for (const auto& f : mesh->faces) {
      for (int32_t v : f) {
        if (v < 0 || static_cast<size_t>(v) >= mesh->positions.size()) __builtin_trap();
      }
    }
  }
  return 0;
}
