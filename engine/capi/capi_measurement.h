// SPDX-License-Identifier: MIT
// Measurement modes of a silk_generator that are no part of silk.h: generation without the
// grammar mask, as the official network's own loop runs, for in-tree comparisons (tests/, bench/
// and tools linked against silk_static). libsilk.so exports none of it (only silk_* leaves it).
#pragma once
#if defined(SILK_HAVE_RUNTIME)
#include "silk/silk.h"

namespace silk::capi {

// on: the generator's later generations draw ids without the grammar mask (the grammar only
// watches: silk_generate_stats.illegal_at and the report's "grammar" name the first id it
// rejects; the mesh is the legal prefix; surface and face guidance, which narrow the mask, do
// nothing). off: the mask again. SILK_ERR_INVALID_ARGUMENT for NULL, SILK_ERR_BUSY while a call
// or a step-wise generation is in progress on it.
silk_status SetUnconstrained(silk_generator* generator, bool on);

}  // namespace silk::capi
#endif
