// SPDX-License-Identifier: MIT
// The one rule "Silk never writes to a file it reads", for silkgen (single and --batch) and every
// silktok subcommand that writes: each run names the files it reads (inputs, a list) and the
// files it writes (outputs, a report) before any work, and a write target that is one of the
// files read (the same path, a symlink or hard link to it, or another spelling of it on a
// case-insensitive file system) or another write target is refused, naming both.
#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace silkapp {

class FileRoles {
 public:
  // `role` says what the file is in messages ("input", "the list", "--report", "-o").
  void Reads(const std::string& path, const std::string& role);
  void Writes(const std::string& path, const std::string& role);
  // "" when no write target is a file read or another write target; else the message naming
  // both ("-o out.obj is the input in.obj (the same file): Silk never writes a file it reads").
  // Work: one stat per file, O(n log n) over n files.
  std::string Check() const;

 private:
  struct File {
    std::string path, role;
  };
  std::vector<File> reads_, writes_;
};

}  // namespace silkapp
