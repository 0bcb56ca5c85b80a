// The CPU backend against closed forms (DESIGN.md §6): the seed's damped spring and the static
// equilibrium of its two-spring chain.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth {
namespace {

constexpr double kG = 9.81;  // |g| [m/s²]

// A vertical chain of nv vertices 1 m apart along −y, the top one pinned (the seed's [1, 2]
// spring and [1, 3] chain).
Scene hangingChain(int nv, double k, double mu, double m, double dt) {
    char text[512];
    std::snprintf(text, sizeof text, R"({
      "cloth": { "resolution": [1, %d], "size": [1.0, %d], "origin": [0, 0, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": %.17g },
      "springs": { "structural": %.17g },
      "damping": %.17g,
      "gravity": [0, -9.81, 0],
      "pins": [[0, 0]],
      "integrator": { "method": "explicit_euler", "dt": %.17g }
    })",
                  nv, nv - 1, m, k, mu, dt);
    return parseScene(text, "chain (test)");
}

// m x'' = −K x − μ x' + m g for the stretch x beyond the rest length L, from x = 0, x' = 0.
// About the equilibrium x_e = m g / K, y = x − x_e obeys y'' + 2γ y' + ω0² y = 0 with γ = μ/2m,
// ω0² = K/m; underdamped (γ < ω0): y = e^{−γt} (y0 cos ω_d t + (γ y0 / ω_d) sin ω_d t),
// ω_d = √(ω0² − γ²), y0 = −x_e.
struct DampedSpring {
    double k, mu, m;
    double stretch(double t) const {
        const double xe = m * kG / k, gamma = mu / (2 * m);
        const double wd = std::sqrt(k / m - gamma * gamma), y0 = -xe;
        return xe +
               std::exp(-gamma * t) * (y0 * std::cos(wd * t) + gamma * y0 / wd * std::sin(wd * t));
    }
    double rate(double t) const {
        const double xe = m * kG / k, gamma = mu / (2 * m);
        const double w0sq = k / m, wd = std::sqrt(w0sq - gamma * gamma), y0 = -xe;
        // d/dt of the above: the cos terms cancel, leaving −(ω0²/ω_d) y0 e^{−γt} sin ω_d t.
        return -w0sq / wd * y0 * std::exp(-gamma * t) * std::sin(wd * t);
    }
};

// Error of the state (stretch, and velocity scaled by 1/ω0 so both are lengths) at time T.
double springErrorAt(const DampedSpring& ref, double dt, double T) {
    const long steps = std::lround(T / dt);
    std::unique_ptr<Solver> solver =
        makeCpuSolver(hangingChain(2, ref.k, ref.mu, ref.m, dt), {Precision::Double, 1});
    EXPECT_EQ(solver->step(steps).stepsTaken, steps);
    const SimState s = solver->read();
    const double stretch = -s.positions[1].y - 1.0, rate = -s.velocities[1].y;
    const double w0 = std::sqrt(ref.k / ref.m);
    const double ex = stretch - ref.stretch(T), ev = (rate - ref.rate(T)) / w0;
    EXPECT_NEAR(s.positions[1].x, 0, 1e-15);
    EXPECT_NEAR(s.positions[1].z, 0, 1e-15);
    return std::sqrt(ex * ex + ev * ev);
}

// Explicit Euler (seed eq. (6)) is first order: halving Δt halves the error at a fixed time.
TEST(ClosedForm, DampedSpringConvergesAtFirstOrder) {
    const DampedSpring spring{100, 0.5, 2};  // ω0 ≈ 7.07 rad/s, γ = 0.125 /s: underdamped
    const double T = 1.3, dt = 1e-3;         // ω0 Δt ≈ 0.007: in the asymptotic range
    const double e1 = springErrorAt(spring, dt, T);
    const double e2 = springErrorAt(spring, dt / 2, T);
    const double e4 = springErrorAt(spring, dt / 4, T);
    const double order1 = std::log2(e1 / e2), order2 = std::log2(e2 / e4);
    std::printf("damped spring errors at T = %g s: %.3e %.3e %.3e, orders %.4f %.4f\n", T, e1, e2,
                e4, order1, order2);
    EXPECT_GE(order1, 0.8);
    EXPECT_LE(order1, 1.2);
    EXPECT_GE(order2, 0.8);
    EXPECT_LE(order2, 1.2);
    // And the error is small in absolute terms: a few per cent of the amplitude m g / K.
    EXPECT_LT(e1, 0.05 * spring.m * kG / spring.k);
}

// The seed's chain of two springs hanging from a pin comes to rest where each spring carries
// the weight below it: the upper one m·2g, the lower one m·g, i.e. lengths L + 2mg/K, L + mg/K.
// Explicit Euler's fixed point (v = 0, F + m g = 0) is exactly the static equilibrium.
TEST(ClosedForm, ChainSettlesToStaticEquilibrium) {
    const double k = 100, mu = 10, m = 1, dt = 1e-3;
    // Δt = 1e-3 < μ/λ_max = 10 / (2·2K) = 0.025; every mode decays as e^{−μ t / 2m} = e^{−5t},
    // so 8 s takes the initial amplitude (≈ 0.3 m) below 1e-18 m.
    std::unique_ptr<Solver> solver = makeCpuSolver(hangingChain(3, k, mu, m, dt), {});
    ASSERT_FALSE(solver->step(8000).unstable);
    const SimState s = solver->read();
    const double upper = glm::length(s.positions[1] - s.positions[0]);
    const double lower = glm::length(s.positions[2] - s.positions[1]);
    const double upperExpected = 1 + 2 * m * kG / k, lowerExpected = 1 + m * kG / k;
    std::printf("chain lengths %.12f %.12f (expected %.12f %.12f)\n", upper, lower, upperExpected,
                lowerExpected);
    EXPECT_NEAR(upper / upperExpected, 1.0, 1e-6);
    EXPECT_NEAR(lower / lowerExpected, 1.0, 1e-6);
    EXPECT_LT(glm::length(s.velocities[2]), 1e-6);
}

}  // namespace
}  // namespace cloth
