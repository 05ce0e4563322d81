// SPDX-License-Identifier: MIT
// Listing, sorting, stem check and sharding of silkgen --batch inputs (batch_inputs.h).
#include "../common/app_errors.h"
#include "../common/app_files.h"
#include "batch_inputs.h"
#include "batch_list.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
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

// Entries of a list file (batch_list.h), read through libsilk (a regular file, size-limited);
// relative paths from the list's folder. A refused line keeps no path: it becomes a failed row.
bool ReadList(const std::string& list, std::vector<BatchInput>* out, std::string* error) {
  std::string text;
  try {
    text = silk_cpp::ReadFile(list, kMaxListBytes);
  } catch (const silk_cpp::Error& e) {
    *error = silkapp::ErrorText(e.status(), e.message() + " (the input list)");
    return false;
  }
  std::vector<ListEntry> entries;
  if (!ParseList(text, &entries, error)) {
    *error = silkapp::ErrorText(SILK_ERR_LIMIT, list + ": " + *error);
    return false;
  }
  text = std::string();
  const fs::path folder = silkapp::FsPath(list).parent_path();
  for (ListEntry& e : entries) {
    BatchInput in;
    in.entry = std::move(e.entry);
    in.problem = std::move(e.problem);
    if (in.problem.empty()) {
      const fs::path p = silkapp::FsPath(in.entry);
      in.path = silkapp::Utf8((p.is_absolute() ? p : folder / p).lexically_normal());
    }
    out->push_back(std::move(in));
  }
  return true;
}

bool ReadFolder(const std::string& dir, std::vector<BatchInput>* out, std::string* error) {
  std::error_code ec;
  for (fs::directory_iterator it(silkapp::FsPath(dir), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = silkapp::Utf8(it->path().filename());
    if (name.empty() || name[0] == '.' || !IsSupportedInput(name)) continue;  // hidden: temp files
    std::error_code ec2;
    if (it->is_directory(ec2))
      continue;  // subfolders are not walked; a FIFO or device fails as a row (libsilk's reader)
    BatchInput in;
    in.problem = EntryProblem(name);
    in.entry = in.problem.empty() ? name : PrintableExcerpt(name, 200);
    if (in.problem.empty())
      in.path = silkapp::Utf8(it->path());
    else
      in.problem = "file name " + in.problem + " (not taken as an input)";
    out->push_back(in);
  }
  if (ec) *error = silkapp::ErrorText(SILK_ERR_IO, dir + ": cannot list the folder (" + ec.message() + ")");
  return !ec;
}

// Two inputs whose outputs would have the same name: refused, naming both.
bool CheckStems(const std::vector<BatchInput>& inputs, std::string* error) {
  std::map<std::string, const BatchInput*> seen;
  for (const BatchInput& in : inputs) {
    if (!in.problem.empty()) continue;  // no output
    auto [it, fresh] = seen.emplace(Lower(in.stem), &in);
    if (!fresh) {
      *error = "invalid argument: two inputs would write the same output '" + in.stem + "': " + it->second->path +
               " and " + in.path + " (rename one, or split the list)";
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
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  const char* step = std::getenv("SLURM_ARRAY_TASK_STEP");
  auto shown = [](const char* v) { return v ? "'" + std::string(v) + "'" : std::string("unset"); };
  const std::string all = "SLURM_ARRAY_TASK_ID=" + shown(id) + ", SLURM_ARRAY_TASK_COUNT=" + shown(count) +
                          ", SLURM_ARRAY_TASK_MIN=" + shown(min) + ", SLURM_ARRAY_TASK_STEP=" + shown(step);
  if (!id) {
    if (!count && !min && !step) return true;  // no array job: one shard
    *error = "Slurm array variables without SLURM_ARRAY_TASK_ID (" + all + "): give --shard I/N";
    return false;
  }
  int task = 0, n = 0, first = 0, stride = 1;
  if (!count || !ParseCount(id, &task) || !ParseCount(count, &n) || (min && !ParseCount(min, &first)) ||
      (step && (!ParseCount(step, &stride) || stride < 1))) {
    *error = "Slurm array variables unusable (" + all +
             "; each a non-negative integer, COUNT and STEP >= 1): give --shard I/N";
    return false;
  }
  const int index = task >= first && (task - first) % stride == 0 ? (task - first) / stride : -1;
  if (n < 1 || index < 0 || index >= n) {
    *error = "SLURM_ARRAY_TASK_ID=" + std::string(id) + " is not one of the " + count +
             " tasks from SLURM_ARRAY_TASK_MIN=" + std::to_string(first) + " step " + std::to_string(stride) + " (" +
             all + "): give --shard I/N";
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
    *error = "invalid argument: " + source + ": a mesh file; --batch takes a list file (one path a line) or a folder";
    return false;
  } else if (!ReadList(source, &all, error)) {
    return false;
  }
  std::sort(all.begin(), all.end(), [](const BatchInput& a, const BatchInput& b) { return a.entry < b.entry; });
  all.erase(std::unique(all.begin(), all.end(),
                        [](const BatchInput& a, const BatchInput& b) {
                          return a.entry == b.entry && a.problem.empty() && b.problem.empty();
                        }),
            all.end());
  if (all.empty()) {
    *error =
        "invalid argument: " + source + ": no inputs (a list needs one path a line; a folder, files the readers take)";
    return false;
  }
  for (size_t i = 0; i < all.size(); ++i) {
    all[i].index = i;
    if (all[i].problem.empty()) all[i].stem = InputStem(all[i].path);
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
