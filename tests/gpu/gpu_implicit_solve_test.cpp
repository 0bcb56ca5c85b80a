// implicit_euler's conjugate gradient on the GPU (docs/integrators.md): the Δv a step applies
// solves the linearised backward-Euler system (checked here in double with src/model's stencil),
// the grab enters H, a solve that cannot converge is counted as a miss, and the iteration cap is
// exact although the host reads the residual only every few iterations.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "gpu/gpu_test_support.h"
#include "model/stiffness.h"

namespace cloth::test {
namespace {

using Json = nlohmann::json;

// A tilted cloth with every family, two pins, stepped at the viewer's 1/60 s.
Json clothJson(double stiffness, int maxIterations) {
    Json j = Json::parse(R"({
      "name": "gpu-implicit",
      "cloth": { "resolution": [9, 7], "size": [1.2, 0.9], "origin": [-0.6, 1.0, -0.45],
                 "u_axis": [1, 0, 0.1], "v_axis": [0, 0.3, 1], "mass": 0.05 },
      "damping": 0.2,
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1]]
    })");
    j["springs"] = {{"structural", stiffness}, {"shear", stiffness / 2}, {"bend", stiffness / 10}};
    j["integrator"] = {{"method", "implicit_euler"},
                       {"dt", 1.0 / 60},
                       {"tolerance", 1e-5},
                       {"max_iterations", maxIterations}};
    return j;
}

Scene clothScene(double stiffness, int maxIterations) {
    return parseScene(clothJson(stiffness, maxIterations).dump(), "gpu implicit (test)");
}

// |b − A Δv| / |b| of the system ((m + hμ) I + h² H) Δv = h (F − μ v + m g − h H v) at the state
// `before`, for the Δv = v_after − v_before the step applied; in double, from the stencil of
// src/model/stiffness.h and the spring law of src/model/forces.h, with the grab's K in H and F.
double relativeResidual(const Scene& scene, const std::optional<Grab>& grab, const SimState& before,
                        const SimState& after) {
    const Grid g = scene.grid();
    const std::size_t n = std::size_t(g.count());
    const auto springs = activeSprings<double>(scene);
    std::vector<std::uint8_t> pinned(n, 0);
    for (const Pin& p : scene.pins) pinned[std::size_t(g.index(p.i, p.j))] = 1;
    const std::vector<glm::dvec3>& x = before.positions;
    const std::vector<glm::dvec3>& v = before.velocities;
    std::vector<glm::dvec3> dv(n), hv(n), hdv(n);
    for (std::size_t k = 0; k < n; ++k) dv[k] = after.velocities[k] - v[k];
    stiffnessProduct(g.nu, g.nv, springs, x.data(), v.data(), pinned.data(), hv.data(), 0,
                     std::int64_t(n));
    stiffnessProduct(g.nu, g.nv, springs, x.data(), dv.data(), pinned.data(), hdv.data(), 0,
                     std::int64_t(n));
    const double h = scene.integrator.dt, m = scene.cloth.mass, mu = scene.damping;
    double rr = 0, bb = 0;
    for (int j = 0; j < g.nv; ++j) {
        for (int i = 0; i < g.nu; ++i) {
            const std::size_t k = std::size_t(g.index(i, j));
            if (pinned[k]) continue;
            glm::dvec3 f(0), hvk = hv[k], hdvk = hdv[k];
            for (const StencilSpring<double>& s : springs)
                if (g.contains(i + s.di, j + s.dj))
                    f += springForce(x[k], x[k + std::size_t(s.indexOffset)], s.stiffness,
                                     s.restLength);
            if (grab && std::size_t(grab->vertex) == k) {
                f += grabForce(x[k], grab->target, grab->stiffness);
                hvk += grab->stiffness * v[k];
                hdvk += grab->stiffness * dv[k];
            }
            const glm::dvec3 b = h * (f - mu * v[k] + m * scene.gravity - h * hvk);
            const glm::dvec3 r = b - ((m + h * mu) * dv[k] + h * h * hdvk);
            rr += glm::dot(r, r);
            bb += glm::dot(b, b);
        }
    }
    return std::sqrt(rr / bb);
}

class GpuImplicitSolve : public GpuTest {};

// Steps from a moving, deformed state, with the grab pulling one vertex: each step's Δv solves
// the system to the tolerance (1e-5), up to float rounding of A Δv and of v + Δv, whichever the
// preconditioner: it changes how the system is solved, not which (the 9 × 7 grid is multigrid's
// coarsest at once: its V-cycle is the exact solve).
TEST_F(GpuImplicitSolve, EachStepSolvesTheLinearisedSystem) {
    for (Preconditioner p :
         {Preconditioner::None, Preconditioner::Jacobi, Preconditioner::Multigrid}) {
        Scene scene = clothScene(2000, 200);
        scene.integrator.preconditioner = p;
        std::unique_ptr<Solver> solver = makeGpuSolver(scene);
        ASSERT_FALSE(solver->step(20).unstable);
        const Grab grab{scene.grid().index(4, 2), {0.1, 0.5, 0.2}, 50.0};
        solver->setGrab(grab);
        double worst = 0;
        for (int s = 0; s < 5; ++s) {
            const SimState before = solver->read();
            ASSERT_FALSE(solver->step(1).unstable);
            worst = std::max(worst, relativeResidual(scene, grab, before, solver->read()));
        }
        const SolveStats& st = solver->solveStats();
        std::printf(
            "%s: worst |b - A dv| / |b| = %.3g over 5 steps; %ld solves, %ld iterations (most "
            "%d), %ld misses\n",
            preconditionerName(p), worst, st.solves, st.iterations, st.mostIterations, st.misses);
        EXPECT_LT(worst, 1e-4) << preconditionerName(p);
        EXPECT_EQ(st.solves, 25);
        EXPECT_EQ(st.misses, 0);
        if (p != Preconditioner::Multigrid) {  // the V-cycle solves it in fewer
            EXPECT_GT(st.mostIterations, 8) << "a solve of several chunks of iterations";
        }
    }
}

// A sheet falling freely (no pins, no drag, springs at rest): every step's Δv is h g, so from
// the second step on the last step's solution is a better start than 0. The same law as the
// CPU's (tests/cpu/implicit_preconditioner_test.cpp), with less gain in float: b − A Δv₀
// recomputed in float carries rounding near the tolerance. Seen: none 26 → 14.7 iterations per
// step, jacobi 41 → 11.8; from 0 every step (the warm start removed) 26 → 26.3, 41 → 39.3.
TEST_F(GpuImplicitSolve, TheWarmStartSolvesASteadyFallInFewerIterations) {
    for (Preconditioner p : {Preconditioner::None, Preconditioner::Jacobi}) {
        Scene scene = clothScene(2e4, 200);
        scene.pins.clear();
        scene.damping = 0;
        scene.integrator.preconditioner = p;
        std::unique_ptr<Solver> solver = makeGpuSolver(scene);
        ASSERT_FALSE(solver->step(1).unstable);
        const long first = solver->solveStats().iterations;
        ASSERT_FALSE(solver->step(9).unstable);
        const double later = double(solver->solveStats().iterations - first) / 9;
        std::printf("%s: %ld iterations at the first step, %.1f per step after\n",
                    preconditionerName(p), first, later);
        EXPECT_GT(first, 20) << preconditionerName(p);
        EXPECT_LT(later, 0.7 * double(first)) << preconditionerName(p);
    }
}

// Without the grab the same check fails for the grab's step: the grab's K is in H and F.
TEST_F(GpuImplicitSolve, TheGrabIsPartOfTheSystem) {
    const Scene scene = clothScene(2000, 200);
    std::unique_ptr<Solver> solver = makeGpuSolver(scene);
    const Grab grab{scene.grid().index(4, 2), {0.1, 0.5, 0.2}, 50.0};
    solver->setGrab(grab);
    const SimState before = solver->read();
    ASSERT_FALSE(solver->step(1).unstable);
    const SimState after = solver->read();
    EXPECT_LT(relativeResidual(scene, grab, before, after), 1e-4);
    EXPECT_GT(relativeResidual(scene, std::nullopt, before, after), 1e-2);
}

// A stiff cloth and a cap of 13 iterations (not a multiple of the 8 between reads): every solve
// stops at exactly 13, is a miss, and the first miss and the worst residual are recorded.
TEST_F(GpuImplicitSolve, ASolveThatCannotConvergeIsAMiss) {
    std::unique_ptr<Solver> solver = makeGpuSolver(clothScene(1e6, 13));
    const StepResult r = solver->step(4);
    const SolveStats& s = solver->solveStats();
    std::printf(
        "K = 1e6 N/m, max_iterations 13: %ld solves, %ld iterations, %ld misses (first "
        "at step %ld), worst residual %.3g\n",
        s.solves, s.iterations, s.misses, s.firstMissStep, s.worstResidual);
    EXPECT_FALSE(r.unstable) << r.reason;
    EXPECT_EQ(s.solves, 4);
    EXPECT_EQ(s.iterations, 4 * 13);
    EXPECT_EQ(s.mostIterations, 13);
    EXPECT_EQ(s.misses, 4);
    EXPECT_EQ(s.firstMissStep, 1);
    EXPECT_GT(s.worstResidual, 1e-5);
}

// The cap and the tolerance are parameters: setParameters changes them without a new kernel.
TEST_F(GpuImplicitSolve, SetParametersChangesTheCapAndTheTolerance) {
    Scene scene = clothScene(2000, 200);
    std::unique_ptr<Solver> solver = makeGpuSolver(scene);
    solver->step(3);
    EXPECT_EQ(solver->solveStats().misses, 0);
    scene.integrator.maxIterations = 2;
    solver->setParameters(scene);
    solver->step(3);
    EXPECT_EQ(solver->solveStats().misses, 3);
    EXPECT_EQ(solver->solveStats().firstMissStep, 4);

    Scene loose = clothScene(2000, 200);
    std::unique_ptr<Solver> tight = makeGpuSolver(loose), relaxed = makeGpuSolver(loose);
    loose.integrator.tolerance = 1e-2;
    relaxed->setParameters(loose);
    tight->step(1);
    relaxed->step(1);
    std::printf("iterations of the first solve: tolerance 1e-5 %ld, 1e-2 %ld\n",
                tight->solveStats().iterations, relaxed->solveStats().iterations);
    EXPECT_LT(relaxed->solveStats().iterations, tight->solveStats().iterations);
    EXPECT_EQ(relaxed->solveStats().misses, 0);
}

// A chain at rest leaves a right-hand side at the rounding of its terms (1e-20 in float as the
// damping takes the last motion): the solve stops at |r| ≤ ε |s| (cg_reduce.comp), as the
// CPU's does (tests/cpu/integrator_equilibrium_test.cpp). Before, block-Jacobi's and the
// V-cycle's solves reduced such a b until p·A p underflowed: 18 and 3 of these 300 were counted
// as breakdowns.
TEST_F(GpuImplicitSolve, AChainAtRestEndsItsSolvesWithoutMisses) {
    // The shipped chain (scenes/chain.json) under implicit Euler.
    Scene scene = loadScene(CLOTH_SOURCE_DIR "/scenes/chain.json",
                            {"integrator.method=\"implicit_euler\"", "integrator.dt=0.2"});
    for (Preconditioner p : kPreconditioners) {
        if (p == Preconditioner::Aggregation) continue;  // CPU only: GpuErrors checks the refusal
        scene.integrator.preconditioner = p;
        std::unique_ptr<Solver> solver = makeGpuSolver(scene);
        const StepResult r = solver->step(300);  // 60 s: at rest from about 40 s on
        ASSERT_FALSE(r.unstable) << r.reason;
        const SolveStats& stats = solver->solveStats();
        EXPECT_EQ(stats.misses, 0)
            << preconditionerName(p) << ", first at step " << stats.firstMissStep;
        const SimState end = solver->read();
        EXPECT_LT(glm::length(end.velocities.back()), 1e-6);  // it rests
    }
}

}  // namespace
}  // namespace cloth::test
