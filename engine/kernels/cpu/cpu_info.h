// SPDX-License-Identifier: MIT
// Physical core count for the default thread count: onnxruntime's matrix kernels gain
// nothing from SMT siblings, so threads default to cores, not logical CPUs.
#pragma once

namespace silk {

// Distinct (package, core) pairs among the CPUs this process may run on; falls back to
// the logical CPU count when the topology is not readable. Always >= 1.
int PhysicalCoreCount();

}  // namespace silk
