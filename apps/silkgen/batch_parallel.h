// SPDX-License-Identifier: MIT
// silkgen --batch --parallel R: up to R meshes decoded together (libsilk's silk_batch, C API 1.6),
// each output written as its mesh ends and the report and the [k/n] lines in input order, so the
// outputs, report rows (timings aside) and exit status are those of --parallel 1.
#pragma once
#include <string>
#include <vector>

#include "batch_inputs.h"
#include "batch_options.h"
#include "batch_report.h"
#include "batch_run.h"
#include "batch_steps.h"
#include "silk/silk.hpp"

namespace silkgen {

// Every input of `mine` through one silk_batch on `model`; stops adding after a signal (the inputs
// in flight end cancelled) or when the report cannot be written (*error names it).
Tally RunInputsParallel(const BatchArgs& args, const BatchSettings& settings, const std::vector<BatchInput>& mine,
                        const silk_cpp::Model& model, const BatchRunInfo& run, BatchReport& report, std::string* error);

}  // namespace silkgen
