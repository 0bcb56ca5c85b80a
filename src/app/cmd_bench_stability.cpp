// clothsim bench stability: its options from the command line, then bench/bench_stability.h runs
// it.
#include <cstdio>

#include "app/bench_flags.h"
#include "app/cli.h"
#include "bench/bench_stability.h"
#include "model/errors.h"

namespace cloth::app {
namespace {

using Options = StabilityOptions;

constexpr const char* kHelp = R"(usage: clothsim bench stability SCENE [options]

For each integrator and each structural stiffness (the other spring families scaled with it),
finds the largest stable time step by bisection and prints it beside the predicted bounds:
'safe' from Gershgorin's bound on lambda_max, 'tight' from a power iteration. For explicit
Euler it repeats the sweep over the mass and over the damping (stable iff dt < mu/lambda_max
and dt < 2m/mu). Runs on the CPU (double) and the GPU (float).

A trial runs the scene linearised about its rest state (no gravity, wind or colliders) from a
velocity kick along the stiffest mode, for --time of simulated time (at least 200 steps, or
--max-steps where that is fewer; at most --max-steps). It is unstable when the state runs away
(not finite, or 1e4 times the kick's speed), or, for explicit Euler, when its discrete energy
|v|^2 + c<x,v> + <x,Hx>/m grows (that integrator leaves its bound too slowly to run away in a
short trial). Methods stable at --cap are reported as stable to the cap (implicit Euler has no
predicted bound).

options:
  --backend cpu|gpu|both    where to run (default both; without a GPU, both means cpu)
  --methods LIST            integrators, comma-separated, or all (default all)
  --sweeps LIST             stiffness,mass,damping (default all three)
  --stiffness LIST          structural stiffnesses [N/m] (default 1e1,1e2,...,1e7)
  --mass LIST               masses per vertex [kg] (default the scene's times 1e-4 ... 1e2)
  --damping LIST            dampings [N*s/m] (default the scene's times 1e-3 ... 1e3)
  --time T                  simulated time of one trial [s] (default 0.5)
  --max-steps N             most steps of one trial (default 20000)
  --tolerance R             bisection ends at unstable/stable <= 1 + R (default 0.02)
  --cap DT                  largest time step tried [s] (default 1)
  --set KEY.PATH=JSON       override a scene key (repeatable), e.g. --set cloth.resolution=[8,8]
  --out DIR                 output folder (default bench/results)
  --label NAME              file names stability_NAME.csv/.png/.svg (default the scene's name)
  --threads N               CPU threads (default automatic)
  --quick                   a small run: 3 values per sweep, 2000 steps, 5% tolerance
  --help                    this text

writes DIR/stability_NAME.csv (one row per sweep value, backend and integrator) and the plots
DIR/stability_NAME.png/.svg (stiffness), stability_mass_NAME, stability_damping_NAME.
)";

std::vector<std::string> parseSweeps(const std::string& flag, const std::string& value) {
    std::vector<std::string> sweeps;
    std::string rest = value + ",";
    for (size_t at; (at = rest.find(',')) != std::string::npos; rest.erase(0, at + 1)) {
        const std::string s = rest.substr(0, at);
        if (s != "stiffness" && s != "mass" && s != "damping")
            throw InputError("command line", flag,
                             "expected stiffness, mass or damping, got '" + s + "'");
        sweeps.push_back(s);
    }
    return sweeps;
}

bool parseFlag(const std::string& f, Args& args, Options& o) {
    if (parseCommonFlag(f, args, o)) return true;
    if (f == "--sweeps")
        o.sweeps = parseSweeps(f, args.value(f));
    else if (f == "--stiffness")
        o.stiffness = parsePositiveList(f, args.value(f));
    else if (f == "--mass")
        o.mass = parsePositiveList(f, args.value(f));
    else if (f == "--damping")
        o.damping = parsePositiveList(f, args.value(f));
    else if (f == "--time")
        o.probe.trialTime = parsePositive(f, args.value(f));
    else if (f == "--max-steps")
        o.probe.maxSteps = args.positiveInt(f);
    else if (f == "--tolerance")
        o.probe.tolerance = parsePositive(f, args.value(f));
    else if (f == "--cap")
        o.probe.cap = parsePositive(f, args.value(f));
    else
        return false;
    return true;
}

// Returns false when --help was asked for.
bool parse(Args& args, Options& o) {
    bool steps = false, tolerance = false;
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help") return false;
        steps |= f == "--max-steps";
        tolerance |= f == "--tolerance";
        if (!parseFlag(f, args, o)) args.unknown(f);
    }
    if (o.scenePath.empty())
        throw InputError("command line", "SCENE", "bench stability needs a scene file");
    parseTargets("--backend", o.backend, {Precision::Double});  // checks the value early
    if (o.quick && !steps) o.probe.maxSteps = 2000;
    if (o.quick && !tolerance) o.probe.tolerance = 0.05;
    o.probe.minSteps = std::min(o.probe.minSteps, o.probe.maxSteps);
    return true;
}

}  // namespace

int benchStabilityCommand(Args& args) {
    return benchSubcommand<Options>(args, kHelp, parse, runBenchStability);
}

}  // namespace cloth::app
