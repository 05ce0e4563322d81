// SPDX-License-Identifier: MIT
// The JSON Lines report of silkgen --batch (batch_report.h).
#include "../common/app_files.h"
#include "batch_report.h"

#include <cerrno>
#include <cstring>
#include <ctime>

#include <nlohmann/json.hpp>

namespace silkgen {
namespace {

// -1 (no figure) as null.
template <typename T>
nlohmann::ordered_json Figure(T v) {
  return v < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(v);
}

std::string UtcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));  // one thread
  return buf;
}

nlohmann::ordered_json Line(const BatchRunInfo& run, const BatchInput& in, const BatchResult& r) {
  nlohmann::ordered_json j;
  j["input"] = in.path;
  j["status"] = r.status;
  j["output"] = r.output;
  j["faces"] = Figure(r.faces);
  j["tokens"] = Figure(r.tokens);
  j["seconds"] = static_cast<double>(static_cast<int64_t>(r.seconds * 1000 + 0.5)) / 1000;
  j["error"] = r.error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.error);
  j["vertices"] = Figure(r.vertices);
  j["parts"] = Figure(r.parts);
  j["stop_reason"] = r.stop_reason.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.stop_reason);
  j["candidates"] = Figure(r.candidates);
  j["chosen_candidate"] = Figure(r.chosen_candidate);
  j["score"] = Figure(r.score);
  j["watertight"] = r.watertight < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.watertight != 0);
  j["edge_manifold"] = r.edge_manifold < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.edge_manifold != 0);
  j["seed"] = run.seed;
  j["entry"] = in.entry;
  j["index"] = in.index;
  j["of"] = run.total;
  j["shard"] = std::to_string(run.shard.index) + "/" + std::to_string(run.shard.count);
  j["shard_source"] = run.shard.source;
  j["run"] = run.run;
  j["time"] = UtcNow();
  return j;
}

}  // namespace

BatchReport::~BatchReport() {
  if (file_) std::fclose(file_);
}

bool BatchReport::Open(const std::string& path, std::string* error) {
  file_ = silkapp::OpenFile(path, "ab");
  if (!file_) {
    *error = path + ": cannot open the report for appending (" + std::strerror(errno) + ")";
    return false;
  }
  // A buffer larger than any line: each line reaches the file in one write (O_APPEND), whole.
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 16);
  return true;
}

void BatchReport::Write(const BatchRunInfo& run, const BatchInput& input, const BatchResult& result) {
  // Invalid UTF-8 in a path or message is replaced, never thrown.
  const std::string text = Line(run, input, result).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
  std::fwrite(text.data(), 1, text.size(), file_);
  std::fflush(file_);
}

}  // namespace silkgen
