// zlib inflate (gzip wrapper, concatenated members accepted) into a growing string.
#include "io/files/gzip_inflate.h"

#include <algorithm>

#ifdef SILK_HAVE_ZLIB
#include <zlib.h>
#endif

namespace silk {

StatusOr<std::string> GunzipBytes(std::string_view gz, const std::string& name, uint64_t max_output_bytes) {
#ifndef SILK_HAVE_ZLIB
  (void)gz;
  (void)max_output_bytes;
  return Unsupported(name + ": gzip input needs zlib, which this build does not have");
#else
  if (gz.size() < 2 || static_cast<unsigned char>(gz[0]) != 0x1f || static_cast<unsigned char>(gz[1]) != 0x8b)
    return ParseError(name + ": not a gzip file (bad magic)");
  z_stream zs{};
  if (inflateInit2(&zs, 15 + 16) != Z_OK) return InternalError(name + ": inflateInit2 failed");
  std::string out;
  out.resize(std::min<uint64_t>(max_output_bytes, std::max<uint64_t>(gz.size() * 4, 4096)));
  size_t in_pos = 0, out_pos = 0;
  Status failure;
  while (true) {
    if (out_pos == out.size()) {
      if (out.size() >= max_output_bytes) {
        failure = LimitExceeded(name + ": decompressed data larger than " + std::to_string(max_output_bytes) + " bytes");
        break;
      }
      out.resize(std::min<uint64_t>(max_output_bytes, out.size() * 2));
    }
    const size_t in_chunk = std::min<size_t>(gz.size() - in_pos, 1u << 30);
    const size_t out_chunk = std::min<size_t>(out.size() - out_pos, 1u << 30);
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(gz.data() + in_pos));
    zs.avail_in = static_cast<uInt>(in_chunk);
    zs.next_out = reinterpret_cast<Bytef*>(&out[out_pos]);
    zs.avail_out = static_cast<uInt>(out_chunk);
    int rc = inflate(&zs, Z_NO_FLUSH);
    in_pos += in_chunk - zs.avail_in;
    out_pos += out_chunk - zs.avail_out;
    if (rc == Z_STREAM_END) {
      if (in_pos == gz.size()) break;
      // Another gzip member follows: keep going.
      if (inflateReset(&zs) != Z_OK) {
        failure = InternalError(name + ": inflateReset failed");
        break;
      }
      continue;
    }
    if (rc == Z_OK) {
      if (in_pos == gz.size() && zs.avail_out != 0) {
        failure = ParseError(name + ": truncated gzip data");
        break;
      }
      continue;
    }
    if (rc == Z_BUF_ERROR) {
      if (in_pos == gz.size() && zs.avail_out != 0) {
        failure = ParseError(name + ": truncated gzip data");
        break;
      }
      continue;
    }
    failure = ParseError(name + ": corrupt gzip data" + (zs.msg ? std::string(" (") + zs.msg + ")" : std::string()));
    break;
  }
  inflateEnd(&zs);
  if (!failure.ok()) return failure;
  out.resize(out_pos);
  return out;
#endif
}

}  // namespace silk
