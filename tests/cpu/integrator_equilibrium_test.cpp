// Static equilibrium (DESIGN.md §6): every scheme's fixed point with v = 0 is F(x) + m g = 0 at
// the free vertices, whatever its step. Implicit Euler with large steps, which damps the fast modes
// numerically, must reach the same hanging shape as symplectic Euler with small ones, and that
// shape must balance the weight of every free vertex (checked with the reference's forces).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cpu/cpu_backend.h"
#include "model/stability.h"
#include "reference/reference.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/reference_bridge.h"

namespace cloth {
namespace {

// A 6×5 cloth hanging in the xy plane from its two top corners, every spring family. The damping
// c = μ/m = 6 /s settles the slowest (pendulum-like, ω ≈ 3 rad/s) modes as about e^{−3t}: after
// 10 s they are below 1e-12 of their start.
Scene hangingCloth(Method method, double dt) {
    Scene s = parseScene(R"({
      "cloth": { "resolution": [6, 5], "size": [1.0, 0.8], "origin": [-0.5, 1, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": 0.05 },
      "springs": { "structural": 300, "shear": 100, "bend": 20 },
      "damping": 0.3,
      "pins": [[0, 0], [-1, 0]],
      "integrator": { "dt": 0.001, "tolerance": 1e-10, "max_iterations": 500 } })",
                         "hanging (test)");
    s.integrator.method = method;
    s.integrator.dt = dt;
    return s;
}

SimState settle(const Scene& scene, double seconds) {
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Double, 1});
    const long steps = std::lround(seconds / scene.integrator.dt);
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << methodName(scene.integrator.method) << ": " << r.reason;
    EXPECT_EQ(solver->solveStats().misses, 0);
    return solver->read();
}

// max over free vertices of |F(x) + m g| / (m |g|), F by the reference (springs; no wind here).
double equilibriumResidual(const Scene& scene, const SimState& s) {
    const ref::Simulation model(toReference(scene));
    const std::vector<ref::V3> f = model.forces(toReferenceVectors(s.positions));
    const double m = scene.cloth.mass, g = glm::length(scene.gravity);
    double worst = 0;
    for (std::size_t k = 0; k < f.size(); ++k) {
        if (model.isPinned(int(k))) continue;
        const glm::dvec3 net = glm::dvec3(f[k][0], f[k][1], f[k][2]) + m * scene.gravity;
        worst = std::max(worst, glm::length(net) / (m * g));
    }
    return worst;
}

TEST(IntegratorEquilibrium, ImplicitEulerReachesTheHangingEquilibriumOfSymplecticEuler) {
    const Scene probe = hangingCloth(Method::SymplecticEuler, 1e-3);
    const double bound = estimateStability(probe, 40).safeDt(Method::SymplecticEuler);
    const double small = std::min(1e-3, 0.25 * bound), large = 0.05;  // ≈ 6.5× that bound
    ASSERT_GT(large, 4 * bound);

    const Scene explicitScene = hangingCloth(Method::SymplecticEuler, small);
    const Scene implicitScene = hangingCloth(Method::ImplicitEuler, large);
    const SimState a = settle(explicitScene, 10);
    const SimState b = settle(implicitScene, 10);
    const double extent = probe.grid().extent();
    double gap = 0, sag = 0, speed = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k) {
        gap = std::max(gap, glm::length(a.positions[k] - b.positions[k]));
        sag = std::max(
            sag, glm::length(a.positions[k] - probe.grid().restPosition(int(k % 6), int(k / 6))));
        speed = std::max({speed, glm::length(a.velocities[k]), glm::length(b.velocities[k])});
    }
    const double ra = equilibriumResidual(explicitScene, a);
    const double rb = equilibriumResidual(implicitScene, b);
    std::printf(
        "hanging cloth: symplectic (dt %.2g) vs implicit (dt %.2g): max |dp| / extent "
        "%.3g, largest sag %.3f m; |F + m g| / m|g|: %.3g, %.3g; speeds < %.3g m/s\n",
        small, large, gap / extent, sag, ra, rb, speed);
    EXPECT_GT(sag, 0.01);  // it did move: the shape is not the rest shape
    EXPECT_LT(gap / extent, 1e-10);
    EXPECT_LT(ra, 1e-10);
    EXPECT_LT(rb, 1e-10);
    EXPECT_LT(speed, 1e-8);
}

// A chain at rest leaves implicit Euler a right-hand side at the rounding of its terms (weight
// against spring force), in float down to 1e-20 as the damping takes the last motion. The CG
// then stops at |r| ≤ ε |s| (src/cpu/cpu_implicit.cpp); before it reduced such a b until p·A p
// underflowed: block-Jacobi counted 19 of these 300 solves as breakdowns, and without a
// preconditioner the run ended unstable.
TEST(IntegratorEquilibrium, ImplicitEulerInFloatRestsWithoutMissesAtTheRoundingOfItsRightHandSide) {
    // The shipped chain (scenes/chain.json) under implicit Euler.
    Scene scene = loadScene(CLOTH_SOURCE_DIR "/scenes/chain.json",
                            {"integrator.method=\"implicit_euler\"", "integrator.dt=0.2"});
    for (Preconditioner p :
         {Preconditioner::None, Preconditioner::Jacobi, Preconditioner::Multigrid}) {
        scene.integrator.preconditioner = p;
        std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Float, 1});
        const StepResult r = solver->step(300);  // 60 s: at rest from about 40 s on
        ASSERT_FALSE(r.unstable) << r.reason;
        const SolveStats& stats = solver->solveStats();
        EXPECT_EQ(stats.misses, 0) << "first at step " << stats.firstMissStep;
        EXPECT_EQ(stats.breakdowns, 0);
        EXPECT_LT(equilibriumResidual(scene, solver->read()), 1e-5);
    }
}

}  // namespace
}  // namespace cloth
