// SPDX-License-Identifier: MIT
// silkgen --batch: one model, one generator, every input of this process's shard in turn, each
// output written atomically and each result reported as it ends (docs/batch.md).
#pragma once
#include <cstdint>
#include <string>

#include "batch_options.h"
#include "silk/silk.h"

namespace silkgen {

// The settings of a single silkgen run, applied to every input.
struct BatchSettings {
  std::string model_dir, output_dir;
  silk_model_params model = silk_model_default_params();
  silk_generate_params generate = silk_generate_default_params();  // callbacks are the batch's own
  silk_save_params save = silk_save_default_params();
  uint64_t seed = 0;
  bool quiet = false;
};

// The exit status: 0 every input ok or skipped, 1 some failed (or nothing could start), 2 bad
// options, 128 + signal after SIGINT/SIGTERM (the mesh in progress abandoned, no partial file).
int RunBatch(const BatchArgs& args, const BatchSettings& settings);

}  // namespace silkgen
