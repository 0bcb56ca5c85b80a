// Extremes of size: a 2048² cloth (4.2 M vertices) steps under every integrator without a crash,
// a hang or a non-finite value, and a CG capped far below convergence says so.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/diagnostics.h"
#include "scene/scene_loader.h"
#include "cpu/cpu_backend.h"
#include "solver/solver.h"
#include "model/stability.h"

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

// A 64² cloth with every family at K = 1e6 N/m at the viewer's Δt = 1/60 s: ω_max Δt ≈ 400,
// where every explicit scheme explodes within a few steps. Backward Euler stays finite and the
// cloth hangs below its pins; with the default 200-iteration cap the solves are inexact, and
// each miss is counted, never silent.
TEST(StiffCloth, ImplicitEulerKeepsA64SquaredClothAtK1e6FiniteAtASixtiethOfASecond) {
    Scene s = parseScene(R"({"cloth": {"resolution": [64, 64], "size": [1, 1],
        "origin": [-0.5, 1.5, 0], "mass": 0.0004}, "springs": {"structural": 1e6,
        "shear": 1e6, "bend": 1e6}, "damping": 0.01, "pins": [[0, 0], [-1, 0]],
        "integrator": {"method": "implicit_euler", "dt": 0.016666666666666666}})",
                         "stiff");
    ASSERT_LT(estimateStability(s, 40).tightDt(Method::Rk4) * 100, s.integrator.dt);
    auto solver = makeCpuSolver(s, {Precision::Double, 0});
    const StepResult r = solver->step(20);
    ASSERT_FALSE(r.unstable) << r.reason;
    const SimState state = solver->read();
    ASSERT_TRUE(allFinite(state));
    for (const glm::dvec3& p : state.positions) {
        EXPECT_LT(p.y, 1.5 + 1e-9);  // nothing flung above the pins
        EXPECT_GT(p.y, 1.5 - 1.5);   // nor further below them than the cloth is long
        EXPECT_LT(std::abs(p.x), 1.0);
    }
    // The free corners have started to fall. (Slower than a rigid plate would, 4 cm in 0.33 s:
    // capped at 200 iterations the CG leaves most of the stiff system's response unsolved.)
    EXPECT_LT(state.positions[std::size_t(63 * 64)].y, 1.49);
    const SolveStats& st = solver->solveStats();
    EXPECT_EQ(st.solves, 20);
    EXPECT_EQ(st.misses == 0, st.mostIterations < 200);
}

}  // namespace
}  // namespace cloth
