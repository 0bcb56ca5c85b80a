// clothsim bench stability: the options it takes and the run (app/cmd_bench_stability.cpp reads the
// options from the command line).
#pragma once

#include "bench/bench.h"
#include "solver/stability_probe.h"

namespace cloth::app {

struct StabilityOptions : BenchCommonOptions {
    StabilityOptions() { methods.assign(std::begin(kMethods), std::end(kMethods)); }
    std::vector<std::string> sweeps{"stiffness", "mass", "damping"};
    std::vector<double> stiffness, mass, damping;  // empty: the defaults
    ProbeOptions probe;
};

// Runs the bench and writes its CSV and plots; returns the exit code.
int runBenchStability(const StabilityOptions& options);

}  // namespace cloth::app
