// What libsilk's own CPU kernels (the ai.silk onnxruntime ops) share: work spread by a
// parallel-for the caller supplies (onnxruntime's intra-op pool), and a switch between the
// vectorized rows and plain C++ that tests use to compare the two.
#pragma once
#include <cstddef>

namespace silk {

// Runs work(state, index) for index in [0, count), possibly in parallel.
using ParallelForFn = void (*)(void* context, void (*work)(void* state, size_t index), void* state, size_t count);

// kBest: the vectorized rows where the CPU has them; kScalar: plain C++.
enum class RowKernels { kBest, kScalar };

}  // namespace silk
