// clothsim bench accuracy: the options it takes and the run (app/cmd_bench_accuracy.cpp reads the
// options from the command line).
#pragma once

#include "bench/bench.h"

namespace cloth::app {

struct AccuracyOptions : BenchCommonOptions {
    AccuracyOptions() { methods.assign(std::begin(kMethods), std::end(kMethods)); }
    std::vector<double> dts;  // empty: the ladder
    double time = 0;          // 0: the default
    int rungs = 6;
};

// Runs the bench and writes its CSV and plots; returns the exit code.
int runBenchAccuracy(const AccuracyOptions& options);

}  // namespace cloth::app
