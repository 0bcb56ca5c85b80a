// How `clothsim bench speed` measures: the machine (CPU model, memory available) and the timing
// loop that turns a solver's step(n) into a median time per step and a table row.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "bench/bench_speed.h"

namespace cloth::app {

std::string cpuModel();           // /proc/cpuinfo's model name
std::uint64_t availableMemory();  // /proc/meminfo's MemAvailable [B]

struct Timing {
    long stepsPerBatch = 1;
    int batches = 0;
    double secondsPerStep = 0, deviceSecondsPerStep = 0;  // medians
};

// Thrown by timeSteps when the run went unstable: that row is reported, not timed.
struct BecameUnstable {};

// Warm-up, then a batch grown by doubling to 50 ms (5 ms with `quick`), then batches until 0.3 s
// (30 ms) and 5 batches; the median batch. `step(n)` runs n steps and returns false if the run
// went unstable (then BecameUnstable is thrown); `device()` gives the device's seconds per step of
// the last call (0 when it has none).
Timing timeSteps(const std::function<bool(long)>& step, const std::function<double()>& device,
                 bool quick);

// A row of the table from a timing: rates, the bytes a step must move, the fraction of
// `bandwidth` [GB/s] they reach.
SpeedRow makeRow(int side, const std::string& target, const std::string& method, int threads,
                 const Timing& t, double minBytesPerVertex, double bandwidth);

}  // namespace cloth::app
