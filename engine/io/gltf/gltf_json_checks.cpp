// SPDX-License-Identifier: MIT
// Pre-validation of glTF JSON with a depth scan and nlohmann::json (exceptions caught here).
#include "io/gltf/gltf_json_checks.h"

#include <nlohmann/json.hpp>

#include "io/files/file_system.h"
#include "io/read_error.h"

namespace silk {

Status CheckGltfJsonText(std::string_view json, const std::string& name, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        return ParseErrorIn(name, "glTF JSON nests deeper than " + std::to_string(max_depth) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  try {
    if (!nlohmann::json::accept(json.begin(), json.end())) return ParseErrorIn(name, "glTF JSON is not valid JSON");
  } catch (const std::exception& e) {
    return ParseErrorIn(name, std::string("glTF JSON is not valid JSON: ") + e.what());
  }
  return Status::Ok();
}

std::string DecodeUriPercent(const std::string& uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out.push_back(static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2])));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

Status CheckGltfExternalBuffers(std::string_view json, const std::string& name, const std::string& base_dir,
                                bool from_memory) {
  try {
    nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
    if (doc.is_discarded()) return ParseErrorIn(name, "glTF JSON is not valid JSON");
    if (!doc.is_object()) return ParseErrorIn(name, "glTF JSON top level is not an object");
    auto it = doc.find("buffers");
    if (it == doc.end() || !it->is_array()) return Status::Ok();
    for (size_t i = 0; i < it->size(); ++i) {
      const nlohmann::json& b = (*it)[i];
      if (!b.is_object()) continue;
      auto u = b.find("uri");
      if (u == b.end() || !u->is_string()) continue;
      const std::string uri = u->get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const std::string what = "buffer " + std::to_string(i) + ": external file '" + uri + "'";
      if (from_memory) return IoError(name + ": " + what + " cannot be loaded (mesh read from memory)");
      const std::string path = (base_dir.empty() ? std::string() : base_dir + "/") + DecodeUriPercent(uri);
      if (!IsRegularFile(path)) return IoError(name + ": " + what + " not found");
    }
  } catch (const std::exception& e) {
    return ParseErrorIn(name, std::string("glTF JSON: ") + e.what());
  }
  return Status::Ok();
}

}  // namespace silk
