// Every integrator on the GPU against the CPU float backend (docs/integrators.md: the same
// update on both): the small cloth with every feature of DESIGN.md §2 (tests/support's
// everythingScene: three families, wind, a floor and a sphere it falls onto, three pins).
// Float against float differ only in rounding order (FMA contraction, sqrt, the CG's
// reductions: double on the CPU, a float tree on the GPU).
#include <cstdio>

#include "cpu/cpu_backend.h"
#include "gpu/gpu_test_support.h"
#include "support/integrator_scenes.h"

namespace cloth::test {
namespace {

constexpr long kSteps = 1000;
// max |p_gpu − p_cpu| / extent, before the first contact and after 1000 steps of sliding and
// resting on the colliders, where last-bit differences could decide "inside or not"
// (docs/gpu.md, "Contacts"); seen: at most 8.4e-7.
constexpr double kTolerance = 1e-5;
// vbd solves each vertex's 3×3 system in float on the GPU, in double on the CPU (a stiff spring
// beside a light vertex: model/vbd_local.h): 5.8e-8 of the extent apart before the contact
// since both iterate the displacement beside the position (1.4e-6 before; 7.9e-9 when vbd first
// ran on the GPU, before its adaptive guess and row kernel), the two then part by the contacts'
// decisions; seen 1.2e-5 after 1000 steps (2026-11-30).
constexpr double kVbdContactTolerance = 5e-5;
// With Chebyshev's extrapolation (ρ = 0.9, 20 sweeps) the contacts' decisions part the two more:
// seen 2.0e-3 at step 400 and 7.0e-4 at 1000, where the CPU in double and in float differ by
// 3.9e-4 and 4.8e-4; before the contact 1.9e-7. Since the projections take no friction term
// (docs/integrators.md "vbd", contact and friction), which on these frictionless colliders still
// left a rounding-level tangential change, rounded differently on the two: 1.1e-5 at 1000;
// iterating the displacement, 5.7e-8 before the contact and 4.6e-6 at 1000.
constexpr double kVbdChebyshevContactTolerance = 5e-3;
// implicit_euler's contacts are constraints of its solve (docs/integrators.md, "Contact in the
// solve"), stopped at |r| ≤ 10⁻⁶ |b| on both: 1.3e-7 m apart at the first contact (step 240),
// the two part while the cloth slides and sticks on the floor (1.1e-6 m at step 300, 1.1e-4 m at
// 550, 2.2e-4 m at 1000), in the same 2 iterations a step; seen 1.0e-4 of the extent.
constexpr double kImplicitContactTolerance = 5e-4;

Scene sceneFor(Method method, double dt = 1e-3) {
    Scene s = everythingScene(method, dt);
    s.integrator.tolerance = 1e-6;  // both CGs well below the differences measured
    s.integrator.maxIterations = 500;
    return s;
}

struct Runs {
    SimState gpu, cpu;
    SolveStats gpuSolves, cpuSolves;
};
Runs runBoth(const Scene& scene, long steps) {
    std::unique_ptr<Solver> gpu = makeGpuSolver(scene);
    std::unique_ptr<Solver> cpu = makeCpuSolver(scene, {Precision::Float, 1});
    for (Solver* s : {gpu.get(), cpu.get()}) {
        const StepResult r = s->step(steps);
        EXPECT_FALSE(r.unstable) << s->name() << ": " << r.reason;
        EXPECT_EQ(r.stepsTaken, steps) << s->name();
        EXPECT_EQ(s->solveStats().misses, 0) << s->name();
    }
    return {gpu->read(), cpu->read(), gpu->solveStats(), cpu->solveStats()};
}

class GpuIntegratorParity : public GpuTest, public ::testing::WithParamInterface<Method> {};

// GPU against CPU float just before the first contact and after kSteps: max |p_gpu − p_cpu| over
// the extent, and the full runs' solve counts. `label` names the case in the printed line.
struct ContactParity {
    long beforeContact = 0;
    double free = 0, all = 0;
    Runs runs;
};
ContactParity contactParity(const Scene& scene, const char* label) {
    ContactParity c;
    const double extent = scene.grid().extent();
    c.beforeContact = firstContactStep(scene, kSteps) - 1;
    EXPECT_GT(c.beforeContact, 100) << label;
    const Runs free = runBoth(scene, c.beforeContact);
    c.runs = runBoth(scene, kSteps);
    c.free = maxDifferenceOverExtent(free.gpu, free.cpu, extent);
    c.all = maxDifferenceOverExtent(c.runs.gpu, c.runs.cpu, extent);
    std::printf("%-16s gpu vs cpu float: %ld steps before contact %.3g, %ld steps %.3g (/ extent)",
                label, c.beforeContact, c.free, kSteps, c.all);
    return c;
}

TEST_P(GpuIntegratorParity, MatchesTheCpuFloatBackend) {
    const Method method = GetParam();
    const ContactParity c = contactParity(sceneFor(method), methodName(method));
    if (method == Method::ImplicitEuler)
        std::printf("; CG iterations gpu %ld, cpu %ld", c.runs.gpuSolves.iterations,
                    c.runs.cpuSolves.iterations);
    std::printf("\n");
    EXPECT_LT(c.free, kTolerance);
    EXPECT_LT(c.all, method == Method::Vbd             ? kVbdContactTolerance
                     : method == Method::ImplicitEuler ? kImplicitContactTolerance
                                                       : kTolerance);
    EXPECT_EQ(c.runs.gpuSolves.solves, c.runs.cpuSolves.solves);
}

// The viewer's Δt = 1/60 s with springs 100× stiffer (h² λ_max/m ≈ 130, far beyond every
// explicit scheme's bound): the CG works for its result over many iterations, and the GPU's
// float reductions still land where the CPU's do, with either preconditioner and the warm start;
// the block-Jacobi one takes as many iterations on both backends (±10 %). The cloth slides on the
// sphere from step 55, and a contact is a threshold (is p* inside?): at step 70 vertex (2, 2),
// grazing the sphere 1e-5 m out, is predicted inside on the GPU and not on the CPU, and the two
// part by 1.0e-3 of the extent there and 1.3e-4–1.8e-4 after 100 steps (2e-6 at step 60; CPU
// float and double stay within 6e-6). So the contact tolerance, as for the contact parity above.
TEST_F(GpuIntegratorParity, ImplicitEulerAtALargeStepMatchesTheCpu) {
    for (Preconditioner p : {Preconditioner::None, Preconditioner::Jacobi}) {
        Scene scene = sceneFor(Method::ImplicitEuler, 1.0 / 60);
        scene.springs = {2e4, 8e3, 2e3};
        scene.integrator.preconditioner = p;
        const Runs runs = runBoth(scene, 100);
        const double diff = maxDifferenceOverExtent(runs.gpu, runs.cpu, scene.grid().extent());
        std::printf(
            "implicit_euler (%s) dt 1/60 s, 100 steps: gpu vs cpu float %.3g (/ extent); CG "
            "iterations gpu %ld (most %d), cpu %ld (most %d)\n",
            preconditionerName(p), diff, runs.gpuSolves.iterations, runs.gpuSolves.mostIterations,
            runs.cpuSolves.iterations, runs.cpuSolves.mostIterations);
        EXPECT_LT(diff, kImplicitContactTolerance) << preconditionerName(p);
        EXPECT_GT(runs.gpuSolves.mostIterations, 8) << preconditionerName(p);
        EXPECT_NEAR(double(runs.gpuSolves.iterations), double(runs.cpuSolves.iterations),
                    0.1 * double(runs.cpuSolves.iterations))
            << preconditionerName(p);
    }
}

// vbd with Chebyshev's extrapolation (docs/integrators.md "vbd"): each sweep after the first moves
// x to ω (x − x^(n−2)) + x^(n−2), so the two iterates it keeps must be whole on the GPU too (the
// oldest once lived in a buffer sized for the CG's partial sums: every vertex past the first few
// dozen was extrapolated from 0, and the sheet left at 10⁴ m/s in its first step).
TEST_F(GpuIntegratorParity, VbdWithChebyshevMatchesTheCpu) {
    Scene scene = sceneFor(Method::Vbd);
    scene.integrator.chebyshevRho = 0.9;
    scene.integrator.iterations = 20;
    const ContactParity c = contactParity(scene, "vbd, rho 0.9");
    std::printf("\n");
    EXPECT_LT(c.free, kTolerance);
    EXPECT_LT(c.all, kVbdChebyshevContactTolerance);
}

INSTANTIATE_TEST_SUITE_P(Methods, GpuIntegratorParity, ::testing::ValuesIn(kMethods),
                         [](const ::testing::TestParamInfo<Method>& p) {
                             return std::string(methodName(p.param));
                         });

}  // namespace
}  // namespace cloth::test
