// clothsim bench accuracy: its options from the command line, then bench/bench_accuracy.h runs it.
#include <cstdio>

#include "app/bench_flags.h"
#include "app/cli.h"
#include "bench/bench_accuracy.h"
#include "model/errors.h"

namespace cloth::app {
namespace {

using Options = AccuracyOptions;

constexpr const char* kHelp = R"(usage: clothsim bench accuracy SCENE [options]

Runs SCENE to a fixed simulated time with each integrator, time step and backend, and measures
the error of the final state against a reference: RK4 in double on the CPU, its time step halved
until halving changes the positions by less than 1e-9 of the cloth's extent (the achieved change
is printed and written to the CSV). Unstable runs are recorded as unstable, not as errors.

Errors are relative to the extent (the rest diagonal of the cloth): position RMS and maximum over
the vertices, the largest structural strain's difference, and the energy difference from the
reference (J, and relative to the energy the reference exchanged). Costs: wall time per simulated
second and per step (the GPU's includes its synchronisation; making a solver is not counted).

options:
  --backend cpu|gpu|both    cpu runs in double and float, gpu in float (default both; without
                            a GPU, both means cpu)
  --methods LIST            integrators, comma-separated, or all (default all)
  --dt LIST                 time steps [s], comma-separated (default: a ladder from each
                            integrator's predicted bound down by factors of 2; implicit Euler
                            from 4 times the largest bound of the others)
  --rungs N                 steps of that ladder (default 6)
  --time T                  simulated time [s] (default 0.5, or the scene's duration if shorter);
                            each dt is rounded to divide it
  --set KEY.PATH=JSON       override a scene key (repeatable), e.g. --set springs.structural=4000
  --out DIR                 output folder (default bench/results)
  --label NAME              file names accuracy_NAME.csv/.png/.svg (default the scene's name)
  --threads N               CPU threads (default automatic)
  --quick                   a small run: 3 rungs, at most 0.1 s simulated
  --help                    this text
)";

bool parseFlag(const std::string& f, Args& args, Options& o) {
    if (parseCommonFlag(f, args, o)) return true;
    if (f == "--dt")
        o.dts = parsePositiveList(f, args.value(f));
    else if (f == "--rungs")
        o.rungs = args.positiveInt32(f);
    else if (f == "--time")
        o.time = parsePositive(f, args.value(f));
    else
        return false;
    return true;
}

// Returns false when --help was asked for.
bool parse(Args& args, Options& o) {
    bool rungs = false;
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help") return false;
        rungs |= f == "--rungs";
        if (!parseFlag(f, args, o)) args.unknown(f);
    }
    if (o.scenePath.empty())
        throw InputError("command line", "SCENE", "bench accuracy needs a scene file");
    parseTargets("--backend", o.backend, {Precision::Double});  // checks the value early
    if (o.quick && !rungs) o.rungs = 3;
    return true;
}

}  // namespace

int benchAccuracyCommand(Args& args) {
    return benchSubcommand<Options>(args, kHelp, parse, runBenchAccuracy);
}

}  // namespace cloth::app
