// SPDX-License-Identifier: MIT
// PLY header model and parser: format, elements, scalar and list properties. Kept apart from
// the body reader so the plausibility checks (counts vs. remaining bytes) see the whole header.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/status.h"

namespace silk {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

enum class PlyType : uint8_t { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

size_t PlyTypeSize(PlyType t);
bool PlyTypeIsInteger(PlyType t);

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::kUInt8;  // lists only
  PlyType value_type = PlyType::kFloat32;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  int64_t line = 0;  // header line that declared it
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;  // first byte after "end_header\n"
  int64_t body_line = 0;   // line number of the first body line (ascii)
};

// Parses the header at the start of `data`; errors name `name` and the header line.
StatusOr<PlyHeader> ParsePlyHeader(std::string_view data, const std::string& name);

}  // namespace silk
