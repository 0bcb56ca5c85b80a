// clothsim bench stability SCENE: the largest stable Δt of each integrator, measured by bisection
// (solver/stability_probe.h), beside the predicted bounds (model/stability.h), over stiffness, and
// over mass and damping for explicit Euler (the Δt < μ/λ_max law, docs/physics.md).
#include "bench/bench_stability.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "bench/bench.h"
#include "model/errors.h"
#include "model/stability.h"
#include "scene/scene_loader.h"
#include "solver/stability_probe.h"

namespace cloth::app {
namespace {

using Options = StabilityOptions;

// One value of one sweep: the scene it runs and the integrators it measures.
struct Point {
    std::string sweep;
    Scene scene;
    std::vector<Method> methods;
};

std::vector<double> decades(double base, int from, int to, bool quick) {
    std::vector<double> v;
    const int step = quick ? (to - from) / 2 : 1;
    for (int e = from; e <= to; e += step) v.push_back(base * std::pow(10.0, e));
    return v;
}

std::vector<Point> sweepPoints(const Scene& scene, const Options& o) {
    std::vector<Point> points;
    const std::vector<Method> euler{Method::ExplicitEuler};
    for (const std::string& sweep : o.sweeps) {
        if (sweep == "stiffness") {
            if (scene.springs.structural <= 0)
                throw InputError(scene.source, "springs.structural",
                                 "the stiffness sweep scales the structural springs; none here");
            const std::vector<double> ks = !o.stiffness.empty() ? o.stiffness
                                           : o.quick            ? std::vector<double>{1e1, 1e3, 1e5}
                                                                : decades(1, 1, 7, false);
            for (double k : ks) {
                Scene s = scene;
                const double factor = k / scene.springs.structural;
                s.springs = {k, scene.springs.shear * factor, scene.springs.bend * factor};
                points.push_back({sweep, s, o.methods});
            }
        } else if (sweep == "mass") {
            for (double m : !o.mass.empty() ? o.mass : decades(scene.cloth.mass, -4, 2, o.quick)) {
                Scene s = scene;
                s.cloth.mass = m;
                points.push_back({sweep, s, euler});
            }
        } else {
            for (double mu :
                 !o.damping.empty() ? o.damping : decades(scene.damping, -3, 3, o.quick)) {
                Scene s = scene;
                s.damping = mu;
                points.push_back({sweep, s, euler});
            }
        }
    }
    return points;
}

struct Row {
    const Point* point;
    BenchTarget target;
    Method method;
    StabilityBound bound;
    ProbeResult probe;
    double wall = 0;
};

Row measure(const Point& p, const BenchTarget& target, Method method, const Options& o) {
    Row row{&p, target, method, estimateStability(p.scene, 40), {}, 0};
    ProbeOptions probe = o.probe;
    probe.kick = target.precision == Precision::Double ? 1e-6 : 1e-3;  // above float's rounding
    const BackendChoice choice = choiceFor(target, o.base());
    const auto t0 = std::chrono::steady_clock::now();
    row.probe = probeStableDt(
        p.scene, method, row.bound.tightDt(method),
        [&](const Scene& s) { return makeSolver(s, choice); }, probe);
    row.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return row;
}

constexpr const char* kColumns =
    "sweep,target,backend,precision,method,k_structural_N_per_m,mass_kg,damping_Ns_per_m,"
    "lambda_gershgorin_N_per_m,lambda_power_N_per_m,predicted_safe_dt_s,predicted_tight_dt_s,"
    "measured_dt_s,unstable_dt_s,status,measured_over_tight,trials,steps,wall_s\n";

std::string csvRow(const Row& r) {
    const Scene& s = r.point->scene;
    const double tight = r.bound.tightDt(r.method);
    const double measured = r.probe.stableDt > 0 ? r.probe.stableDt : NAN;
    std::vector<std::string> cells{r.point->sweep, r.target.id(), backendName(r.target.backend),
                                   precisionName(r.target.precision), methodName(r.method)};
    for (double x : {s.springs.structural, s.cloth.mass, s.damping, r.bound.lambdaMax,
                     r.bound.lambdaPower, r.bound.safeDt(r.method), tight, measured,
                     r.probe.unstableDt > 0 ? r.probe.unstableDt : NAN})
        cells.push_back(cell(x));
    const double ratio = std::isfinite(tight) && tight > 0 ? measured / tight : NAN;
    cells.insert(cells.end(),
                 {probeStatusName(r.probe.status), cell(ratio), std::to_string(r.probe.trials),
                  std::to_string(r.probe.steps), cell(r.wall)});
    return join(cells, ',') + "\n";
}

void printRow(const Row& r) {
    const Scene& s = r.point->scene;
    const double x = r.point->sweep == "stiffness" ? s.springs.structural
                     : r.point->sweep == "mass"    ? s.cloth.mass
                                                   : s.damping;
    std::printf("%-9s %-9.3g %-10s %-16s %-11.4g %-11.4g %-11.4g %-19s %4d %6.2f\n",
                r.point->sweep.c_str(), x, r.target.id().c_str(), methodName(r.method),
                r.probe.stableDt, r.bound.safeDt(r.method), r.bound.tightDt(r.method),
                probeStatusName(r.probe.status), r.probe.trials, r.wall);
    std::fflush(stdout);
}

void plotSweeps(const Options& o, const Scene& scene, const std::string& csv,
                const std::vector<Row>& rows) {
    // The mass and damping sweeps keep λ: their predicted bound min(μ/λ, 2m/μ) is drawn as a
    // curve, kink included, from these.
    const StabilityBound b = estimateStability(scene, 40);
    for (const std::string& sweep : o.sweeps) {
        std::vector<std::pair<Method, BenchTarget>> curves;
        for (const Row& r : rows)  // sorted by sweep, target, integrator
            if (r.point->sweep == sweep && (curves.empty() || curves.back().first != r.method ||
                                            curves.back().second.id() != r.target.id()))
                curves.emplace_back(r.method, r.target);
        PlotVars vars = seriesVars(curves);
        vars.insert(vars.end(), {{"csv", csv},
                                 {"sweep", sweep},
                                 {"lambda_safe", cell(b.lambdaMax)},
                                 {"lambda_tight", cell(b.lambdaPower)},
                                 {"mass", cell(scene.cloth.mass)},
                                 {"damping", cell(scene.damping)},
                                 {"title", scene.name + ": largest stable dt against " + sweep}});
        const std::string stem =
            outputPath(o.out, "stability_" + (sweep == "stiffness" ? "" : sweep + "_") + o.label);
        for (const std::string& f : plot(o.scriptDir, "stability.gp", stem, vars))
            std::printf("wrote %s\n", f.c_str());
    }
}

}  // namespace

int runBenchStability(const StabilityOptions& options) {
    StabilityOptions o = options;
    const Scene scene = loadBenchScene(o);
    const std::string csv = outputPath(o.out, "stability_" + o.label + ".csv");
    const std::vector<Point> points = sweepPoints(scene, o);
    const auto targets = availableTargets(parseTargets("--backend", o.backend, {Precision::Double}),
                                          scene, o.backend == "gpu", o.base());
    std::printf(
        "%s: %d x %d vertices; trial %g s simulated, %ld..%ld steps, tolerance %g, "
        "cap %g s\n",
        scene.name.c_str(), scene.cloth.nu, scene.cloth.nv, o.probe.trialTime, o.probe.minSteps,
        o.probe.maxSteps, o.probe.tolerance, o.probe.cap);
    std::printf("%-9s %-9s %-10s %-16s %-11s %-11s %-11s %-19s %4s %6s\n", "sweep", "value",
                "target", "method", "measured_s", "safe_s", "tight_s", "status", "runs", "wall");
    std::string text = "# clothsim bench stability " + scene.source + ": trial " +
                       cell(o.probe.trialTime) + " s simulated, steps " +
                       std::to_string(o.probe.minSteps) + ".." + std::to_string(o.probe.maxSteps) +
                       ", tolerance " + cell(o.probe.tolerance) + ", cap " + cell(o.probe.cap) +
                       " s\n" + kColumns;
    std::vector<Row> rows;
    MethodSupport support;
    for (const Point& p : points)
        for (const BenchTarget& t : targets)
            for (Method m : p.methods) {
                if (!support.runs(t, p.scene, m, o.base())) continue;
                rows.push_back(measure(p, t, m, o));
                printRow(rows.back());
            }
    // One curve's rows together (sweep, target, integrator), as the plot's lines need.
    std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
        return std::tie(a.point->sweep, a.target.backend, a.method) <
               std::tie(b.point->sweep, b.target.backend, b.method);
    });
    for (const Row& r : rows) text += csvRow(r);
    writeWholeFile(csv, text);
    std::printf("wrote %s\n", csv.c_str());
    plotSweeps(o, scene, csv, rows);
    return kOk;
}

}  // namespace cloth::app
