// `clothsim bench realtime`: the real-time frontier. For each integrator and target, the largest
// N for which an N×N sheet of a material, draped onto a sphere, simulates T seconds in at most T
// seconds of wall time (T = 1 s), at the largest Δt it stays stable at (implicit methods: one
// step per 1/60 s frame), with the error after T against a fine reference at the same N.
// Its options (app/cmd_bench_realtime.cpp reads them from the command line), the trials and the
// frontier rows (bench_realtime.cpp searches, bench_realtime_trial.cpp times one trial,
// bench_realtime_report.cpp writes the CSV, the JSON, the table and the plot).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "solver/solver.h"

namespace cloth::app {

// How the drape's cloth is modelled: as a material (Scene::vertexMass, slotStiffness,
// dampingRate, bendingStiffness), or as the seed's per-vertex form that carries the material's
// interior vertex mass, springs and drag uniformly (bench_realtime_scene.h, perVertexForm).
enum class ClothForm { Material, PerVertex };
const char* clothFormName(ClothForm f);  // "material", "per-vertex"

struct RealtimeOptions : BenchCommonOptions {
    RealtimeOptions() { methods.assign(std::begin(kMethods), std::end(kMethods)); }
    std::string material = "cotton";  // --material: a preset (model/material_presets.h)
    ClothForm form = ClothForm::Material;
    double time = 1;              // T: simulated time of a trial [s]
    std::vector<int> sizes;       // --sizes: time these N instead of searching
    double tolerance = 0.1;       // the bisection stops at failing/passing N <= 1 + this
    double safety = 0.9;          // explicit Δt = safety × the tight predicted bound
    double referenceFactor = 10;  // the reference's Δt = min(tight bound, rows' Δt) / this
    int maxSize = 2048;           // the search's largest N
    bool error = true;            // run the references and measure the error
    bool allowDebug = false;
};

// Runs the bench and writes its files; returns the exit code.
int runBenchRealtime(const RealtimeOptions& options);

// What became of one trial: an N at one Δt on one target.
enum class TrialStatus {
    RealTime,    // T simulated, stable, in at most T of wall time
    TooSlow,     // T simulated, stable, in more than T
    CutOff,      // stopped early: its wall time ran past the pace by the margin
    Unstable,    // at every Δt tried (halved after each instability)
    DoesNotFit,  // the device cannot hold the grid
};
const char* trialStatusName(TrialStatus s);  // "real_time", "too_slow", ...

struct Trial {
    int n = 0;              // the sheet is n × n vertices
    double dt = 0;          // the step [s]: (1/60 s) / stepsPerFrame
    double tightDt = 0;     // the method's tight predicted bound at this n [s] (inf: none)
    int stepsPerFrame = 1;  // steps per 1/60 s frame
    int halvings = 0;       // Δt halvings after an instability
    int attempts = 1;       // runs at the final Δt (2: a slow one was retried)
    TrialStatus status = TrialStatus::Unstable;
    double simulated = 0;    // simulated time reached [s]
    double wall = 0;         // wall time of the stepping [s]
    double cgPerStep = NAN;  // implicit Euler's conjugate-gradient iterations per step
    long cgMisses = 0;       // solves that stopped at max_iterations
    std::string reason;      // why it was not real time, "" when it was
    SimState state;          // the state after T, kept for a real-time trial (its error)
    bool realTime() const { return status == TrialStatus::RealTime; }
    double wallPerSim() const { return simulated > 0 ? wall / simulated : NAN; }
};

// One integrator on one target: the trials in the order they ran and what they found.
struct Frontier {
    Method method = Method::SymplecticEuler;
    BenchTarget target;
    std::vector<Trial> trials;
    int best = -1;             // index in trials of the largest real-time N (-1: none)
    int fail = -1;             // index of the smallest N above it that failed (-1: none tried)
    double error = NAN;        // RMS |x − x_ref| / extent at the best N after T
    double referenceDt = NAN;  // the reference's Δt [s]
    // How much the reference moves when its Δt is doubled (RMS / extent): errors below it are
    // not resolved.
    double referenceChange = NAN;
    double searchWall = 0;  // wall time of the whole search, reference excluded [s]
    int n() const { return best >= 0 ? trials[std::size_t(best)].n : 0; }
};

struct RealtimeMeta {
    std::string label, material, form, buildType, cpuModel, gpuRenderer, scriptDir;
    std::string materialLine;       // the material's numbers as run
    std::vector<std::string> sets;  // the --set overrides, as given
    double time = 1, tolerance = 0.1, safety = 0.9, referenceFactor = 10;
    bool quick = false, searched = true;
    double totalWall = 0;  // [s]
};

// Writes DIR/realtime_LABEL.csv (the frontier), realtime_LABEL_trials.csv (every trial), .json
// (both), the plot (when gnuplot is there) and the table on stdout.
void reportRealtime(const std::string& outDir, const RealtimeMeta& meta,
                    const std::vector<Frontier>& rows);

}  // namespace cloth::app
