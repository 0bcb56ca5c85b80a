// Extremes of size: a 2048² cloth (4.2 M vertices) steps under every integrator without a crash,
// a hang or a non-finite value, and a CG capped far below convergence says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cpu/cpu_backend.h"
#include "model/grid.h"
#include "model/stability.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"
#include "solver/solver.h"

namespace cloth {
namespace {

Scene largeCloth(Method method) {
    Scene s = parseScene(R"({"cloth": {"resolution": [2048, 2048], "size": [2, 2],
        "mass": 1e-6}, "springs": {"structural": 100, "shear": 50, "bend": 10},
        "damping": 1e-3, "pins": [[0, 0], [-1, 0]], "integrator": {"dt": 1e-6,
        "max_iterations": 3}})",
                         "large");
    s.integrator.method = method;
    // Implicit Euler at a frame's step, where h²K/m = 3e4 makes the system stiff.
    if (method == Method::ImplicitEuler) s.integrator.dt = 1.0 / 60;
    return s;
}

TEST(LargeGrid, EveryIntegratorSteps2048SquaredAndStaysFinite) {
    for (Method method : kMethods) {
        auto solver = makeCpuSolver(largeCloth(method), {Precision::Float, 0});
        const StepResult r = solver->step(2);
        EXPECT_FALSE(r.unstable) << methodName(method) << ": " << r.reason;
        EXPECT_EQ(r.stepsTaken, 2);
        const SimState state = solver->read();
        EXPECT_EQ(state.positions.size(), std::size_t(2048) * 2048);
        EXPECT_TRUE(allFinite(state)) << methodName(method);
        // The cloth starts at rest length: gravity alone moves the free vertices, pins stay put.
        EXPECT_EQ(state.positions[0], largeCloth(method).grid().restPosition(0, 0));
        EXPECT_LT(state.positions[2048 * 1024 + 1024].y, 0.0) << methodName(method);
        if (method == Method::ImplicitEuler) {
            // Three iterations cannot reach 1e-5 on 12.6 M unknowns: each solve is a miss.
            EXPECT_EQ(solver->solveStats().solves, 2);
            EXPECT_EQ(solver->solveStats().misses, 2);
        }
    }
}

// A 64² cloth with every family at K = 1e6 N/m, hung flat by two corners, at the viewer's
// Δt = 1/60 s: h²K/m = 7·10⁵ (ω_max Δt ≈ 800), where every explicit scheme explodes at once.
Scene stiffCloth(Method method) {
    Scene s = parseScene(R"({"cloth": {"resolution": [64, 64], "size": [1, 1],
        "origin": [-0.5, 1.5, 0], "mass": 0.0004}, "springs": {"structural": 1e6,
        "shear": 1e6, "bend": 1e6}, "damping": 0.01, "pins": [[0, 0], [-1, 0]],
        "integrator": {"method": "implicit_euler", "dt": 0.016666666666666666}})",
                         "stiff");
    s.integrator.method = method;
    return s;
}

// Energy a linearised step can add. Backward Euler on the linearised system dissipates (its
// damping and its numerical damping only remove energy); what it cannot see is that a spring
// turned by the step lengthens at second order: ends moving apart at |Δv| rotate it by at most
// θ = h|Δv|/L, which stretches it by L(√(1 + θ²) − 1) ≤ Lθ²/2 and stores ½K(Lθ²/2)². Summed
// over every modelled spring, from the velocities the step ended with (those that moved it). The
// expansion needs θ < 1 rad: a step that turns a spring further is outside the law.
struct Linearisation {
    double energy = 0;   // [J]
    double maxTurn = 0;  // largest θ [rad]
};
Linearisation linearisation(const Scene& scene, const SimState& state) {
    const Grid g = scene.grid();
    const double h = scene.integrator.dt;
    Linearisation lin;
    for (const SpringOffset& o : kSpringOffsets) {
        if (o.di < 0 || (o.di == 0 && o.dj < 0)) continue;  // each spring once
        const double k = scene.springs.of(o.family), rest = g.restLength(o.di, o.dj);
        for (int j = 0; j < g.nv; ++j)
            for (int i = 0; i < g.nu; ++i) {
                if (!g.contains(i + o.di, j + o.dj)) continue;
                const glm::dvec3 dv =
                    state.velocities[g.index(i + o.di, j + o.dj)] - state.velocities[g.index(i, j)];
                const double theta = h * glm::length(dv) / rest;
                lin.energy += 0.5 * k * std::pow(0.5 * rest * theta * theta, 2);
                lin.maxTurn = std::max(lin.maxTurn, theta);
            }
    }
    return lin;
}

// Steps `steps` times; returns the first step that is unstable, turns a spring by more than
// 1 rad, or gains more energy than the linearisation's bound (0: none).
long firstStepGainingTooMuch(const Scene& scene, Precision precision, long steps) {
    auto solver = makeCpuSolver(scene, {precision, 0});
    double before = energy(scene, solver->read()).total();
    for (long n = 1; n <= steps; ++n) {
        const StepResult r = solver->step(1);
        const SimState state = solver->read();
        if (r.unstable || !allFinite(state)) {
            std::printf("step %ld: unstable (%s)\n", n, r.reason.c_str());
            return n;
        }
        const double after = energy(scene, state).total();
        const Linearisation lin = linearisation(scene, state);
        if (lin.maxTurn > 1 || after - before > lin.energy) {
            std::printf(
                "step %ld: energy gained %.3g J, the linearisation's bound %.3g J, "
                "largest turn %.3g rad\n",
                n, after - before, lin.energy, lin.maxTurn);
            return n;
        }
        before = after;
    }
    return 0;
}

// Step one, solved to the tolerance: the flat cloth's springs are at rest length, so the
// linearised system has no vertical stiffness, and every free vertex falls by exactly what a
// single damped particle does, δ = h·v₁, v₁ = h g / (1 + hμ/m). The spring from a pin to its
// neighbour, of rest length L = 1/63 m, then has turned by δ/L = 0.121 rad and is stretched by
// √(1 + (δ/L)²) − 1 = 0.73%: the step's whole strain is this rotation error, nothing else.
TEST(StiffCloth, BackwardEulersFirstStepStretchesOnlyBySpringRotation) {
    const Scene s = stiffCloth(Method::ImplicitEuler);
    auto solver = makeCpuSolver(s, {Precision::Double, 0});
    ASSERT_FALSE(solver->step(1).unstable);
    ASSERT_EQ(solver->solveStats().misses, 0);
    const double h = s.integrator.dt, g = 9.81;
    const double v1 = h * g / (1 + h * s.damping / s.cloth.mass), fall = h * v1;
    const Grid grid = s.grid();
    const SimState state = solver->read();
    double worstFall = 0;
    for (int k = 1; k < 64 * 64; ++k) {
        if (k == 63) continue;  // the two pins
        // |r| ≤ 1e-5 |b| bounds the solve's relative error by 1e-5 times the system's condition
        // along the vertical, which is 1 (its vertical block is (m + hμ)·I).
        worstFall = std::max(
            worstFall,
            std::abs((grid.restPosition(k % 64, k / 64).y - state.positions[k].y) / fall - 1));
    }
    EXPECT_LT(worstFall, 1e-5);
    const double turn = fall / grid.du;
    const double predicted = std::sqrt(1 + turn * turn) - 1;
    const SpringStrain strain = largestStrain(s, state);
    std::printf("fall %.6g m (%.2g off), strain %.6g, rotation predicts %.6g\n", fall, worstFall,
                strain.strain, predicted);
    EXPECT_NEAR(strain.strain, predicted, 1e-5 * predicted);  // the same 1e-5 solve error
}

// Twenty steps with the default 200-iteration cap, as the viewer runs it: every state finite,
// nothing reported unstable, and no step gains more energy than the rotation of its springs
// can inject (measured: 0.12 J gained against a bound of 0.19 J at the worst step, step 2; the
// largest turn 0.14 rad). The
// capped solves are inexact, and each miss is counted, never silent.
TEST(StiffCloth, ImplicitEulerAtASixtiethOfASecondGainsNoMoreThanItsLinearisationInjects) {
    const Scene s = stiffCloth(Method::ImplicitEuler);
    ASSERT_LT(estimateStability(s, 40).tightDt(Method::Rk4) * 100, s.integrator.dt);
    EXPECT_EQ(firstStepGainingTooMuch(s, Precision::Double, 20), 0);
    auto solver = makeCpuSolver(s, {Precision::Double, 0});
    ASSERT_FALSE(solver->step(20).unstable);
    const SolveStats& st = solver->solveStats();
    EXPECT_EQ(st.solves, 20);
    EXPECT_EQ(st.misses == 0, st.mostIterations < 200);
}

// The law has teeth: symplectic Euler at ω_max Δt ≈ 800 amplifies the stiff modes; its first step
// is within the bound (the springs start at rest), its second turns springs by 10⁴ rad.
TEST(StiffCloth, AnExplicitSchemeAtThisStepBreaksTheLaw) {
    EXPECT_EQ(firstStepGainingTooMuch(stiffCloth(Method::SymplecticEuler), Precision::Double, 5),
              2);
}

}  // namespace
}  // namespace cloth
