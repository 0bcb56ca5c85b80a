// clothsim bench accuracy SCENE: error against a converged RK4 reference, for each integrator,
// time step and backend, against the wall time it cost; the CSV and a log-log plot of the
// Pareto front (bench/accuracy.gp).
#include "bench/bench_accuracy.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "bench/bench.h"
#include "model/errors.h"
#include "model/stability.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"

namespace cloth::app {
namespace {

using Options = AccuracyOptions;

constexpr double kConverged = 1e-9;         // reference: change on halving / extent
constexpr long kReferenceSteps = 1L << 21;  // most steps the reference may take
constexpr long kMostSteps = 1L << 30;       // most steps one --dt may ask for

struct Run {
    SimState state;  // the final state (empty when unstable)
    bool unstable = false;
    long steps = 0;   // steps completed
    double wall = 0;  // stepping and reading back [s]
    SolveStats solve;
};

Run runScene(const Scene& scene, const BackendChoice& choice, long steps) {
    const std::unique_ptr<Solver> solver = makeSolver(scene, choice);
    Run run;
    const auto t0 = std::chrono::steady_clock::now();
    const StepResult r = solver->step(steps);
    if (!r.unstable) run.state = solver->read();
    run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.unstable = r.unstable || !allFinite(run.state);
    run.steps = r.unstable ? std::max(0L, r.firstBadStep - 1) : r.stepsTaken;
    run.solve = solver->solveStats();
    return run;
}

// runScene, repeated while the runs so far took less than `minWall` in all (at most 20 times):
// a run of a few microseconds is timed by its fastest repetition, not by one noisy reading.
Run timedRun(const Scene& scene, const BackendChoice& choice, long steps, double minWall) {
    Run best = runScene(scene, choice, steps);
    double total = best.wall;
    for (int rep = 1; rep < 20 && total < minWall; ++rep) {
        const Run again = runScene(scene, choice, steps);
        total += again.wall;
        best.wall = std::min(best.wall, again.wall);
    }
    return best;
}

// Largest |a_k − b_k| over the vertices [m].
double maxDistance(const SimState& a, const SimState& b) {
    double d = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k)
        d = std::max(d, glm::length(a.positions[k] - b.positions[k]));
    return d;
}

struct Reference {
    SimState initial, state;
    double dt = 0, wall = 0;
    double change = INFINITY;  // of the last halving / extent (none yet: infinite)
    long steps = 0;
    bool converged = false;
};

// RK4 in double, Δt = T/n, n doubled until the positions move by < kConverged·extent.
Reference converge(const Scene& scene, double time, double extent, long maxSteps) {
    Scene s = scene;
    s.integrator.method = Method::Rk4;
    const double bound = estimateStability(scene, 40).tightDt(Method::Rk4);
    double start = scene.integrator.dt;
    if (std::isfinite(bound) && bound > 0) start = std::min(start, 0.5 * bound);
    long n = std::max(16L, long(std::ceil(time / start)));
    const BackendChoice cpu{Backend::Cpu, Precision::Double, 0};
    Reference ref;
    ref.initial = makeSolver(s, cpu)->read();
    auto runAt = [&](long steps) {
        s.integrator.dt = time / double(steps);
        Run r = runScene(s, cpu, steps);
        ref.wall += r.wall;
        return r;
    };
    Run previous = runAt(n);
    while (previous.unstable && 2 * n <= maxSteps) previous = runAt(n *= 2);
    if (previous.unstable) throw std::runtime_error("the RK4 reference is unstable at every dt");
    while (2 * n <= maxSteps) {
        Run next = runAt(n *= 2);
        if (next.unstable) throw std::runtime_error("the RK4 reference became unstable on halving");
        ref.change = maxDistance(previous.state, next.state) / extent;
        previous = std::move(next);
        if (ref.change < kConverged) break;
    }
    ref.converged = ref.change < kConverged;
    ref.state = std::move(previous.state);
    ref.steps = n;
    ref.dt = time / double(n);
    return ref;
}

// Time steps for `m`: the ladder from its predicted (tight) bound down by factors of 2.
std::vector<double> ladder(Method m, const StabilityBound& b, double time, int rungs) {
    double top = b.tightDt(m);
    if (!std::isfinite(top) || top <= 0) {
        double largest = 0;
        for (Method other : kMethods)
            if (std::isfinite(b.tightDt(other))) largest = std::max(largest, b.tightDt(other));
        top = largest > 0 ? 4 * largest : time / 8;
    }
    std::vector<double> dts;
    for (int k = 0; k < rungs; ++k) dts.push_back(std::min(top, time) / std::pow(2.0, k));
    return dts;
}

struct Row {
    BenchTarget target;
    Method method;
    double dt, tightDt;
    Run run;
    double rms = NAN, max = NAN, strain = NAN, energyJ = NAN, energyRel = NAN;
};

void measureErrors(Row& row, const Scene& scene, const Reference& ref, double extent) {
    if (row.run.unstable) return;
    const SimState& s = row.run.state;
    double sum = 0;
    for (std::size_t k = 0; k < s.positions.size(); ++k) {
        const glm::dvec3 d = s.positions[k] - ref.state.positions[k];
        sum += glm::dot(d, d);
    }
    row.rms = std::sqrt(sum / double(s.positions.size())) / extent;
    row.max = maxDistance(s, ref.state) / extent;
    row.strain = std::abs(maxStrain(scene, s) - maxStrain(scene, ref.state));
    const double eRef = energy(scene, ref.state).total();
    row.energyJ = energy(scene, s).total() - eRef;
    const double exchanged = std::abs(eRef - energy(scene, ref.initial).total());
    row.energyRel = exchanged > 0 ? row.energyJ / exchanged : NAN;
}

constexpr const char* kColumns =
    "target,backend,precision,method,dt_s,steps,status,sim_time_s,pos_rms_err_rel,"
    "pos_max_err_rel,strain_err,energy_drift_J,energy_drift_rel,wall_s,wall_per_sim_s,"
    "wall_per_step_s,force_evals_per_step,cg_iterations_per_step,predicted_tight_dt_s\n";

std::string csvRow(const Row& r) {
    const double simTime = double(r.run.steps) * r.dt;
    const double perStep = r.run.steps > 0 ? r.run.wall / double(r.run.steps) : NAN;
    const double cg = r.run.steps > 0 ? double(r.run.solve.iterations) / double(r.run.steps) : NAN;
    std::vector<std::string> cells{r.target.id(),
                                   backendName(r.target.backend),
                                   precisionName(r.target.precision),
                                   methodName(r.method),
                                   cell(r.dt),
                                   std::to_string(r.run.steps),
                                   r.run.unstable ? "unstable" : "stable"};
    for (double x : {simTime, r.rms, r.max, r.strain, r.energyJ, r.energyRel, r.run.wall,
                     simTime > 0 ? r.run.wall / simTime : NAN, perStep,
                     double(forceEvaluationsPerStep(r.method)), cg, r.tightDt})
        cells.push_back(cell(x));
    return join(cells, ',') + "\n";
}

void printRow(const Row& r) {
    const double simTime = double(r.run.steps) * r.dt;
    std::printf("%-11s %-16s %-10.4g %-9ld %-9s %-10.3g %-10.3g %-10.3g %-10.3g\n",
                r.target.id().c_str(), methodName(r.method), r.dt, r.run.steps,
                r.run.unstable ? "unstable" : "stable", r.rms, r.max, r.strain,
                simTime > 0 ? r.run.wall / simTime : NAN);
    std::fflush(stdout);
}

std::string referenceLine(const Reference& ref) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "reference: rk4 cpu double, dt = %.6g s (%ld steps); halving dt changed the "
                  "positions by %.3g x extent (%s %g: %s)",
                  ref.dt, ref.steps, ref.change, ref.change < kConverged ? "<" : ">=", kConverged,
                  ref.converged ? "converged" : "NOT converged, step limit reached");
    return buf;
}

void plotRows(const Options& o, const Scene& scene, const std::string& csv,
              const std::vector<Row>& rows, double time) {
    double worst = 0;
    std::vector<std::pair<Method, BenchTarget>> curves;
    for (const Row& r : rows) {
        if (std::isfinite(r.rms)) worst = std::max(worst, r.rms);
        if (curves.empty() || curves.back().first != r.method ||
            curves.back().second.id() != r.target.id())
            curves.emplace_back(r.method, r.target);
    }
    const double top = worst > 0 ? std::pow(10.0, std::ceil(std::log10(worst)) + 1) : 1;
    PlotVars vars = seriesVars(curves);
    vars.insert(vars.end(), {{"csv", csv},
                             {"unstable_y", cell(top)},
                             {"title", scene.name + ": position error at t = " + cell(time) +
                                           " s against cost"}});
    for (const std::string& f :
         plot(o.scriptDir, "accuracy.gp", outputPath(o.out, "accuracy_" + o.label), vars))
        std::printf("wrote %s\n", f.c_str());
}

// Every target × integrator × Δt, each Δt rounded to divide `time`, measured against `ref`.
std::vector<Row> runAll(const Options& o, const Scene& scene,
                        const std::vector<BenchTarget>& targets, const Reference& ref, double time,
                        double extent) {
    const StabilityBound bound = estimateStability(scene, 40);
    std::vector<Row> rows;
    for (const BenchTarget& t : targets)
        for (Method m : o.methods) {
            if (!runsMethod(t, scene, m, o.base())) continue;
            for (double wanted : o.dts.empty() ? ladder(m, bound, time, o.rungs) : o.dts) {
                const long n = std::max(1L, std::lround(time / wanted));
                Scene s = scene;
                s.integrator.method = m;
                s.integrator.dt = time / double(n);
                Row row{t, m, s.integrator.dt, bound.tightDt(m),
                        timedRun(s, choiceFor(t, o.base()), n, o.quick ? 0.005 : 0.05)};
                measureErrors(row, scene, ref, extent);
                printRow(row);
                rows.push_back(std::move(row));
            }
        }
    return rows;
}

}  // namespace

int runBenchAccuracy(const AccuracyOptions& options) {
    AccuracyOptions o = options;
    const Scene scene = loadBenchScene(o);
    const std::string csv = outputPath(o.out, "accuracy_" + o.label + ".csv");
    double time = o.time > 0 ? o.time : std::min(0.5, scene.duration);
    if (o.quick && o.time == 0) time = std::min(time, 0.1);
    // Each Δt asked for takes time/Δt steps: refused before anything runs where that is past
    // kMostSteps (a Δt of 1e-300 s rounded its count to 1 and ran at Δt = time).
    for (double dt : o.dts)
        if (!(time / dt <= double(kMostSteps)))
            throw InputError("command line", "--dt",
                             cell(dt) + " s would take " + cell(time / dt) + " steps over " +
                                 cell(time) + " s; at most " + cell(double(kMostSteps)));
    const double extent = scene.grid().extent() > 0 ? scene.grid().extent() : 1.0;
    const auto targets = availableTargets(
        parseTargets("--backend", o.backend, {Precision::Double, Precision::Float}), scene,
        o.backend == "gpu", o.base());

    const Reference ref = converge(scene, time, extent, o.quick ? 1L << 17 : kReferenceSteps);
    std::printf("%s: %d x %d vertices, t = %g s, extent %.4g m\n%s [%.2f s]\n", scene.name.c_str(),
                scene.cloth.nu, scene.cloth.nv, time, extent, referenceLine(ref).c_str(), ref.wall);
    std::printf("%-11s %-16s %-10s %-9s %-9s %-10s %-10s %-10s %-10s\n", "target", "method", "dt_s",
                "steps", "status", "rms/ext", "max/ext", "strain_err", "wall/sim_s");
    const std::vector<Row> rows = runAll(o, scene, targets, ref, time, extent);
    std::string text = "# clothsim bench accuracy " + scene.source + ", t = " + cell(time) +
                       " s, extent " + cell(extent) + " m\n# " + referenceLine(ref) + "\n" +
                       kColumns;
    for (const Row& r : rows) text += csvRow(r);
    writeWholeFile(csv, text);
    std::printf("wrote %s\n", csv.c_str());
    plotRows(o, scene, csv, rows, time);
    return kOk;
}

}  // namespace cloth::app
