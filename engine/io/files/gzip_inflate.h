// gzip decompression for "x.ply.gz"-style inputs, with an output size limit against
// decompression bombs. Needs zlib (SILK_HAVE_ZLIB); without it every call is an error.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "core/status.h"

namespace silk {

StatusOr<std::string> GunzipBytes(std::string_view gz, const std::string& name, uint64_t max_output_bytes);

}  // namespace silk
