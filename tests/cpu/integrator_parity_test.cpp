// The CPU backend's five integrators against the reference (tests/reference, written from
// docs/integrators.md alone): a small cloth with every feature of DESIGN.md §2, 1000 steps, each
// method. Double precision, serial and threaded, must agree to rounding; implicit Euler to the
// accuracy both conjugate gradients are run to; float to what float rounding accumulates before
// the first contact (after it, §2's "s < 0" flips on float rounding, see reference_parity_test).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <memory>

#include "cpu/cpu_backend.h"
#include "reference/reference.h"
#include "solver/solver.h"
#include "support/integrator_scenes.h"
#include "support/reference_bridge.h"

namespace cloth {
namespace {

constexpr long kSteps = 1000;
constexpr double kDoubleTolerance = 1e-12;   // max |p − p_ref| / extent
constexpr double kImplicitTolerance = 1e-9;  // both CGs stopped at |r| ≤ 1e-12 |b|
constexpr double kFloatTolerance = 1e-5;     // before the first contact

Scene sceneFor(Method method) {
    Scene s = everythingScene(method);
    s.integrator.tolerance = 1e-12;
    s.integrator.maxIterations = 1000;
    return s;
}

SimState runCpu(const Scene& scene, Precision precision, int threads, long steps) {
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {precision, threads});
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << methodName(scene.integrator.method) << ": " << r.reason;
    EXPECT_EQ(r.stepsTaken, steps);
    EXPECT_EQ(solver->solveStats().misses, 0) << methodName(scene.integrator.method);
    return solver->read();
}

ref::Simulation runReference(const Scene& scene, long steps) {
    ref::Simulation sim(toReference(scene));
    for (long n = 0; n < steps; ++n) sim.step();
    EXPECT_TRUE(sim.finiteAndBelowMaxSpeed()) << methodName(scene.integrator.method);
    EXPECT_EQ(sim.cgStats().misses, 0);
    return sim;
}

// The scene reaches its colliders with most of the run left, in every scheme: the parity below
// covers resting and sliding contact.
TEST(IntegratorParity, SmallEverythingSceneReachesItsColliders) {
    for (Method method : kMethods) {
        const long first = firstContactStep(sceneFor(method), kSteps);
        EXPECT_GT(first, 0) << methodName(method);
        EXPECT_LT(first, kSteps / 2) << methodName(method);
    }
}

TEST(IntegratorParity, DoubleMatchesTheReferenceForEveryMethod) {
    for (Method method : kMethods) {
        // vbd's 10 iterations do not converge to its reference, backward Euler: its parity is
        // tests/cpu/vbd_test.cpp's, at convergence.
        if (method == Method::Vbd) continue;
        const Scene scene = sceneFor(method);
        const double extent = scene.grid().extent();
        const ref::Simulation expected = runReference(scene, kSteps);
        const double tolerance =
            method == Method::ImplicitEuler ? kImplicitTolerance : kDoubleTolerance;
        for (int threads : {1, 2}) {
            const double dev = maxDeviationOverExtent(
                runCpu(scene, Precision::Double, threads, kSteps), expected, extent);
            std::printf("%-16s double, %d thread(s): max |p - p_ref| / extent = %.3g\n",
                        methodName(method), threads, dev);
            EXPECT_LT(dev, tolerance) << methodName(method) << ", " << threads << " threads";
        }
    }
}

TEST(IntegratorParity, FloatMatchesTheReferenceBeforeContact) {
    for (Method method : kMethods) {
        // vbd's 10 iterations do not converge to its reference, backward Euler: its parity is
        // tests/cpu/vbd_test.cpp's, at convergence.
        if (method == Method::Vbd) continue;
        const Scene scene = sceneFor(method);
        const long steps = firstContactStep(scene, kSteps) - 1;
        ASSERT_GT(steps, 100) << methodName(method);
        const double dev =
            maxDeviationOverExtent(runCpu(scene, Precision::Float, 1, steps),
                                   runReference(scene, steps), scene.grid().extent());
        std::printf("%-16s float, %ld steps before contact: max |p - p_ref| / extent = %.3g\n",
                    methodName(method), steps, dev);
        EXPECT_LT(dev, kFloatTolerance) << methodName(method);
    }
}

// Threads split the vertices into bands; no vertex's arithmetic, and no CG reduction, may depend
// on the split: every method gives the same bits on 1, 2 and 3 threads, in double and float.
TEST(IntegratorParity, SerialAndThreadedRunsAreBitIdenticalForEveryMethod) {
    for (Method method : kMethods) {
        const Scene scene = sceneFor(method);
        for (Precision precision : {Precision::Double, Precision::Float}) {
            const SimState serial = runCpu(scene, precision, 1, 300);
            for (int threads : {2, 3}) {
                const SimState parallel = runCpu(scene, precision, threads, 300);
                const std::size_t bytes = serial.positions.size() * sizeof(glm::dvec3);
                EXPECT_EQ(0, std::memcmp(parallel.positions.data(), serial.positions.data(), bytes))
                    << methodName(method) << ", " << threads << " threads, "
                    << precisionName(precision);
                EXPECT_EQ(0,
                          std::memcmp(parallel.velocities.data(), serial.velocities.data(), bytes))
                    << methodName(method) << ", " << threads << " threads, "
                    << precisionName(precision);
            }
        }
    }
}

}  // namespace
}  // namespace cloth
