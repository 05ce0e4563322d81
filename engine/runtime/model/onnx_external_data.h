// SPDX-License-Identifier: MIT
// Finds the external-data locations an ONNX model names (TensorProto.external_data entries
// with key "location"), so the runtime can keep them inside the model folder before
// onnxruntime opens them. A bounded protobuf wire-format walker over untrusted bytes: no
// protobuf dependency, every length checked against the bytes its message has left.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "core/status.h"

namespace silk {

// Random access to the bytes of an ONNX file (a file on disk, or memory for the fuzzer).
class OnnxByteSource {
 public:
  virtual ~OnnxByteSource() = default;
  virtual uint64_t size() const = 0;
  // Copies the n bytes at offset (inside size()) into out; false on a read error.
  virtual bool Read(uint64_t offset, size_t n, char* out) = 0;
};

using ExternalDataVisitor = std::function<Status(const std::string& location)>;

// Calls visit for every external-data "location" of the model, in file order: the graph's
// initializers and sparse initializers, tensors in node attributes, subgraphs, functions and
// training graphs (every entry keyed "location", whatever its tensor's data_location says).
// Stops at visit's first error. Errors name `name`: malformed wire format, messages nested over
// 100 deep, a location longer than 4096 bytes.
Status ForEachExternalDataLocation(OnnxByteSource& src, const std::string& name, const ExternalDataVisitor& visit);
Status ForEachExternalDataLocation(std::string_view bytes, const std::string& name, const ExternalDataVisitor& visit);
// The file at `path`, read in small windows (the tensor bytes are skipped, never read).
Status ForEachExternalDataLocationInFile(const std::string& path, const ExternalDataVisitor& visit);

}  // namespace silk
