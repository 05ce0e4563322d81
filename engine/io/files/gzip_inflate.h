// SPDX-License-Identifier: MIT
// gzip decompression for "x.ply.gz"-style inputs, with an output size limit against
// decompression bombs. Needs zlib (SILK_HAVE_ZLIB); without it every call is an error.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "core/status.h"

namespace silk {

// Inflates every gzip member of `gz`. Streaming in two passes: the first counts the output
// through a small scratch buffer and stops with kLimitExceeded ("<name>: gzip data inflates
// past ...") as soon as the total passes max_output_bytes, so a bomb costs no memory; the
// second inflates into a buffer of exactly the counted size.
StatusOr<std::string> GunzipBytes(std::string_view gz, const std::string& name, uint64_t max_output_bytes);

}  // namespace silk
