// SPDX-License-Identifier: MIT
// C API: the file reads and writes the tools share (silk.h "files"): the atomic writer, the
// regular-file reader, the output-path check and the signal-time discard of temporaries.
#include <algorithm>

#include "capi/capi_internal.h"
#include "io/files/atomic_file.h"
#include "io/files/file_bytes.h"
#include "io/files/output_path.h"
#include "io/files/partial_files.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

silk_status silk_file_check_output(const char* path) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(path, "silk_file_check_output: path is NULL");
    return SetError(silk::CheckOutputPath(path));
  });
}

silk_status silk_file_write(const char* path, const void* bytes, size_t size) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(path && (bytes || size == 0), "silk_file_write: NULL argument");
    const char* b = static_cast<const char*>(bytes);
    return SetError(silk::WriteFileAtomically(path, size ? std::string(b, b + size) : std::string()));
  });
}

silk_status silk_file_read(const char* path, uint64_t max_bytes, char* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE(path, "silk_file_read: path is NULL");
    uint64_t size = 0;
    SILK_CAPI_TRY(SetError(silk::CheckRegularFile(path, &size)));
    if (size > max_bytes)
      return SetError(SILK_ERR_LIMIT, std::string(path) + ": file is " + std::to_string(size) + " bytes, limit " +
                                          std::to_string(max_bytes));
    if (!out && capacity == 0) {  // the size query: the file's size now
      if (out_count) *out_count = static_cast<size_t>(size);
      return Ok();
    }
    silk::StatusOr<std::string> bytes = silk::ReadFileBytes(path, std::min<uint64_t>(max_bytes, capacity));
    if (!bytes.ok()) {
      if (bytes.status().code() == silk::StatusCode::kLimitExceeded)
        return SetError(SILK_ERR_BUFFER_TOO_SMALL, std::string(path) + ": the file grew past the buffer of " +
                                                       std::to_string(capacity) + " bytes since its size was asked");
      return SetError(bytes.status());
    }
    silk_status answer;
    if (!silk::capi::BeginCopy("silk_file_read", out, capacity, bytes->size(), out_count, &answer)) return answer;
    std::copy(bytes->begin(), bytes->end(), out);
    return Ok();
  });
}

void silk_file_discard_partial(void) { silk::DiscardPartialFiles(); }
