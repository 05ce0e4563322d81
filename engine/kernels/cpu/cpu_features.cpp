// SPDX-License-Identifier: MIT
// The CPU's instruction sets, asked once per process (cpu_features.h).
#include "kernels/cpu/cpu_features.h"

#ifdef SILK_KERNELS_X86
namespace silk {

bool CpuHasAvx2() {
  static const bool has =
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("f16c");
  return has;
}

bool CpuHasAvx512() {
  static const bool has = CpuHasAvx2() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
  return has;
}

bool CpuHasAvx512Vnni() {
  static const bool has = CpuHasAvx2() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                          __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512vnni");
  return has;
}

}  // namespace silk
#endif
