// SPDX-License-Identifier: MIT
// Formatting only: what is listed and where it is found is libsilk's (silk_models_list).
#include "model_list.h"

#include <cstdio>

#include <nlohmann/json.hpp>

namespace silkgen {

namespace {

using Json = nlohmann::json;

std::string Size(double bytes) {
  char buf[32];
  if (bytes >= 1e9)
    std::snprintf(buf, sizeof(buf), "%.2f GB", bytes / 1e9);
  else
    std::snprintf(buf, sizeof(buf), "%.1f MB", bytes / 1e6);
  return buf;
}

// "fp32, int8*" : the list with the default starred.
std::string Choices(const Json& list, const Json& chosen) {
  std::string s;
  for (const Json& v : list) {
    const std::string name = v.get<std::string>();
    s += (s.empty() ? "" : ", ") + name + (chosen.is_string() && chosen.get<std::string>() == name ? "*" : "");
  }
  return s;
}

std::string Row(const std::string& name, const std::string& arch, const std::string& size, const std::string& decoders,
                const std::string& caches, const std::string& folder) {
  char buf[1024];
  std::snprintf(buf, sizeof(buf), "%-20s %-22s %-9s %-18s %-18s %s\n", name.c_str(), arch.c_str(), size.c_str(),
                decoders.c_str(), caches.c_str(), folder.c_str());
  return buf;
}

std::string ModelRow(const Json& m) {
  const std::string name = m.value("name", "") + (m.value("bundled", false) ? " (bundled)" : "");
  const std::string size = Size(m.value("bytes", 0.0));
  if (m.contains("error")) return Row(name, "unusable: " + m.value("error", ""), size, "", "", m.value("dir", ""));
  const Json& p = m["parameters"];
  const std::string config = m.value("config", "");
  const std::string arch = m.value("arch", "") + (config == m.value("arch", "") ? "" : " " + config) + " (" +
                           std::to_string(p.value("n_layers", 0)) + " x " + std::to_string(p.value("d_model", 0)) + ")";
  return Row(name, arch, size, Choices(m["decoders"], m["default_decoder"]),
             Choices(m["kv_precisions"], m["default_kv_precision"]), m.value("dir", ""));
}

}  // namespace

std::string ModelListText(const std::string& catalog_json) {
  const Json c = Json::parse(catalog_json);
  std::string text = Row("NAME", "ARCHITECTURE", "SIZE", "DECODERS", "KV CACHES", "FOLDER");
  for (const Json& m : c["models"]) text += ModelRow(m);
  if (c["models_dir"].is_string())
    text += "models folder: " + c["models_dir"].get<std::string>() +
            " (SILK_MODELS moves it; silk-export import-official --name NAME adds to it; * = default)\n";
  else
    text += "no models folder: " + c.value("models_dir_error", "") + "\n";
  if (c.value("not_listed", 0) > 0) text += std::to_string(c.value("not_listed", 0)) + " more folders not listed\n";
  return text;
}

}  // namespace silkgen
