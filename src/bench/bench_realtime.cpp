// clothsim bench realtime: for each integrator and target, the largest N whose N×N drape runs in
// real time (bench_realtime.h), found by doubling N from 8 and then bisecting between the last
// real-time N and the first that was not; the error of its state after T against a symplectic
// Euler reference in double at a tenth of its bound (or of the rows' Δt), at the same N.
#include "bench/bench_realtime.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>

#include "bench/bench_realtime_scene.h"
#include "bench/bench_realtime_trial.h"
#include "bench/bench_speed_model.h"
#include "bench/bench_speed_timing.h"
#include "model/stability.h"

namespace cloth::app {
namespace {

using Options = RealtimeOptions;
using Clock = std::chrono::steady_clock;

constexpr int kFirstSize = 8;  // the doubling's start; the bisection goes below it if need be

double since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

Scene sceneAt(const Options& o, int n, Method method) {
    Scene s = realtimeDrape(o.material, n, o.time, o.sets);
    if (o.form == ClothForm::PerVertex) s = perVertexForm(s);
    s.integrator.method = method;
    return s;
}

void printTrial(const Frontier& f, const Trial& t) {
    std::printf("  %-16s %-10s N = %-5d dt = %-10.4g %6d/frame  %-11s wall/sim %-8.3g %s\n",
                methodName(f.method), f.target.id().c_str(), t.n, t.dt, t.stepsPerFrame,
                trialStatusName(t.status), t.wallPerSim(), t.reason.c_str());
    std::fflush(stdout);
}

// best: the largest real-time N; fail: the smallest N above it that was not.
void settle(Frontier& f) {
    for (std::size_t k = 0; k < f.trials.size(); ++k)
        if (f.trials[k].realTime() && (f.best < 0 || f.trials[k].n > f.n())) f.best = int(k);
    for (std::size_t k = 0; k < f.trials.size(); ++k) {
        const Trial& t = f.trials[k];
        if (!t.realTime() && t.n > f.n() && (f.fail < 0 || t.n < f.trials[std::size_t(f.fail)].n))
            f.fail = int(k);
    }
    for (std::size_t k = 0; k < f.trials.size(); ++k)
        if (int(k) != f.best) f.trials[k].state = {};  // only the frontier's error is measured
}

// Doubling from kFirstSize while real time, then bisection between the last real-time N (lo;
// 1 stands for "none yet", N = 2 is the smallest sheet) and the first that was not (hi), until
// hi ≤ lo·(1 + tolerance) or they are neighbours. --sizes: exactly those N.
Frontier search(Method method, const BenchTarget& target, const Options& o) {
    Frontier f;
    f.method = method;
    f.target = target;
    const Clock::time_point start = Clock::now();
    const BackendChoice choice = choiceFor(target, o.base());
    auto realTime = [&](int n) {
        f.trials.push_back(trialAtSize(sceneAt(o, n, method), choice, o));
        const Trial& t = f.trials.back();
        printTrial(f, t);
        if (t.realTime())  // only the largest real-time N's state is kept, for its error
            for (Trial& smaller : f.trials)
                if (smaller.n < t.n) smaller.state = {};
        return t.realTime();
    };
    if (!o.sizes.empty()) {
        for (int n : o.sizes) realTime(n);
    } else {
        int lo = 1, hi = 0;
        for (int n = std::min(kFirstSize, o.maxSize); hi == 0 && n <= o.maxSize; n *= 2)
            (realTime(n) ? lo : hi) = n;
        while (hi > lo + 1 && hi > lo * (1 + o.tolerance)) {
            const int mid = std::max(2, (lo + hi) / 2);
            (realTime(mid) ? lo : hi) = mid;
        }
    }
    f.searchWall = since(start);
    settle(f);
    return f;
}

double rmsError(const SimState& a, const SimState& b, double extent) {
    double sum = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k) {
        const glm::dvec3 d = a.positions[k] - b.positions[k];
        sum += glm::dot(d, d);
    }
    return std::sqrt(sum / double(a.positions.size())) / extent;
}

struct Reference {
    SimState state;
    double dt = 0;
    // RMS distance / extent between the reference and the same run at twice its Δt: how far from
    // converged it is, the floor under which an error says nothing (NaN: that run was unstable).
    double change = NAN;
};

// Symplectic Euler on the CPU in double at min(its tight bound, `finest`) / factor, the steps
// rounded up to an even number over `time`, halved after an instability; then again at twice
// that Δt for Reference::change. `finest` is the smallest Δt of the runs compared with it:
// explicit Euler steps far below symplectic Euler's bound, and a reference coarser than the run
// it judges would measure its own error.
Reference reference(Scene s, double finest, const Options& o) {
    s.integrator.method = Method::SymplecticEuler;
    const double tight = estimateStability(s, 40).tightDt(Method::SymplecticEuler);
    const double wanted = std::min(tight > 0 ? tight : kFrame, finest) / o.referenceFactor;
    long steps = std::max(2L, std::lround(std::ceil(o.time / wanted)));
    steps += steps % 2;
    BackendChoice cpu = o.base();
    cpu.backend = Backend::Cpu;
    cpu.precision = Precision::Double;
    auto run = [&](long n) -> std::optional<SimState> {
        s.integrator.dt = o.time / double(n);
        const std::unique_ptr<Solver> solver = makeSolver(s, cpu);
        if (solver->step(n).unstable) return std::nullopt;
        return solver->read();
    };
    for (int halvings = 0; halvings <= kMaxHalvings; ++halvings, steps *= 2)
        if (std::optional<SimState> state = run(steps)) {
            Reference ref{std::move(*state), o.time / double(steps)};
            if (const std::optional<SimState> coarse = run(steps / 2))
                ref.change = rmsError(ref.state, *coarse, s.grid().extent());
            return ref;
        }
    throw std::runtime_error("the symplectic Euler reference at N = " + std::to_string(s.cloth.nu) +
                             " is unstable at every dt tried");
}

// Each frontier's error against the reference at its N, one reference per N.
void measureErrors(std::vector<Frontier>& rows, const Options& o) {
    std::map<int, double> finest;  // the smallest Δt of the frontiers at each N
    for (const Frontier& f : rows)
        if (f.best >= 0) {
            const Trial& t = f.trials[std::size_t(f.best)];
            finest[t.n] = finest.count(t.n) ? std::min(finest[t.n], t.dt) : t.dt;
        }
    std::map<int, Reference> cache;
    for (const auto& [n, dt] : finest) {
        const Clock::time_point start = Clock::now();
        cache[n] = reference(sceneAt(o, n, Method::SymplecticEuler), dt, o);
        std::printf(
            "  reference N = %d: symplectic_euler cpu_double, dt = %.4g s; at twice that dt the "
            "state moves by %.3g x extent [%.1f s]\n",
            n, cache[n].dt, cache[n].change, since(start));
        std::fflush(stdout);
    }
    for (Frontier& f : rows) {
        if (f.best < 0) continue;
        const Trial& t = f.trials[std::size_t(f.best)];
        const double extent = sceneAt(o, t.n, f.method).grid().extent();
        f.error = rmsError(t.state, cache[t.n].state, extent);
        f.referenceDt = cache[t.n].dt;
        f.referenceChange = cache[t.n].change;
    }
}

// The run's settings and machine, for the files' headers.
RealtimeMeta describeRun(const Options& o, const std::vector<BenchTarget>& targets) {
    const Scene s = realtimeDrape(o.material, kFirstSize, o.time, o.sets);
    const Material& m = *s.material;
    char line[240];
    std::snprintf(line, sizeof line,
                  "%s: density %g kg/m2, stretch %g N/m, shear %g N/m, bend %g N m, air_damping "
                  "%g 1/s",
                  m.preset.c_str(), m.density, m.stretch, m.shear, m.bend, m.airDamping);
    RealtimeMeta meta;
    meta.label = o.label;
    meta.material = o.material;
    meta.materialLine = line;
    meta.form = clothFormName(o.form);
    meta.buildType = CLOTH_BUILD_TYPE;
    meta.cpuModel = cpuModel();
    for (const BenchTarget& t : targets)
        if (t.backend == Backend::Gpu) meta.gpuRenderer = gpuRenderer();
    meta.scriptDir = o.scriptDir;
    meta.time = o.time;
    meta.sets = o.sets;
    meta.tolerance = o.tolerance;
    meta.safety = o.safety;
    meta.referenceFactor = o.referenceFactor;
    meta.quick = o.quick;
    meta.searched = o.sizes.empty();
    return meta;
}

}  // namespace

const char* clothFormName(ClothForm f) {
    return f == ClothForm::Material ? "material" : "per-vertex";
}

const char* trialStatusName(TrialStatus s) {
    switch (s) {
        case TrialStatus::RealTime:
            return "real_time";
        case TrialStatus::TooSlow:
            return "too_slow";
        case TrialStatus::CutOff:
            return "cut_off";
        case TrialStatus::Unstable:
            return "unstable";
        case TrialStatus::DoesNotFit:
            return "does_not_fit";
    }
    return "?";
}

int runBenchRealtime(const RealtimeOptions& options) {
    const Clock::time_point start = Clock::now();
    Options o = options;
    if (const auto why = debugRefusal(CLOTH_BUILD_TYPE, o.allowDebug)) {
        std::fprintf(stderr, "clothsim bench realtime: %s\n", why->c_str());
        return kInvalidInput;
    }
    // The scene with the --set overrides, checked before anything runs.
    const Scene probe = sceneAt(o, kFirstSize, Method::SymplecticEuler);
    // The per-vertex form's files sit beside the material's, not over them.
    if (o.label.empty())
        o.label = o.material + (o.form == ClothForm::PerVertex ? "_per_vertex" : "");
    checkOutputs(o.out, o.label);  // an unusable --out or --label is refused now, not after
    auto targets = parseTargets("--backend", o.backend, {Precision::Float, Precision::Double});
    targets = availableTargets(targets, probe, o.backend == "gpu", o.base());

    RealtimeMeta meta = describeRun(o, targets);
    std::printf("bench realtime: the drape, %s (%s form); %g s simulated per trial\n",
                meta.materialLine.c_str(), meta.form.c_str(), o.time);

    std::vector<Frontier> rows;
    MethodSupport support;
    for (Method m : o.methods)
        for (const BenchTarget& t : targets)
            if (support.runs(t, probe, m, o.base())) rows.push_back(search(m, t, o));
    if (o.error) measureErrors(rows, o);
    meta.totalWall = since(start);
    reportRealtime(o.out, meta, rows);
    return kOk;
}

}  // namespace cloth::app
