#include "bench/bench_realtime_trial.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "model/stability.h"
#include "solver/diagnostics.h"
#include "solver/instability.h"

namespace cloth::app {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kPowerIterations = 40;       // the tight bound's power iteration (bench stability's)
constexpr double kMaxStepsPerFrame = 1e8;  // below Δt ≈ 1.7e-10 s no trial could be real time
// Steps go in chunks that start at one step and double while a chunk takes less than this, up to
// a frame's: a trial far slower than real time is cut off after a few steps, not after a frame
// that may take seconds, and a fast one soon steps whole frames (a call costs tens of µs). No
// chunk crosses the end of a frame, where the strain is checked.
constexpr double kShortChunk = 0.005;  // [s]

// `pattern` with its %g conversions of `a` (and `b`) filled in.
std::string format(const char* pattern, double a, double b = 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, pattern, a, b);
    return buf;
}

// A run that completed: real time, too slow, or unstable by its final state.
void finish(Trial& t, const Scene& scene, const Solver& solver, double time) {
    t.state = solver.read();
    if (!allFinite(t.state)) {
        t.status = TrialStatus::Unstable;
        t.reason = "a position or velocity is not finite after the run";
    } else if (const auto why = strainBreach(scene, t.state)) {
        t.status = TrialStatus::Unstable;
        t.reason = *why;
    } else if (t.wall <= time) {
        t.status = TrialStatus::RealTime;
    } else {
        t.status = TrialStatus::TooSlow;
        t.reason = format("%.3g s of wall time for %.3g s simulated", t.wall, t.simulated);
    }
    if (t.status != TrialStatus::RealTime) t.state = {};
}

}  // namespace

double firstDt(Method method, double tightDt, double safety) {
    if (method == Method::ImplicitEuler || method == Method::Vbd) return kFrame;  // no bound
    if (!(tightDt > 0)) return 0;
    return std::min(kFrame, safety * tightDt);
}

Trial timeTrial(const Scene& scene, const BackendChoice& choice, long stepsPerFrame, double time) {
    Trial t;
    t.n = scene.cloth.nu;
    t.dt = scene.integrator.dt;
    t.stepsPerFrame = int(stepsPerFrame);
    const std::unique_ptr<Solver> solver = makeSolver(scene, choice);
    const SimState initial = solver->read();
    solver->step(1);
    solver->write(initial);
    const SolveStats before = solver->solveStats();
    const long total = std::max(1L, std::lround(time / kFrame)) * stepsPerFrame;
    long steps = 0, chunk = 1, checked = 0;
    Clock::time_point start = Clock::now();
    while (steps < total) {
        const double chunkStart = t.wall;
        const long frameEnd = (steps / stepsPerFrame + 1) * stepsPerFrame;
        StepResult r = solver->step(std::min({chunk, total - steps, frameEnd - steps}));
        steps += r.stepsTaken;
        t.wall = std::chrono::duration<double>(Clock::now() - start).count();
        t.simulated = double(steps) * t.dt;
        if (!r.unstable && steps % stepsPerFrame == 0 && steps < total) {
            // Every displayed frame's strain (solver/instability.h), off the clock: a sheet that
            // tears and contracts again within a few frames passes a sparser check (a run's,
            // every 0.1 s) and the final state's, yet a viewer would have shown it torn.
            const Clock::time_point t0 = Clock::now();
            if (const auto strained = strainInstability(scene, *solver, checked)) r = *strained;
            checked = steps;
            start += Clock::now() - t0;
        }
        if (r.unstable) {
            t.status = TrialStatus::Unstable;
            t.reason = format("unstable at t = %.4g s: ", t.simulated) + r.reason;
            break;
        }
        if (t.wall - chunkStart < kShortChunk) chunk = std::min(2 * chunk, stepsPerFrame);
        if (steps == total) {
            finish(t, scene, *solver, time);
        } else if (t.wall > kCutOffFactor * t.simulated + kCutOffSlack) {
            t.status = TrialStatus::CutOff;
            t.reason =
                format("cut off at %.3g s simulated, %.3g s of wall time", t.simulated, t.wall);
            break;
        }
    }
    const SolveStats& after = solver->solveStats();
    if (steps > 0 && after.solves > before.solves) {
        t.cgPerStep = double(after.iterations - before.iterations) / double(steps);
        t.cgMisses = after.misses - before.misses;
    }
    return t;
}

namespace {

// Contention only ever slows a trial down: of two runs at the same Δt the faster is the
// machine's. A retry that turns unstable (it got further than a run that was cut off) is not
// taken.
Trial better(Trial first, Trial second) {
    second.attempts = first.attempts = 2;
    if (second.status == TrialStatus::Unstable) return first;
    return second.realTime() || second.wallPerSim() < first.wallPerSim() ? second : first;
}

}  // namespace

Trial trialAtSize(Scene scene, const BackendChoice& choice, const RealtimeOptions& o) {
    const Method method = scene.integrator.method;
    const double tight = estimateStability(scene, kPowerIterations).tightDt(method);
    Trial t;
    t.n = scene.cloth.nu;
    t.tightDt = tight;
    if (choice.backend == Backend::Gpu)
        if (const auto why = gpuRefusal(scene, choice.gpu)) {
            t.status = TrialStatus::DoesNotFit;
            t.reason = *why;
            return t;
        }
    const double dt = firstDt(method, tight, o.safety);
    if (!(dt > 0) || kFrame / dt > kMaxStepsPerFrame) {
        t.reason = "no stable time step is predicted";
        return t;
    }
    long stepsPerFrame = std::lround(std::ceil(kFrame / dt * (1 - 1e-12)));
    for (int halvings = 0;; ++halvings, stepsPerFrame *= 2) {
        scene.integrator.dt = kFrame / double(stepsPerFrame);
        t = timeTrial(scene, choice, stepsPerFrame, o.time);
        if (t.status == TrialStatus::TooSlow || t.status == TrialStatus::CutOff)
            t = better(t, timeTrial(scene, choice, stepsPerFrame, o.time));
        t.tightDt = tight;
        t.halvings = halvings;
        if (t.status != TrialStatus::Unstable || halvings == kMaxHalvings) return t;
    }
}

}  // namespace cloth::app
