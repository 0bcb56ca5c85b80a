// implicit_euler's preconditioned, warm-started conjugate gradient on the CPU
// (docs/integrators.md, "Preconditioners"): a preconditioner changes how the linear system is
// solved, never which system; the warm start is the last step's solution.
#include <gtest/gtest.h>

#include <cstdio>

#include "backends/solver_factory.h"
#include "support/material_scene.h"
#include "support/preconditioned_runs.h"
#include "support/same_bits.h"
#include "support/sanitized.h"

namespace cloth {
namespace {

using test::largestDifference;
using test::Solved;

// The material sheet (pinned corners, wind, drag, masses ¼ and ½ at corners and edges) at
// Δt = 1/60 with bending and spring damping: both preconditioners solved to 1e-11 give the same
// motion, block-Jacobi in fewer iterations.
TEST(ImplicitPreconditioner, JacobiSolvesTheSameSystemInFewerIterations) {
    Scene scene = materialScene(Method::ImplicitEuler, 1.0 / 60);
    scene.material->bend = 1e-4;
    scene.material->springDamping = 1e-3;
    scene.integrator.tolerance = 1e-11;
    scene.integrator.maxIterations = 2000;
    const Solved none =
        test::runPreconditioned(scene, Preconditioner::None, Precision::Double, 1, 60);
    const Solved jacobi =
        test::runPreconditioned(scene, Preconditioner::Jacobi, Precision::Double, 1, 60);
    EXPECT_EQ(none.stats.misses, 0);
    EXPECT_EQ(jacobi.stats.misses, 0);
    const double d = largestDifference(none.state, jacobi.state);
    std::printf("after 1 s: |x_none − x_jacobi| ≤ %.3g m; iterations per step %.1f → %.1f\n", d,
                double(none.stats.iterations) / none.stats.solves,
                double(jacobi.stats.iterations) / jacobi.stats.solves);
    EXPECT_LT(d, 1e-9 * scene.grid().extent());
    EXPECT_LT(jacobi.stats.iterations, none.stats.iterations * 3 / 4);
}

// Dot products sum fixed chunks in order, the block-Jacobi step is per vertex: 1, 2 and 3
// threads give the same bits, in float and double.
TEST(ImplicitPreconditioner, JacobiRunsAreBitIdenticalOnAnyThreadCount) {
    Scene scene = materialScene(Method::ImplicitEuler, 1.0 / 120);
    scene.cloth.nu = 40;  // rows enough for three bands of whole chunks, cells about square
    scene.cloth.nv = 90;
    scene.cloth.size = {1.2, 2.7};
    scene.pins = {{0, 89}, {39, 89}};
    const long steps = test::sanitizedSteps(8, 3);
    for (Precision precision : {Precision::Float, Precision::Double}) {
        const Solved serial =
            test::runPreconditioned(scene, Preconditioner::Jacobi, precision, 1, steps);
        for (int threads : {2, 3}) {
            const Solved parallel =
                test::runPreconditioned(scene, Preconditioner::Jacobi, precision, threads, steps);
            test::expectSameBits(serial.state, parallel.state,
                                 std::to_string(threads) + " threads");
            EXPECT_EQ(serial.stats.iterations, parallel.stats.iterations);
        }
    }
}

// A free-falling sheet without drag: its springs stay at rest and every step's Δv is hg, up to
// the solve's tolerance. From the second step on, the last step's Δv is that solution but for the
// residual the last solve left: the warm start leaves a few iterations where the first step,
// from 0, took many (without it every step would take as many).
TEST(ImplicitPreconditioner, WarmStartSolvesASteadyFallInAFewIterations) {
    const Scene scene = fallingMaterialScene(Method::ImplicitEuler, 0.0, 1.0 / 60);
    for (Preconditioner p : {Preconditioner::None, Preconditioner::Jacobi}) {
        const Solved first = test::runPreconditioned(scene, p, Precision::Double, 1, 1);
        const Solved ten = test::runPreconditioned(scene, p, Precision::Double, 1, 10);
        const double later = double(ten.stats.iterations - first.stats.iterations) / 9;
        std::printf("%s: %ld iterations at the first step, %.1f per step after\n",
                    preconditionerName(p), first.stats.iterations, later);
        EXPECT_GT(first.stats.iterations, 20) << preconditionerName(p);
        EXPECT_LT(later, 0.1 * double(first.stats.iterations)) << preconditionerName(p);
        EXPECT_EQ(ten.stats.misses, 0);
    }
}

}  // namespace
}  // namespace cloth
