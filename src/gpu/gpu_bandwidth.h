// The GPU's memory bandwidth as `clothsim bench speed` measures it: a compute kernel copying one
// large SSBO into another, the bytes read plus the bytes written over the best time.
#pragma once

#include <cstddef>

namespace cloth {

// Copies `bytes` (rounded down to whole vec4s) from one buffer into another `repeats` times after
// one warm-up copy, each timed with glFinish and a steady clock; returns (2·bytes)/best time
// [bytes/s]. Makes the process-wide context if needed: throws GpuUnavailable.
double measureGpuCopyBandwidth(std::size_t bytes, int repeats);

}  // namespace cloth
