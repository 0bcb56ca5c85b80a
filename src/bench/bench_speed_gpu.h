// `clothsim bench speed`'s GPU sweep (docs/performance.md): which work-group shapes, forces kernels
// and dispatch modes the GPU rows are timed with, and their flags.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "gpu/gpu_options.h"

namespace cloth::app {

struct GpuSweepOptions {
    std::vector<std::pair<int, int>> workGroups{{16, 16}};
    std::vector<ForcesKernel> forces{ForcesKernel::Global};
    std::vector<StepDispatch> dispatches{StepDispatch::Auto};
    int checkEvery = GpuOptions{}.checkEvery;
    bool passTimes = false;  // time a forces pass, an integrate pass and a copy alone

    // Every combination of the flags, in the order given.
    std::vector<GpuOptions> variants() const;
};

}  // namespace cloth::app
