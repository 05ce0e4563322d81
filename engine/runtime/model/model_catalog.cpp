// SPDX-License-Identifier: MIT
// Builds the catalog JSON of model_catalog.h: LoadModelConfig for each folder (the same checks a
// load makes of model.json, without onnxruntime sessions) and the bytes its files take on disk.
#include "runtime/model/model_catalog.h"

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/files/model_folders.h"
#include "io/files/native_path.h"
#include "runtime/model/model_config.h"

namespace silk {

namespace {

using Json = nlohmann::json;

// Bytes of the regular files directly inside dir (model folders are flat).
uint64_t FolderBytes(const std::string& dir) {
  std::error_code ec;
  uint64_t total = 0;
  for (std::filesystem::directory_iterator it(NativePath(dir), ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code fe;
    if (it->is_regular_file(fe)) total += it->file_size(fe);
  }
  return total;
}

Json Describe(const std::string& name, const std::string& dir, bool bundled) {
  Json m = {{"name", name}, {"dir", dir}, {"bundled", bundled}, {"bytes", FolderBytes(dir)}};
  auto c = LoadModelConfig(dir);
  if (!c.ok()) {
    m["error"] = c.status().message();
    return m;
  }
  m["arch"] = c->arch == ModelArch::kOfficial ? "official" : "silk";
  m["config"] = c->config_name;
  m["parameters"] = {{"d_model", c->dims.d_model}, {"n_layers", c->dims.n_layers}, {"n_heads", c->dims.n_heads}};
  Json decoders = Json::array(), kv = Json::array({"fp32"});
  for (DecoderPrecision p : {DecoderPrecision::kFp32, DecoderPrecision::kInt8, DecoderPrecision::kInt4})
    if (!c->DecoderFile(p).empty()) decoders.push_back(DecoderPrecisionName(p));
  for (KvPrecision k : {KvPrecision::kFp16, KvPrecision::kInt8}) {
    bool any = false;
    for (DecoderPrecision p : {DecoderPrecision::kFp32, DecoderPrecision::kInt8, DecoderPrecision::kInt4})
      any = any || !c->DecoderFile(p, k).empty();
    if (any) kv.push_back(KvPrecisionName(k));
  }
  m["decoders"] = decoders;
  m["default_decoder"] = DecoderPrecisionName(c->default_decoder);
  m["kv_precisions"] = kv;
  m["default_kv_precision"] = KvPrecisionName(c->DefaultKv(c->default_decoder));
  return m;
}

// The subfolders' names, sorted (a models folder that does not exist yet has none); at most
// kMaxScannedEntries entries are looked at, so a huge folder costs a bounded time.
constexpr int kMaxScannedEntries = 100 * kMaxListedModels;
std::vector<std::string> SubfolderNames(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  int seen = 0;
  for (std::filesystem::directory_iterator it(NativePath(dir), ec), end;
       !ec && it != end && seen++ < kMaxScannedEntries; it.increment(ec)) {
    std::error_code fe;
    if (it->is_directory(fe)) names.push_back(Utf8Path(it->path().filename()));
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

std::string ModelCatalogJson() {
  Json out = {{"models", Json::array()}, {"not_listed", 0}};
  if (auto bundled = BundledModelDir(); bundled.ok()) out["models"].push_back(Describe("default", *bundled, true));
  auto dir = UserModelsDir();
  if (!dir.ok()) {
    out["models_dir"] = nullptr;
    out["models_dir_error"] = dir.status().message();
    return out.dump();
  }
  out["models_dir"] = *dir;
  int listed = 0, skipped = 0;
  for (const std::string& name : SubfolderNames(*dir)) {
    if (!CheckModelName(name).ok()) continue;  // not reachable by name
    if (listed++ >= kMaxListedModels) {
      ++skipped;
      continue;
    }
    auto sub = UserModelDir(name);
    if (sub.ok()) out["models"].push_back(Describe(name, *sub, false));
  }
  out["not_listed"] = skipped;
  return out.dump();
}

}  // namespace silk
