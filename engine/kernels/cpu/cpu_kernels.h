// SPDX-License-Identifier: MIT
// What libsilk's own CPU kernels (the ai.silk onnxruntime ops) share: work spread by a
// parallel-for the caller supplies (onnxruntime's intra-op pool), and a switch between the
// vectorized rows and plain C++ that tests use to compare the two.
#pragma once
#include <cstddef>

namespace silk {

// Runs work(state, index) for index in [0, count), possibly in parallel.
using ParallelForFn = void (*)(void* context, void (*work)(void* state, size_t index), void* state, size_t count);

// work(state, i) for i in [0, count): through parallel_for when there is one and more than one
// task, else in order on this thread.
inline void RunTasks(ParallelForFn parallel_for, void* context, void (*work)(void*, size_t), void* state,
                     size_t count) {
  if (parallel_for && count > 1) {
    parallel_for(context, work, state, count);
  } else {
    for (size_t i = 0; i < count; ++i) work(state, i);
  }
}

// kBest: the widest vectorized rows the CPU has; kAvx2: the 256-bit ones even where it has wider
// ones (so tests check both on one machine); kScalar: plain C++.
enum class RowKernels { kBest, kAvx2, kScalar };

}  // namespace silk
