// SPDX-License-Identifier: MIT
// The JSON Lines report of silkgen --batch (batch_report.h).
#include "../common/app_errors.h"
#include "../common/app_files.h"
#include "batch_report.h"

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>

#ifndef _WIN32
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

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
  j["input"] = in.path.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(in.path);
  j["status"] = r.status;
  j["output"] = r.output.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.output);
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
  j["edge_manifold"] =
      r.edge_manifold < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.edge_manifold != 0);
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

// A copy with every string at most `max_bytes` (a report line stays under 64 KiB however long a
// path or a message is: 4 strings x 2 KiB x 6, the longest JSON escape, is 48 KiB).
nlohmann::ordered_json Capped(nlohmann::ordered_json j, size_t max_bytes) {
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it->is_string() && it->get_ref<const std::string&>().size() > max_bytes)
      *it = it->get<std::string>().substr(0, max_bytes) + "...";
  return j;
}

std::string Dump(const nlohmann::ordered_json& j) {
  // Invalid UTF-8 in a path or message is replaced, never thrown.
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace

BatchReport::~BatchReport() {
  if (file_) std::fclose(file_);
}

bool BatchReport::Open(const std::string& path, std::string* error) {
  auto fail = [&](const std::string& why) {
    *error = silkapp::ErrorText(SILK_ERR_IO, path + ": cannot open the report for appending (" + why + ")");
    return false;
  };
#ifdef _WIN32
  if (silkapp::FsPath(path).has_filename() && std::filesystem::exists(silkapp::FsPath(path)) &&
      !silkapp::IsRegularFile(path))
    return fail("not a regular file");
  file_ = silkapp::OpenFile(path, "ab");
  if (!file_) return fail(std::strerror(errno));
#else
  // Non-blocking, so a FIFO cannot hold the open; then only a regular file is taken.
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC | O_NONBLOCK | O_NOCTTY, 0666);
  if (fd < 0) return fail(std::strerror(errno));
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return fail("not a regular file: a report is a file the run appends to");
  }
  ::fcntl(fd, F_SETFL, O_WRONLY | O_APPEND);
  file_ = ::fdopen(fd, "ab");
  if (!file_) {
    ::close(fd);
    return fail(std::strerror(errno));
  }
#endif
  path_ = path;
  // A buffer larger than any line: each line reaches the file in one write (O_APPEND), whole.
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 16);
  return true;
}

bool BatchReport::Write(const BatchRunInfo& run, const BatchInput& input, const BatchResult& result,
                        std::string* error) {
  const nlohmann::ordered_json line = Line(run, input, result);
  std::string text = Dump(line);
  if (text.size() >= kMaxLineBytes) text = Dump(Capped(line, 2048));
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0) {
    *error = path_ + ": cannot write the report (" + std::strerror(errno ? errno : EIO) +
             "); the run stops, the inputs done so far have their outputs";
    return false;
  }
  return true;
}

bool BatchReport::Close(std::string* error) {
  if (!file_) return true;
  const int rc = std::fclose(file_);
  file_ = nullptr;
  if (rc != 0) {
    *error = path_ + ": cannot write the report (" + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

}  // namespace silkgen
