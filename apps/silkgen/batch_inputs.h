// SPDX-License-Identifier: MIT
// silkgen --batch: which inputs a process takes. The list (a text file of paths or a folder's
// supported files), its sorted order, the stem check and the shard (--shard I/N or Slurm's array
// variables) are decided here, identically in every process of a farm.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace silkgen {

// One input: `entry` is the sort key (the list line as written, or the file name in a folder),
// `path` the file opened (a relative list line resolved against the list file's folder).
struct BatchInput {
  std::string entry, path, stem;
  std::string problem;  // "" or why the entry is refused (a failed row; path and stem stay empty)
  size_t index = 0;     // position in the sorted list (0-based), the same in every shard
};

// Shard `index` of `count` takes the inputs whose sorted position p has p % count == index.
struct Shard {
  int index = 0, count = 1;
  std::string source = "none";  // "--shard", "SLURM_ARRAY_TASK_ID" or "none"
};

// "I/N" with 0 <= I < N; false and a message naming the problem otherwise.
bool ParseShard(const std::string& text, Shard* shard, std::string* error);
// From SLURM_ARRAY_TASK_ID / _COUNT (and _MIN, _STEP when set); source "none" when the variables
// are absent. False with a message when they are set but unusable.
bool ShardFromEnvironment(Shard* shard, std::string* error);

// A name the mesh readers take (.obj .ply .stl .off .gltf .glb .pmd .xyz .pts, each optionally .gz).
bool IsSupportedInput(const std::string& path);
// The output stem: the file name without .gz and its format extension ("a/b.obj.gz" -> "b").
std::string InputStem(const std::string& path);

// Every input of a list file or (non-recursive) folder, sorted by entry, duplicates removed,
// index set. False with a message when the source cannot be read, holds no input, or two
// inputs share a stem (case-insensitively: both are named).
bool ListInputs(const std::string& source, std::vector<BatchInput>* inputs, std::string* error);

// The inputs of one shard, in sorted order.
std::vector<BatchInput> ShardInputs(const std::vector<BatchInput>& all, const Shard& shard);

}  // namespace silkgen
