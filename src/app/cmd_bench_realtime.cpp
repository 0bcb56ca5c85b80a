// clothsim bench realtime: its options from the command line, then bench/bench_realtime.h runs
// it.
#include <cstdio>

#include "app/bench_flags.h"
#include "app/cli.h"
#include "bench/bench_realtime.h"
#include "model/errors.h"
#include "model/material_presets.h"

namespace cloth::app {
namespace {

using Options = RealtimeOptions;

constexpr const char* kHelp = R"(usage: clothsim bench realtime [options]

The real-time frontier: for each integrator and target (the CPU in float and double, the GPU in
float), the largest N for which an N x N sheet of a material simulates T = 1 s in at most 1 s of
wall time. The scene is the drape: a 1 m x 1 m sheet, horizontal at y = 0.8 m, falls onto a
sphere of radius 0.25 m resting on the ground plane y = 0, no pins.

Time step: explicit methods (explicit and symplectic Euler, Verlet, RK4) take 0.9 x their tight
predicted bound at that N (power iteration at the rest state, model/stability.h), implicit Euler
and vbd one 1/60 s frame; at most one frame either way, steps per frame = ceil((1/60 s) / dt). A run that
turns unstable (or has a spring past max_strain at the end of any frame) is retried at half the
dt, up to 4 times; each row says how often. A trial steps against the steady clock in calls of
one step, then twice as many while a call takes under 5 ms, up to a frame, none across the end
of a frame (the GPU finishes its work before the call returns), after one warm-up step whose
state is discarded, and is cut off once its wall time passes 1.5 x the simulated time + 50 ms;
the strain check of each frame is off the clock. A run that is too slow or cut off is run
once more and the faster kept (the machine may be shared: contention only slows a run down).

Search: N = 8, 16, 32, ... while real time, then bisection between the last N that was and the
first that was not, until they are within --tolerance of each other. Error: the frontier's state
after T against symplectic Euler on the CPU in double, same N, at a tenth of its tight bound or
of the smallest dt of the rows at that N (explicit Euler's), whichever is smaller: RMS over
vertices of |x - x_ref| divided by the sheet's extent (its diagonal). One reference per N, run
again at twice its dt: how far that moves it (reference_change_rel) is the floor under which an
error is not resolved.

options:
  --material NAME       a preset: cotton (default), silk, denim, wool, polyester, rubber;
                        --set material.KEY=VALUE overrides one of its numbers
  --form material|per-vertex
                        the cloth as the material (default: lumped vertex masses, membrane
                        springs, drag and bending energy, docs/physics.md), or in the seed's
                        per-vertex form: every vertex an interior vertex's mass, the same
                        membrane springs and drag, no bending (what uniform masses cost)
  --backend cpu|gpu|both   where to run (default both; without a GPU, both means cpu)
  --methods LIST        integrators, comma-separated, or all (default all)
  --sizes LIST          time these N only (no search); the frontier is the largest of them
                        that is real time
  --time T              simulated time of a trial [s] (default 1; the criterion stays wall time
                        <= simulated time)
  --tolerance R         bisection ends when the failing N <= (1 + R) x the passing N (default 0.1)
  --safety F            explicit dt = F x the tight predicted bound, 0 < F <= 1 (default 0.9)
  --reference-factor F  the reference's dt = min(its tight bound, the rows' dt) / F, F >= 1
                        (default 10)
  --max-size N          largest N the search tries (default 2048)
  --no-error            no reference runs: the error columns stay empty (for re-timing)
  --set KEY.PATH=JSON   override a scene key (repeatable), e.g. --set material.bend=1e-4;
                        not the keys the bench sets: cloth.resolution, integrator.method,
                        integrator.dt, duration, material.preset (--material)
  --out DIR             output folder (default bench/results)
  --label NAME          file names realtime_NAME.* (default the material's name, with
                        _per_vertex for --form per-vertex)
  --threads N           CPU threads (default automatic)
  --quick               a small run for CI: T = 0.25 s, tolerance 0.25, reference factor 4,
                        max size 128
  --allow-debug         run in a Debug build (refused otherwise: its timings mean nothing)
  --help                this text

writes DIR/realtime_NAME.csv (the frontier: one row per integrator and target, with its dt, steps
per frame, wall time per simulated second, the next N tried and the error),
realtime_NAME_trials.csv (every trial), realtime_NAME.json (both), and the plot of wall time per
simulated second against N, realtime_NAME.png/.svg.
)";

// A number in [lo, hi]; InputError naming the flag otherwise.
double parseInRange(const std::string& flag, const std::string& value, double lo, double hi,
                    const char* expected) {
    const double x = parsePositive(flag, value);
    if (x < lo || x > hi)
        throw InputError("command line", flag,
                         std::string("expected ") + expected + ", got '" + value + "'");
    return x;
}

// The keys the bench sets for each trial: a --set of one of them, or of an object holding one,
// would be overwritten or would break the search.
void checkSets(const std::vector<std::string>& sets) {
    for (const std::string& set : sets) {
        const std::string key = set.substr(0, set.find('='));
        for (const std::string owned : {"cloth.resolution", "integrator.method", "integrator.dt",
                                        "duration", "material.preset"})
            if (key == owned || owned.rfind(key + ".", 0) == 0)
                throw InputError("command line", "--set",
                                 "bench realtime sets " + owned +
                                     " itself (N: --sizes; the integrators: --methods; the "
                                     "preset: --material), got '" +
                                     set + "'");
    }
}

bool parseFlag(const std::string& f, Args& args, Options& o) {
    if (f == "--material") {
        o.material = args.value(f);
        if (!materialPreset(o.material))
            throw InputError("command line", f,
                             "unknown material preset '" + o.material + "'; expected one of " +
                                 materialPresetList());
    } else if (f == "--form") {
        const std::string v = args.value(f);
        if (v != "material" && v != "per-vertex")
            throw InputError("command line", f, "expected material or per-vertex, got '" + v + "'");
        o.form = v == "material" ? ClothForm::Material : ClothForm::PerVertex;
    } else if (f == "--sizes") {
        o.sizes = parseSizes(f, args.value(f));
    } else if (f == "--time") {
        o.time = parseInRange(f, args.value(f), 1.0 / 60, 60, "a time from 1/60 s to 60 s");
    } else if (f == "--tolerance") {
        o.tolerance = parseInRange(f, args.value(f), 1e-3, 10, "a ratio from 0.001 to 10");
    } else if (f == "--safety") {
        o.safety = parseInRange(f, args.value(f), 1e-6, 1, "a fraction 0 < F <= 1");
    } else if (f == "--reference-factor") {
        o.referenceFactor = parseInRange(f, args.value(f), 1, 1e4, "a factor from 1 to 1e4");
    } else if (f == "--max-size") {
        o.maxSize = parseSizes(f, args.value(f)).front();
    } else if (f == "--no-error") {
        o.error = false;
    } else if (f == "--allow-debug") {
        o.allowDebug = true;
    } else {
        return false;
    }
    return true;
}

// Returns false when --help was asked for.
bool parse(Args& args, Options& o) {
    bool time = false, tolerance = false, factor = false, maxSize = false;
    while (!args.done()) {
        const std::string f = args.flag();
        if (f == "--help" || f == "-h") return false;
        time |= f == "--time";
        tolerance |= f == "--tolerance";
        factor |= f == "--reference-factor";
        maxSize |= f == "--max-size";
        if (!parseCommonFlag(f, args, o) && !parseFlag(f, args, o)) args.unknown(f);
    }
    parseTargets("--backend", o.backend, {Precision::Float});  // checks the value early
    checkSets(o.sets);
    if (o.quick && !time) o.time = 0.25;
    if (o.quick && !tolerance) o.tolerance = 0.25;
    if (o.quick && !factor) o.referenceFactor = 4;
    if (o.quick && !maxSize) o.maxSize = 128;
    return true;
}

}  // namespace

int benchRealtimeCommand(Args& args) {
    return benchSubcommand<Options>(args, kHelp, parse, runBenchRealtime);
}

}  // namespace cloth::app
