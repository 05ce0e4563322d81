// SPDX-License-Identifier: MIT
// C API: the encoder's points of a generation, put back into the input's frame (silkgen
// --save-points), so a caller can see what the model saw, estimated normals included.
#if defined(SILK_HAVE_RUNTIME)
#include <algorithm>
#include <string>
#include <vector>

#include "capi/capi_generator.h"

using silk::capi::BusyLock;
using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

extern "C" {

silk_status silk_generator_copy_points(silk_generator* g, double* out, size_t capacity, size_t* out_count) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE(g, "silk_generator_copy_points: generator is NULL");
    BusyLock lock(g);
    if (!lock.ok())
      return SetError(SILK_ERR_BUSY,
                      "silk_generator_copy_points: generator busy (in use on another thread; use one "
                      "generator per thread)");
    if (!g->has_result && !g->session.active())
      return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_copy_points: no generation started");
    const std::vector<double> points = g->session.InputFramePoints();
    if (silk_status c;
        !silk::capi::BeginCopy("silk_generator_copy_points", out, capacity, points.size(), out_count, &c))
      return c;
    std::copy(points.begin(), points.end(), out);
    return Ok();
  });
}

}  // extern "C"
#endif
