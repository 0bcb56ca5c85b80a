// Every integrator on the GPU inside its predicted stability bound (src/model/stability.h,
// docs/stability.md), and implicit Euler far outside every explicit scheme's: a stiff cloth at
// the viewer's Δt = 1/60 s.
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "cpu/cpu_backend.h"
#include "gpu/gpu_test_support.h"
#include "model/stability.h"
#include "solver/diagnostics.h"

namespace cloth::test {
namespace {

using Json = nlohmann::json;

// gpu_parity_test.cpp's tilted cloth, smaller: every spring family, damping, two pins.
Json smallCloth(Method method) {
    Json j = Json::parse(R"({
      "name": "gpu-stability",
      "cloth": { "resolution": [12, 9], "size": [1.2, 0.9], "origin": [-0.6, 1.0, -0.45],
                 "u_axis": [1, 0, 0.1], "v_axis": [0, 0.3, 1], "mass": 0.5 },
      "springs": { "structural": 200.0, "shear": 80.0, "bend": 20.0 },
      "damping": 3.0,
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1]]
    })");
    j["integrator"] = {{"method", methodName(method)}, {"dt", 1e-3}};
    return j;
}

// The largest |x| and |v| of a state, and whether all of it is finite.
struct Extremes {
    double position = 0, speed = 0;
    bool finite = true;
};
Extremes extremes(const SimState& s) {
    Extremes e;
    for (std::size_t k = 0; k < s.positions.size(); ++k) {
        const double x = glm::length(s.positions[k]), v = glm::length(s.velocities[k]);
        e.finite = e.finite && std::isfinite(x) && std::isfinite(v);
        e.position = std::max(e.position, x);
        e.speed = std::max(e.speed, v);
    }
    return e;
}

class GpuIntegratorStability : public GpuTest, public ::testing::WithParamInterface<Method> {};

constexpr long kSteps = 2000;

// At 0.8 of the tight bound (the power-iteration λ_max at rest) for 2000 steps: no instability
// reported, everything finite, and the law a stable scheme keeps on a damped cloth without wind
// (DESIGN.md §6): the total energy never rises above where it started. The cloth starts at rest,
// so E(0) is its potential energy; falling, gravity's work goes into motion and springs and the
// damping (μ/m = 6/s) takes it out. A scheme past its bound pumps energy in and breaks this
// within a few hundred steps. Tolerance: float rounding of E, |E(0)| ≈ 600 J summed over 108
// vertices at ~1e-7 relative each (~1e-5 |E(0)| at worst): 1e-4 |E(0)| is ten times that.
// implicit_euler has no bound: it runs at 20 times explicit Euler's.
TEST_P(GpuIntegratorStability, EnergyNeverRisesAtFourFifthsOfItsBound) {
    const Method method = GetParam();
    Scene scene = parseScene(smallCloth(method).dump(), "gpu stability (test)");
    const StabilityBound bound = estimateStability(scene, 40);
    const double limit = bound.tightDt(method);
    scene.integrator.dt =
        std::isinf(limit) ? 20 * bound.tightDt(Method::ExplicitEuler) : 0.8 * limit;
    std::unique_ptr<Solver> solver = makeGpuSolver(scene);
    const double e0 = energy(scene, solver->read()).total();
    double highest = e0;
    StepResult r;
    for (int chunk = 0; chunk < 10 && !r.unstable; ++chunk) {
        r = solver->step(kSteps / 10);
        const SimState state = solver->read();
        highest = std::max(highest, energy(scene, state).total());
    }
    const Extremes e = extremes(solver->read());
    std::printf("%-16s bound %.4g s (safe %.4g s), dt %.4g s: max |x| %.3g m, max |v| %.3g m/s\n",
                methodName(method), limit, bound.safeDt(method), scene.integrator.dt, e.position,
                e.speed);
    std::printf("%-16s energy: E(0) %.6g J, highest %.6g J\n", methodName(method), e0, highest);
    EXPECT_FALSE(r.unstable) << r.reason;
    EXPECT_EQ(solver->stepsDone(), kSteps);
    EXPECT_TRUE(e.finite);
    EXPECT_LE(highest, e0 + 1e-4 * std::abs(e0)) << "energy rose: not a stable run";
    EXPECT_EQ(solver->solveStats().misses, 0);
}

INSTANTIATE_TEST_SUITE_P(Methods, GpuIntegratorStability, ::testing::ValuesIn(kMethods),
                         [](const ::testing::TestParamInfo<Method>& p) {
                             return std::string(methodName(p.param));
                         });

// Past the bound (1.5× the tight one) each explicit scheme blows up, and the GPU reports it at
// the step the CPU float backend does: the same check after the same update, whatever the
// scheme's passes.
class GpuIntegratorInstability : public GpuIntegratorStability {};

TEST_P(GpuIntegratorInstability, ReportsInstabilityWhereTheCpuDoes) {
    const Method method = GetParam();
    Scene scene = parseScene(smallCloth(method).dump(), "gpu instability (test)");
    scene.integrator.dt = 1.5 * estimateStability(scene, 40).tightDt(method);
    std::unique_ptr<Solver> gpu = makeGpuSolver(scene);
    std::unique_ptr<Solver> cpu = makeCpuSolver(scene, {Precision::Float, 1});
    const StepResult g = gpu->step(kSteps), c = cpu->step(kSteps);
    std::printf("%-16s dt %.4g s: unstable at step %ld (gpu), %ld (cpu float): %s\n",
                methodName(method), scene.integrator.dt, g.firstBadStep, c.firstBadStep,
                g.reason.c_str());
    ASSERT_TRUE(g.unstable);
    ASSERT_TRUE(c.unstable);
    EXPECT_NEAR(double(g.firstBadStep), double(c.firstBadStep), 2);
    EXPECT_EQ(gpu->stepsDone(), g.firstBadStep);
}

INSTANTIATE_TEST_SUITE_P(ExplicitMethods, GpuIntegratorInstability,
                         ::testing::Values(Method::ExplicitEuler, Method::SymplecticEuler,
                                           Method::Verlet, Method::Rk4),
                         [](const ::testing::TestParamInfo<Method>& p) {
                             return std::string(methodName(p.param));
                         });

// A 64×64 cloth with every family at K = 1e6 N/m stepped at 1/60 s: ω_max Δt is in the
// hundreds, where every explicit scheme explodes in a few steps; backward Euler stays finite and,
// being dissipative, never raises the energy, even with its CG stopped at the iteration cap.
TEST_F(GpuIntegratorStability, ImplicitEulerKeepsAStiffClothFiniteAtASixtiethOfASecond) {
    Json j = Json::parse(R"({
      "name": "gpu-stiff",
      "cloth": { "resolution": [64, 64], "size": [1.0, 1.0], "origin": [-0.5, 1.5, 0.0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.01 },
      "springs": { "structural": 1e6, "shear": 1e6, "bend": 1e6 },
      "damping": 0.1,
      "pins": [[0, 0], [-1, 0]],
      "integrator": { "method": "implicit_euler", "dt": 0.016666666666666666 }
    })");
    const Scene scene = parseScene(j.dump(), "gpu stiff (test)");
    const double explicitBound = estimateStability(scene).safeDt(Method::SymplecticEuler);
    std::unique_ptr<Solver> solver = makeGpuSolver(scene);
    const double e0 = energy(scene, solver->read()).total();
    double highest = e0;
    StepResult r;
    for (int chunk = 0; chunk < 6 && !r.unstable; ++chunk) {  // 0.5 s: the CG runs to its cap
        r = solver->step(5);
        highest = std::max(highest, energy(scene, solver->read()).total());
    }
    const Extremes e = extremes(solver->read());
    const SolveStats& s = solver->solveStats();
    std::printf(
        "stiff 64x64 at dt = 1/60 s (symplectic Euler's bound %.3g s): max |x| %.3g m, "
        "max |v| %.3g m/s; %ld solves, %ld iterations (most %d), %ld misses, worst "
        "residual %.3g\n",
        explicitBound, e.position, e.speed, s.solves, s.iterations, s.mostIterations, s.misses,
        s.worstResidual);
    std::printf("energy: E(0) %.6g J, highest %.6g J\n", e0, highest);
    EXPECT_LT(300 * explicitBound, scene.integrator.dt);
    EXPECT_FALSE(r.unstable) << r.reason;
    EXPECT_TRUE(e.finite);
    // Backward Euler dissipates: E never rises above its start (tolerance as above).
    EXPECT_LE(highest, e0 + 1e-4 * std::abs(e0)) << "energy rose";
    EXPECT_EQ(s.solves, 30);
}

}  // namespace
}  // namespace cloth::test

namespace cloth::test {
namespace {

// The agreement rule: at the same (K, Δt), CPU float and GPU reach the same verdict,
// stable or unstable, except within ±10% of the boundary. Stiffness over six decades, each
// explicit scheme at 0.85× and 1.15× its tight bound (0.5×/2× are further from the edge, where
// agreement is easier), 3000 steps. Just past the bound a mode grows slowly from rounding noise,
// so the step at which it runs away depends on the last bits: rk4 at K = 1000, 1.15×, runs away
// after 587 steps on the CPU in float and after 1039 or 1907 on the GPU, whether the drag is
// taken as (F − μv)/m or as F/m − cv. Every run that runs away does so well within 3000.
TEST_F(GpuIntegratorStability, CpuAndGpuAgreeOnStabilityAcrossSixDecadesOfStiffness) {
    int unstableVerdicts = 0;
    for (double k : {1e1, 1e3, 1e5, 1e7}) {
        for (Method method :
             {Method::ExplicitEuler, Method::SymplecticEuler, Method::Verlet, Method::Rk4}) {
            Json j = smallCloth(method);
            j["springs"] = {{"structural", k}, {"shear", 0.4 * k}, {"bend", 0.1 * k}};
            Scene scene = parseScene(j.dump(), "gpu agreement (test)");
            const double bound = estimateStability(scene, 40).tightDt(method);
            for (double factor : {0.85, 1.15}) {
                scene.integrator.dt = factor * bound;
                const StepResult g = makeGpuSolver(scene)->step(3000);
                const StepResult c = makeCpuSolver(scene, {Precision::Float, 1})->step(3000);
                EXPECT_EQ(g.unstable, c.unstable)
                    << methodName(method) << " K = " << k << ", dt = " << factor << " x bound: gpu "
                    << g.reason << " / cpu " << c.reason;
                unstableVerdicts += c.unstable;
            }
        }
    }
    // Not a vacuous agreement: past the bound most runs do blow up.
    EXPECT_GE(unstableVerdicts, 8);
}

}  // namespace
}  // namespace cloth::test
