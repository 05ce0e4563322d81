// SPDX-License-Identifier: MIT
// libFuzzer target: arbitrary bytes as an ONNX model whose external-data locations the runtime
// checks before onnxruntime opens them (ForEachExternalDataLocation, a protobuf walker over
// untrusted bytes). It must never read out of bounds, recurse without limit, or hand over a
// location over 4096 bytes; a visitor error must stop the walk and come back unchanged.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "runtime/model/onnx_external_data.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  size_t seen = 0;
  silk::Status s = silk::ForEachExternalDataLocation(bytes, "fuzz/decoder.onnx", [&](const std::string& loc) {
    if (loc.size() > 4096) __builtin_trap();
    ++seen;
    return silk::Status::Ok();
  });
  if (!s.ok() && s.message().empty()) __builtin_trap();
  if (seen == 0) return 0;
  // Refusing the first location stops the walk with exactly that error.
  size_t calls = 0;
  silk::Status stop = silk::ForEachExternalDataLocation(bytes, "fuzz/decoder.onnx", [&](const std::string&) {
    ++calls;
    return silk::ParseError("refused");
  });
  if (calls != 1 || stop.message() != "refused") __builtin_trap();
  return 0;
}
