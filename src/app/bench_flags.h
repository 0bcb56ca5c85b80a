// The flags every bench subcommand shares, read from the command line into bench/'s options.
#pragma once

#include <cstdio>
#include <string>

#include "app/backend_flags.h"
#include "app/cli.h"
#include "bench/bench.h"
#include "bench/bench_speed_gpu.h"

namespace cloth::app {

int benchCommand(Args& args);           // cmd_bench.cpp: bench accuracy|stability|speed|realtime
int benchAccuracyCommand(Args& args);   // cmd_bench_accuracy.cpp
int benchStabilityCommand(Args& args);  // cmd_bench_stability.cpp
int benchSpeedCommand(Args& args);      // cmd_bench_speed.cpp
int benchRealtimeCommand(Args& args);   // cmd_bench_realtime.cpp

// Takes flag `f` if it is one of the common ones (--backend, --methods, --set, --out, --label,
// --threads, --quick) and returns true; false leaves it to the subcommand.
bool parseCommonFlag(const std::string& f, Args& args, BenchCommonOptions& o);

// --sizes LIST: whole grid sides from 2 to 65535, comma-separated; InputError naming `flag`.
std::vector<int> parseSizes(const std::string& flag, const std::string& value);

// --workgroups LIST, --gpu-forces global|tiled|both, --gpu-dispatch LIST, --check-every N,
// --pass-times: true when `flag` was one of them (its value taken from `args` into `o`).
// InputError naming the flag for a bad value.
bool parseGpuSweepFlag(const std::string& flag, Args& args, GpuSweepOptions& o);

// A bench subcommand: its options start from the environment's backend tuning and script folder,
// `parse` reads the command line into them (false: --help was asked for, then `help` is
// printed), and `run` runs the bench.
template <typename Options>
int benchSubcommand(Args& args, const char* help, bool (*parse)(Args&, Options&),
                    int (*run)(const Options&)) {
    Options o;
    o.tuning = backendChoiceFromEnvironment();
    o.scriptDir = benchDirFromEnvironment();
    if (!parse(args, o)) {
        std::fputs(help, stdout);
        return kOk;
    }
    return run(o);
}

}  // namespace cloth::app
