// SPDX-License-Identifier: MIT
// Listing, sorting, stem check and sharding of silkgen --batch inputs (batch_inputs.h).
#include "../common/app_files.h"
#include "batch_inputs.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <system_error>

namespace fs = std::filesystem;

namespace silkgen {
namespace {

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A non-negative decimal integer that fits an int (no sign, no spaces); false otherwise.
bool ParseCount(const std::string& text, int* value) {
  if (text.empty() || text.size() > 9) return false;
  for (char c : text)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  *value = std::atoi(text.c_str());
  return true;
}

std::string Trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

// Lines of a list file: '#' starts a comment line, blank lines and CR before LF are ignored.
bool ReadList(const std::string& list, std::vector<BatchInput>* out, std::string* error) {
  std::ifstream f(silkapp::FsPath(list), std::ios::binary);
  if (!f) {
    *error = list + ": cannot read the input list";
    return false;
  }
  const fs::path folder = silkapp::FsPath(list).parent_path();
  std::string line;
  while (std::getline(f, line)) {
    const std::string entry = Trim(line);
    if (entry.empty() || entry[0] == '#') continue;
    const fs::path p = silkapp::FsPath(entry);
    BatchInput in;
    in.entry = entry;
    in.path = silkapp::Utf8((p.is_absolute() ? p : folder / p).lexically_normal());
    out->push_back(in);
  }
  return true;
}

bool ReadFolder(const std::string& dir, std::vector<BatchInput>* out, std::string* error) {
  std::error_code ec;
  for (fs::directory_iterator it(silkapp::FsPath(dir), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = silkapp::Utf8(it->path().filename());
    if (name.empty() || name[0] == '.' || !IsSupportedInput(name)) continue;  // hidden: temp files
    std::error_code ec2;
    if (!it->is_regular_file(ec2)) continue;
    BatchInput in;
    in.entry = name;
    in.path = silkapp::Utf8(it->path());
    out->push_back(in);
  }
  if (ec) *error = dir + ": cannot list the folder (" + ec.message() + ")";
  return !ec;
}

// Two inputs whose outputs would have the same name: refused, naming both.
bool CheckStems(const std::vector<BatchInput>& inputs, std::string* error) {
  std::map<std::string, const BatchInput*> seen;
  for (const BatchInput& in : inputs) {
    auto [it, fresh] = seen.emplace(Lower(in.stem), &in);
    if (!fresh) {
      *error = "two inputs would write the same output '" + in.stem + "': " + it->second->path + " and " + in.path +
               " (rename one, or split the list)";
      return false;
    }
  }
  return true;
}

}  // namespace

bool ParseShard(const std::string& text, Shard* shard, std::string* error) {
  const size_t slash = text.find('/');
  Shard s;
  s.source = "--shard";
  if (slash == std::string::npos || !ParseCount(text.substr(0, slash), &s.index) ||
      !ParseCount(text.substr(slash + 1), &s.count)) {
    *error = "--shard: '" + text + "' is not I/N (two non-negative integers, e.g. 0/4)";
    return false;
  }
  if (s.count < 1 || s.index >= s.count) {
    *error = "--shard: '" + text + "': need N >= 1 and 0 <= I < N";
    return false;
  }
  *shard = s;
  return true;
}

bool ShardFromEnvironment(Shard* shard, std::string* error) {
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (!id) return true;  // no array job: one shard
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  const char* step = std::getenv("SLURM_ARRAY_TASK_STEP");
  int task = 0, n = 0, first = 0, stride = 1;
  if (!count || !ParseCount(id, &task) || !ParseCount(count, &n) || (min && !ParseCount(min, &first)) ||
      (step && (!ParseCount(step, &stride) || stride < 1))) {
    *error = std::string("Slurm array variables unusable (SLURM_ARRAY_TASK_ID=") + id +
             ", SLURM_ARRAY_TASK_COUNT=" + (count ? count : "unset") + ", SLURM_ARRAY_TASK_MIN=" + (min ? min : "unset") +
             "): give --shard I/N";
    return false;
  }
  const int index = task >= first && (task - first) % stride == 0 ? (task - first) / stride : -1;
  if (n < 1 || index < 0 || index >= n) {
    *error = "SLURM_ARRAY_TASK_ID=" + std::string(id) + " is not one of the " + count +
             " tasks from SLURM_ARRAY_TASK_MIN=" + std::to_string(first) + " step " + std::to_string(stride) +
             ": give --shard I/N";
    return false;
  }
  shard->index = index;
  shard->count = n;
  shard->source = "SLURM_ARRAY_TASK_ID";
  return true;
}

bool IsSupportedInput(const std::string& path) {
  std::string p = Lower(path);
  if (EndsWith(p, ".gz")) p.resize(p.size() - 3);
  for (const char* ext : {".obj", ".ply", ".stl", ".off", ".gltf", ".glb", ".pmd", ".xyz", ".pts"})
    if (EndsWith(p, ext)) return true;
  return false;
}

std::string InputStem(const std::string& path) {
  fs::path name = silkapp::FsPath(path).filename();
  if (Lower(silkapp::Utf8(name.extension())) == ".gz") name = name.stem();
  return silkapp::Utf8(name.stem());
}

bool ListInputs(const std::string& source, std::vector<BatchInput>* inputs, std::string* error) {
  std::vector<BatchInput> all;
  std::error_code ec;
  if (fs::is_directory(silkapp::FsPath(source), ec)) {
    if (!ReadFolder(source, &all, error)) return false;
  } else if (IsSupportedInput(source)) {
    *error = source + ": a mesh file; --batch takes a list file (one path a line) or a folder";
    return false;
  } else if (!ReadList(source, &all, error)) {
    return false;
  }
  std::sort(all.begin(), all.end(), [](const BatchInput& a, const BatchInput& b) { return a.entry < b.entry; });
  all.erase(std::unique(all.begin(), all.end(),
                        [](const BatchInput& a, const BatchInput& b) { return a.entry == b.entry; }),
            all.end());
  if (all.empty()) {
    *error = source + ": no inputs (a list needs one path a line; a folder, files the readers take)";
    return false;
  }
  for (size_t i = 0; i < all.size(); ++i) {
    all[i].index = i;
    all[i].stem = InputStem(all[i].path);
  }
  if (!CheckStems(all, error)) return false;
  *inputs = std::move(all);
  return true;
}

std::vector<BatchInput> ShardInputs(const std::vector<BatchInput>& all, const Shard& shard) {
  std::vector<BatchInput> mine;
  for (const BatchInput& in : all)
    if (static_cast<int>(in.index % static_cast<size_t>(shard.count)) == shard.index) mine.push_back(in);
  return mine;
}

}  // namespace silkgen
