// SPDX-License-Identifier: MIT
// Readers for the official reference files in shared/spec.
#include "support/golden_files.h"

#include <algorithm>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <sstream>

#include "support/test_paths.h"

namespace silk::testing {

bool ReadTokenFile(const std::string& path, std::vector<int32_t>* ids) {
  std::ifstream in(path);
  if (!in) return false;
  ids->clear();
  long long v;
  while (in >> v) ids->push_back(static_cast<int32_t>(v));
  return true;
}

GridFace CanonicalFace(const std::array<std::array<int32_t, 3>, 3>& c) {
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (c[k] < c[best]) best = k;
  GridFace f{};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) f[k * 3 + a] = c[(best + k) % 3][a];
  return f;
}

GridFace ReversedFace(const GridFace& f) {
  std::array<std::array<int32_t, 3>, 3> c{};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) c[k][a] = f[((3 - k) % 3) * 3 + a];
  return CanonicalFace(c);
}

GridFace UnorientedFace(const GridFace& f) {
  std::array<std::array<int32_t, 3>, 3> c{};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) c[k][a] = f[k * 3 + a];
  std::sort(c.begin(), c.end());
  GridFace out{};
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a) out[k * 3 + a] = c[k][a];
  return out;
}

bool ReadProcessedFile(const std::string& path, std::vector<GridFace>* faces) {
  faces->clear();
  std::ifstream in(path);
  if (!in) return true;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::array<std::array<int32_t, 3>, 3> c{};
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k)
      for (int a = 0; a < 3 && ok; ++a) ok = static_cast<bool>(ls >> c[k][a]);
    if (ok) faces->push_back(CanonicalFace(c));
  }
  return true;
}

std::vector<std::map<std::string, std::string>> ReadTsvRows(const std::string& path) {
  std::vector<std::map<std::string, std::string>> rows;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  auto split = [](const std::string& s) {
    std::vector<std::string> out;
    std::string cur;
    for (char ch : s) {
      if (ch == '\t') {
        out.push_back(cur);
        cur.clear();
      } else if (ch != '\r') {
        cur += ch;
      }
    }
    out.push_back(cur);
    return out;
  };
  if (!std::getline(in, line)) return rows;
  header = split(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    auto cols = split(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header.size() && i < cols.size(); ++i) row[header[i]] = cols[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

bool ReadPlainObj(const std::string& path, silk::IoMesh* mesh) {
  std::ifstream in(path);
  if (!in) return false;
  mesh->positions.clear();
  mesh->triangles.clear();
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw == "v") {
      std::string a, b, c;
      ls >> a >> b >> c;
      mesh->positions.push_back(
          {std::strtod(a.c_str(), nullptr), std::strtod(b.c_str(), nullptr), std::strtod(c.c_str(), nullptr)});
    } else if (kw == "f") {
      std::array<int32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        std::string g;
        ls >> g;
        t[k] = std::atoi(g.c_str()) - 1;
      }
      mesh->triangles.push_back(t);
    }
  }
  return true;
}

std::vector<std::string> GoldenDevOkNames() {
  std::vector<std::string> names;
  for (const auto& row : ReadTsvRows(SharedPath("spec/golden-dev/INDEX.tsv")))
    if (row.count("status") && row.at("status") == "ok") names.push_back(row.at("name"));
  return names;
}

std::vector<std::string> GoldenNames() {
  std::vector<std::string> names;
  const std::string dir = SharedPath("spec/golden");
  if (DIR* d = opendir(dir.c_str())) {
    while (dirent* e = readdir(d)) {
      std::string n = e->d_name;
      const std::string suf = ".tokens.txt";
      if (n.size() > suf.size() && n.compare(n.size() - suf.size(), suf.size(), suf) == 0)
        names.push_back(n.substr(0, n.size() - suf.size()));
    }
    closedir(d);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace silk::testing
