// bench speed's GPU sweep flags (bench_speed_gpu.h).
#include "bench/bench_speed_gpu.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "model/errors.h"

namespace cloth::app {
std::vector<GpuOptions> GpuSweepOptions::variants() const {
    std::vector<GpuOptions> all;
    for (const auto& [x, y] : workGroups)
        for (ForcesKernel f : forces)
            for (StepDispatch d : dispatches) all.push_back({x, y, checkEvery, f, d});
    return all;
}

}  // namespace cloth::app
