// clothsim bench accuracy|stability|speed|realtime (DESIGN.md §5): picks the benchmark.
#include <cstdio>
#include <cstring>

#include "app/bench_flags.h"
#include "model/errors.h"

namespace cloth::app {
namespace {

constexpr const char* kHelp =
    R"(usage: clothsim bench accuracy|stability|speed|realtime [SCENE] [options]

  accuracy SCENE    error against a converged RK4 reference versus wall time, for every
                    integrator, time step and backend: the CSV and a log-log plot of the
                    Pareto front (error per cost)
  stability SCENE   the largest stable time step of every integrator found by bisection,
                    beside the predicted bounds, over stiffness (and mass and damping for
                    explicit Euler): the CSV and log-log plots
  speed [SCENE]     steps per second of every backend over grid sizes (default scene
                    scenes/hanging.json, denim: the same cloth, finer, at every size),
                    beside the one-thread baseline loop (1x) and the measured CPU
                    triad and GPU copy bandwidths: CSV, JSON, a table and a log-log plot
  realtime          the real-time frontier: for every integrator and backend, the largest
                    N x N sheet of a material (default cotton) draped onto a sphere that
                    simulates 1 s in at most 1 s of wall time, with its dt, steps per frame,
                    wall time per simulated second and error against a fine reference (and
                    how far from converged that is): CSV, JSON, a table and a plot

'clothsim bench accuracy|stability|speed|realtime --help' list the options.
Results go to --out DIR (default bench/results) as CSV (header with units), PNG and SVG plots
(drawn by gnuplot from bench/*.gp; without gnuplot only the CSV is written).

exit codes: 0 ok, 1 internal error, 2 invalid input, 4 GPU asked for and unavailable
)";

}  // namespace

int benchCommand(Args& args) {
    const std::string which = args.done() ? "" : args.next();
    if (which == "--help" || which == "-h") {
        std::fputs(kHelp, stdout);
        return kOk;
    }
    Args sub("bench " + which, [&] {
        std::vector<std::string> rest;
        while (!args.done()) rest.push_back(args.next());
        return rest;
    }());
    if (which == "accuracy") return benchAccuracyCommand(sub);
    if (which == "stability") return benchStabilityCommand(sub);
    if (which == "speed") return benchSpeedCommand(sub);
    if (which == "realtime") return benchRealtimeCommand(sub);
    throw InputError("command line", which.empty() ? "bench" : which,
                     "expected bench accuracy|stability|speed|realtime; see clothsim bench --help");
}

}  // namespace cloth::app
