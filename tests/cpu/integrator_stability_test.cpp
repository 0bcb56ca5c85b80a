// The stability law of each integrator (DESIGN.md §2, docs/integrators.md, src/model/stability.h)
// on the CPU backend in double: runs at 0.8 of the predicted bound stay finite and bounded for
// 20000 steps; the explicit schemes at 1.5 of it are reported unstable; and the bound measured by
// bisection over a fixed simulated time agrees with the prediction across K = 1e1 … 1e7.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cpu/cpu_backend.h"
#include "model/stability.h"
#include "reference/reference.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/reference_bridge.h"

namespace cloth {
namespace {

constexpr int kPowerIterations = 40;
constexpr Method kExplicitMethods[] = {Method::ExplicitEuler, Method::SymplecticEuler,
                                       Method::Verlet, Method::Rk4};

Scene withMethod(Scene s, Method method, double dt) {
    s.integrator.method = method;
    s.integrator.dt = dt;
    return s;
}

// A 1×n chain hanging along −y from its pinned top vertex, 1 m long, under gravity g.
Scene chain(int n, double k, double mu, double m, double g) {
    char text[512];
    std::snprintf(text, sizeof text, R"({
      "cloth": { "resolution": [1, %d], "size": [1, 1], "v_axis": [0, -1, 0], "mass": %.17g },
      "springs": { "structural": %.17g }, "damping": %.17g, "gravity": [0, %.17g, 0],
      "pins": [[0, 0]], "integrator": { "dt": 0.001 } })",
                  n, m, k, mu, -g);
    return parseScene(text, "chain (test)");
}

// An n×n cloth, 1 m square, horizontal, pinned at two corners, every spring family.
Scene cloth(int n, double k, double mu, double m, double g) {
    char text[640];
    std::snprintf(text, sizeof text, R"({
      "cloth": { "resolution": [%d, %d], "size": [1, 1], "mass": %.17g },
      "springs": { "structural": %.17g, "shear": %.17g, "bend": %.17g }, "damping": %.17g,
      "gravity": [0, %.17g, 0], "pins": [[0, 0], [-1, 0]], "integrator": { "dt": 0.001 } })",
                  n, n, m, k, k / 4, k / 10, mu, -g);
    return parseScene(text, "cloth (test)");
}

// The two hanging scenes of the 20000-step runs. Their damping gives the stiffest mode a damping
// ratio ζ ≈ 0.15, so that explicit Euler's growth at 1.5 of its bound, |z|² = 1 + 0.75 (μ/m)²/ω²
// = 1 + 3ζ² per step, is fast. max_speed is 20 m/s, five times what a fall from the pins reaches:
// explicit Euler's growth saturates once the amplitude reaches the rest length (springs fold
// through zero length, where the force is bounded), and the chain then tumbles at ≈ 40 m/s, which
// the default max_speed of 1e4 m/s would never report.
Scene hangingChain() {
    Scene s = chain(3, 1000, 5, 0.1, 9.81);  // λ = 2.618 K, ω = 162 rad/s
    s.maxSpeed = 20;
    return s;
}
Scene hangingCloth() {
    Scene s = cloth(5, 500, 1.5, 0.05, 9.81);
    s.maxSpeed = 20;
    return s;
}

// Largest distance from the start over the run and the final energy, sampled every 1000 steps.
struct RunSummary {
    bool unstable = false;
    std::string reason;
    double maxDisplacement = 0;             // [m]
    double startEnergy = 0, endEnergy = 0;  // [J], by the reference's formulas
};

RunSummary runFor(const Scene& scene, long steps) {
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Double, 1});
    const ref::Simulation model(toReference(scene));
    const SimState start = solver->read();
    RunSummary out;
    out.startEnergy = totalEnergy(model, start);
    for (long done = 0; done < steps; done += 1000) {
        const StepResult r = solver->step(1000);
        if (r.unstable) {
            out.unstable = true;
            out.reason = r.reason;
            return out;
        }
        const SimState s = solver->read();
        for (std::size_t k = 0; k < s.positions.size(); ++k)
            out.maxDisplacement =
                std::max(out.maxDisplacement, glm::length(s.positions[k] - start.positions[k]));
    }
    out.endEnergy = totalEnergy(model, solver->read());
    return out;
}

// At 0.8 of tightDt a run stays finite, inside a few extents of where it started, and (damped,
// no wind) ends with less energy than it started with. Implicit Euler and vbd have no bound: they
// run at 20 times symplectic Euler's.
TEST(IntegratorStability, EveryMethodIsBoundedAtEightTenthsOfItsPredictedStep) {
    for (const Scene& base : {hangingChain(), hangingCloth()}) {
        const StabilityBound b = estimateStability(base, kPowerIterations);
        for (Method method : kMethods) {
            const bool unbounded = method == Method::ImplicitEuler || method == Method::Vbd;
            const double dt =
                unbounded ? 20 * b.tightDt(Method::SymplecticEuler) : 0.8 * b.tightDt(method);
            const RunSummary r = runFor(withMethod(base, method, dt), 20000);
            const double extent = base.grid().extent();
            std::printf("%-5s %-16s dt %.3e: max displacement %.3f m, energy %.4f -> %.4f J\n",
                        base.name.c_str(), methodName(method), dt, r.maxDisplacement, r.startEnergy,
                        r.endEnergy);
            EXPECT_FALSE(r.unstable) << methodName(method) << ": " << r.reason;
            EXPECT_LT(r.maxDisplacement, 3 * extent) << methodName(method);
            EXPECT_LT(r.endEnergy, r.startEnergy) << methodName(method);
        }
    }
}

TEST(IntegratorStability, ExplicitMethodsAreReportedUnstableAtOneAndAHalfTimesTheBound) {
    for (const Scene& base : {hangingChain(), hangingCloth()}) {
        const StabilityBound b = estimateStability(base, kPowerIterations);
        for (Method method : kExplicitMethods) {
            std::unique_ptr<Solver> solver =
                makeCpuSolver(withMethod(base, method, 1.5 * b.tightDt(method)), {});
            const StepResult r = solver->step(20000);
            std::printf("%-5s %-16s at 1.5x: unstable at step %ld (%s)\n", base.name.c_str(),
                        methodName(method), r.firstBadStep, r.reason.c_str());
            EXPECT_TRUE(r.unstable) << methodName(method);
            EXPECT_FALSE(r.reason.empty()) << methodName(method);
            EXPECT_LE(r.stepsTaken, 20000);
        }
    }
}

// --- The measured bound against the prediction, K = 1e1 … 1e7 -------------------------------
//
// No gravity; every free vertex starts displaced by a0 = 1e-4 of the spacing (a fixed ripple),
// at rest. The damping gives the stiffest mode (ω² = λ/m, λ from the power estimate) the ratio
// ζ = μ/(2 m ω) = 0.1 at every K, so the law's dependence on K is all in the step. A run
// "blows up" when it is reported unstable within T = 300 periods of that mode, with max_speed
// = 0.1 ω·spacing, i.e. a growth of G ≈ 1000 over the start's speeds (ω a0) while the amplitude
// is still a tenth of the spacing, far from folding a spring through zero length.
//
// The factor. Below the true bound every mode decays: no blow-up, so measured ≥ true. Above it,
// at Δt = (1 + δ) Δt*, the run blows up once its growth over N = T/Δt steps exceeds ln G ≈ 7
// (+ ln 10 if the stiffest mode holds only a tenth of the ripple):
//   explicit_euler  |z|² = 1 − cΔt + ω²Δt² grows by c·δΔt* = 4ζ²δ per step and N = Tω/(2ζ):
//                   a growth of Tω ζ δ = 188 δ, so δ ≤ 0.04 … 0.05;
//   symplectic_euler, verlet, rk4  a root leaves the unit circle at a rate of order δ/ζ per step
//                   (through −1 for the first two: ≈ 2δ(1 + ω²Δt*/c) ≈ 20δ for symplectic
//                   Euler), N ≈ 700 … 1000: δ of order 1e-3, 1e-2 at most.
// Below, the power estimate (≤ the true λ_max, 40 iterations) can only make the prediction
// optimistic, by (λ_power/λ_max)^{1/2} for the ω-limited schemes and λ_power/λ_max for explicit
// Euler. Hence explicit Euler within [0.97, 1.06] of the prediction, the others within
// [0.97, 1.02].
double factorHigh(Method m) {
    return m == Method::ExplicitEuler ? 1.06 : 1.02;
}
constexpr double kFactorLow = 0.97;

struct SweepCase {
    Scene scene;
    SimState start;
    double omega;  // of the stiffest mode, from the power estimate [rad/s]
};

SweepCase sweepCase(Scene s, double spacing) {
    const StabilityBound b = estimateStability(s, kPowerIterations);
    const double omega = std::sqrt(b.lambdaPower / s.cloth.mass);
    s.damping = 2 * 0.1 * s.cloth.mass * omega;
    s.maxSpeed = 0.1 * omega * spacing;
    std::unique_ptr<Solver> solver = makeCpuSolver(s, {Precision::Double, 1});
    SimState start = solver->read();
    std::vector<bool> pinned(start.positions.size(), false);
    for (const Pin& p : s.pins) pinned[std::size_t(s.grid().index(p.i, p.j))] = true;
    for (std::size_t k = 0; k < start.positions.size(); ++k) {
        if (pinned[k]) continue;
        for (int c = 0; c < 3; ++c)
            start.positions[k][c] += 1e-4 * spacing * std::sin(1.9 * double(k) + 2.7 * c + 0.3);
    }
    return {s, start, omega};
}

bool blowsUp(const SweepCase& c, Method method, double dt) {
    std::unique_ptr<Solver> solver =
        makeCpuSolver(withMethod(c.scene, method, dt), {Precision::Double, 1});
    solver->write(c.start);
    const double T = 300 * 2 * M_PI / c.omega;
    return solver->step(std::lround(T / dt)).unstable;
}

// Bisection between 0.5 and 2 times the prediction to 1e-3 of it.
double measuredBound(const SweepCase& c, Method method, double predicted) {
    double lo = 0.5 * predicted, hi = 2 * predicted;
    EXPECT_FALSE(blowsUp(c, method, lo)) << methodName(method);
    EXPECT_TRUE(blowsUp(c, method, hi)) << methodName(method);
    while (hi - lo > 1e-3 * predicted) {
        const double mid = 0.5 * (lo + hi);
        (blowsUp(c, method, mid) ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}

TEST(IntegratorStability, MeasuredBoundMatchesThePredictionFromK1e1To1e7) {
    for (double k : {1e1, 1e3, 1e5, 1e7}) {
        const SweepCase cases[] = {
            sweepCase(chain(2, k, 0, 1, 0), 1.0),
            sweepCase(chain(3, k, 0, 1, 0), 0.5),
            sweepCase(cloth(4, k, 0, 1, 0), 1.0 / 3),
        };
        for (const SweepCase& c : cases) {
            const StabilityBound b = estimateStability(c.scene, kPowerIterations);
            for (Method method : kExplicitMethods) {
                const double predicted = b.tightDt(method);
                const double measured = measuredBound(c, method, predicted);
                std::printf("K %.0e %dx%d %-16s predicted %.4e measured %.4e ratio %.4f\n", k,
                            c.scene.cloth.nu, c.scene.cloth.nv, methodName(method), predicted,
                            measured, measured / predicted);
                EXPECT_GE(measured / predicted, kFactorLow) << methodName(method) << ", K " << k;
                EXPECT_LE(measured / predicted, factorHigh(method))
                    << methodName(method) << ", K " << k;
            }
        }
    }
}

}  // namespace
}  // namespace cloth
