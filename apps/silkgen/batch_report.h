// SPDX-License-Identifier: MIT
// silkgen --batch's report: JSON Lines, one object per input, appended and flushed as each input
// ends, so a killed run leaves every finished input on record (docs/batch.md "Report").
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "batch_inputs.h"

namespace silkgen {

// What one input gave. Figures stay at -1 (written as null) when there are none (skipped, failed).
struct BatchResult {
  std::string status;  // "ok", "skipped", "failed" or "cancelled"
  std::string output, error, stop_reason;
  int64_t tokens = -1;
  int faces = -1, vertices = -1, parts = -1, candidates = -1, chosen_candidate = -1;
  int watertight = -1, edge_manifold = -1;
  double score = -1, seconds = 0;
};

// Fields every line of one process carries.
struct BatchRunInfo {
  std::string run;  // host:pid:start time, tells the runs of an appended report apart
  Shard shard;
  uint64_t seed = 0;
  size_t total = 0;  // inputs in the whole sorted list
};

class BatchReport {
 public:
  // Longest line written (docs/batch.md): longer strings are cut to 2 KiB each.
  static constexpr size_t kMaxLineBytes = 1 << 16;
  ~BatchReport();
  // Opens `path` for appending (created if missing; only a regular file, a FIFO or device is
  // refused); false with a message naming it.
  bool Open(const std::string& path, std::string* error);
  // One line, written with one call and flushed; false with a message naming the report when
  // the write fails (disk full, quota, file size limit).
  bool Write(const BatchRunInfo& run, const BatchInput& input, const BatchResult& result, std::string* error);
  // Closes the file; false with a message when the last write-back failed.
  bool Close(std::string* error);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
};

}  // namespace silkgen
