// SPDX-License-Identifier: MIT
// zlib inflate (gzip wrapper, concatenated members accepted), bounded and streaming.
#include "io/files/gzip_inflate.h"

#include <algorithm>
#include <functional>
#include <vector>

#ifdef SILK_HAVE_ZLIB
#include <zlib.h>
#endif

namespace silk {

#ifdef SILK_HAVE_ZLIB
namespace {

using Sink = std::function<void(const char*, size_t)>;

// One zlib step over `gz` from *in_pos into `scratch`; the produced bytes go to `sink`.
// Returns zlib's code; *total counts every byte produced so far.
int InflateStep(z_stream& zs, std::string_view gz, size_t* in_pos, std::vector<char>& scratch, uint64_t* total,
                const Sink& sink) {
  const size_t in_chunk = std::min<size_t>(gz.size() - *in_pos, 1u << 30);
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(gz.data() + *in_pos));
  zs.avail_in = static_cast<uInt>(in_chunk);
  zs.next_out = reinterpret_cast<Bytef*>(scratch.data());
  zs.avail_out = static_cast<uInt>(scratch.size());
  const int rc = inflate(&zs, Z_NO_FLUSH);
  *in_pos += in_chunk - zs.avail_in;
  const size_t produced = scratch.size() - zs.avail_out;
  *total += produced;
  if (sink && produced) sink(scratch.data(), produced);
  return rc;
}

// Inflates all members, stopping as soon as the output passes `max_output_bytes`.
Status InflateAll(z_stream& zs, std::string_view gz, const std::string& name, uint64_t max_output_bytes,
                  uint64_t* total, const Sink& sink) {
  std::vector<char> scratch(size_t{1} << 18);
  size_t in_pos = 0;
  *total = 0;
  while (true) {
    const int rc = InflateStep(zs, gz, &in_pos, scratch, total, sink);
    if (*total > max_output_bytes)
      return LimitExceeded(name + ": gzip data inflates past the limit of " + std::to_string(max_output_bytes) +
                           " bytes (ReadOptions::max_inflated_bytes / max_inflation_ratio; decompress it first)");
    if (rc == Z_STREAM_END) {
      if (in_pos == gz.size()) return Status::Ok();
      // Another gzip member follows: keep going.
      if (inflateReset(&zs) != Z_OK) return InternalError(name + ": inflateReset failed");
      continue;
    }
    if (rc == Z_OK || rc == Z_BUF_ERROR) {
      if (in_pos == gz.size() && zs.avail_out != 0) return ParseError(name + ": truncated gzip data");
      continue;
    }
    return ParseError(name + ": corrupt gzip data" + (zs.msg ? std::string(" (") + zs.msg + ")" : std::string()));
  }
}

// One complete inflation of `gz` (a fresh zlib stream) into `sink`; *total gets the size.
Status InflatePass(std::string_view gz, const std::string& name, uint64_t max_output_bytes, uint64_t* total,
                   const Sink& sink) {
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 16) != Z_OK) return InternalError(name + ": inflateInit2 failed");
  Status s = InflateAll(zs, gz, name, max_output_bytes, total, sink);
  inflateEnd(&zs);
  return s;
}

}  // namespace
#endif

StatusOr<std::string> GunzipBytes(std::string_view gz, const std::string& name, uint64_t max_output_bytes) {
#ifndef SILK_HAVE_ZLIB
  (void)gz;
  (void)max_output_bytes;
  return Unsupported(name + ": gzip input needs zlib, which this build does not have");
#else
  if (gz.size() < 2 || static_cast<unsigned char>(gz[0]) != 0x1f || static_cast<unsigned char>(gz[1]) != 0x8b)
    return ParseError(name + ": not a gzip file (bad magic)");
  uint64_t size = 0;
  SILK_RETURN_IF_ERROR(InflatePass(gz, name, max_output_bytes, &size, Sink()));  // count only: bombs stop here
  std::string out;
  out.reserve(static_cast<size_t>(size));
  uint64_t again = 0;
  SILK_RETURN_IF_ERROR(InflatePass(gz, name, size, &again, [&out](const char* p, size_t n) { out.append(p, n); }));
  if (again != size || out.size() != size) return InternalError(name + ": gzip output changed between passes");
  return out;
#endif
}

}  // namespace silk
