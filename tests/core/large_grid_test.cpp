// Extremes of size: a 2048² cloth (4.2 M vertices) steps under every integrator without a crash,
// a hang or a non-finite value, and a CG capped far below convergence says so.
#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/scene_loader.h"
#include "core/solver.h"

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

}  // namespace
}  // namespace cloth
