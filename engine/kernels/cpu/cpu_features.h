// SPDX-License-Identifier: MIT
// The x86 instruction sets libsilk's kernels choose between at run time: one check of the CPU for
// each set, and the target attributes that compile a function for it (the rest of the library
// stays baseline x86-64, so a vectorized function runs only after its check says yes).
#pragma once

#if (defined(__x86_64__) || defined(_M_X64)) && (defined(__GNUC__) || defined(__clang__))
#define SILK_KERNELS_X86 1
#include <immintrin.h>

#define SILK_TARGET_AVX2 __attribute__((target("avx2,fma,f16c")))
#define SILK_TARGET_AVX512 __attribute__((target("avx2,fma,f16c,avx512f,avx512dq")))
#define SILK_TARGET_AVX512_VNNI __attribute__((target("avx2,fma,f16c,avx512f,avx512bw,avx512vl,avx512vnni")))
// AVX-512 F alone: helpers that functions of both AVX-512 targets inline (vector_sums.h).
#define SILK_TARGET_AVX512F __attribute__((target("avx2,fma,f16c,avx512f")))

// GCC 12's AVX-512 intrinsics pass _mm512_undefined_*() as the unused merge source, which its
// -Wmaybe-uninitialized (or -Wuninitialized) reports once inlined (fixed in later GCC); the values
// are never read. These bracket the AVX-512 code of a file.
#define SILK_AVX512_CODE_BEGIN                                                               \
  _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"") \
      _Pragma("GCC diagnostic ignored \"-Wuninitialized\"")
#define SILK_AVX512_CODE_END _Pragma("GCC diagnostic pop")

namespace silk {

// AVX2, FMA and F16C (SILK_TARGET_AVX2).
bool CpuHasAvx2();
// Those and AVX-512 F and DQ (SILK_TARGET_AVX512).
bool CpuHasAvx512();
// Those of AVX2 and AVX-512 F, BW, VL and VNNI (SILK_TARGET_AVX512_VNNI).
bool CpuHasAvx512Vnni();

}  // namespace silk
#endif
