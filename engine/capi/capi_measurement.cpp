// SPDX-License-Identifier: MIT
// The generator's measurement mode (capi/capi_measurement.h): a flag on the handle that the next
// start passes to the runtime's request, never a silk_generate_params field.
#if defined(SILK_HAVE_RUNTIME)
#include "capi/capi_measurement.h"

#include "capi/capi_generator.h"

namespace silk::capi {

silk_status SetUnconstrained(silk_generator* g, bool on) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g, "SetUnconstrained: generator is NULL");
    BusyLock lock(g);
    if (!lock.ok() || g->session.active())
      return SetError(SILK_ERR_BUSY, "SetUnconstrained: a generation is in progress on this generator");
    g->unconstrained = on;
    return Ok();
  });
}

}  // namespace silk::capi
#endif
