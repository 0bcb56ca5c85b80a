// The GPU backend with a material's spring damping (HAS_SPRING_DAMPING: springs.glsl's
// springDampingForce in the force pass, stiffness.glsl's springDampingProduct in implicit Euler's
// system, mirroring model/spring_math.h): against the reference and the CPU float backend to the
// tolerances of gpu_bending_test.cpp, and the damping's own effect against the reference's; a
// scene without it compiles none of it.
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "support/material_scene.h"

namespace cloth::test {
namespace {

constexpr double kReferenceTolerance = 1e-4;  // max |p − p_ref| / extent (gpu_parity_test)
constexpr double kCpuFloatTolerance = 1e-5;   // max |p_gpu − p_cpu| / extent (integrator parity)

// The sheet of tests/cpu/spring_damping_test.cpp, hanging from two corners under gravity and a
// light wind, with β = 1e-4 s: symplectic Euler's ω²Δt² + 2βω²Δt ≈ 3.3 < 4; explicit Euler,
// stable only thanks to β, at Δt = 1e-5 s.
constexpr double kBeta = 1e-4;

Scene dampedScene(Method method) {
    Scene s = materialScene(method, method == Method::ExplicitEuler ? 1e-5 : 1e-4);
    s.material->springDamping = kBeta;
    s.integrator.tolerance = 1e-6;
    s.integrator.maxIterations = 500;
    return s;
}

// max_k |(a_k − a0_k) − (r_k − r0_k)| and max_k |r_k − r0_k| [m]: what β changes in a solver's
// state against what it changes in the reference's.
std::pair<double, double> effectError(const SimState& a, const SimState& a0,
                                      const ref::Simulation& r, const ref::Simulation& r0) {
    double error = 0, effect = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k) {
        glm::dvec3 e;
        for (int c = 0; c < 3; ++c) e[c] = r.positions()[k][c] - r0.positions()[k][c];
        effect = std::max(effect, glm::length(e));
        error = std::max(error, glm::length(a.positions[k] - a0.positions[k] - e));
    }
    return {error, effect};
}

class GpuSpringDamping : public GpuTest, public ::testing::WithParamInterface<Method> {};

// The whole state against the reference and the CPU float backend to the tolerances of
// gpu_bending_test.cpp. The damping moves this sheet by ~5e-5 of its extent, less than those
// tolerances, so its own effect — the state with β minus the state without, on the GPU and in
// the reference — is compared too: to 25% (measured 3–11%; a GPU without the damping is 100%
// off). Explicit Euler has no undamped run to subtract (it blows up), so leaving the damping out
// fails its first comparison.
TEST_P(GpuSpringDamping, MatchesTheReferenceAndTheCpuFloatBackend) {
    const Method method = GetParam();
    const Scene scene = dampedScene(method);
    const long steps = method == Method::ExplicitEuler ? 3000 : 1000;
    const double extent = scene.grid().extent();
    const SimState gpu = runGpu(scene, steps);
    const ref::Simulation reference = runReference(scene, steps);
    const double offReference = maxDeviationOverExtent(gpu, reference, extent);
    const double toCpu = maxDifferenceOverExtent(gpu, runCpuFloat(scene, steps), extent);
    std::printf("%-16s gpu vs reference %.3g, vs cpu float %.3g", methodName(method), offReference,
                toCpu);
    EXPECT_LT(offReference, kReferenceTolerance);
    EXPECT_LT(toCpu, kCpuFloatTolerance);
    if (method != Method::ExplicitEuler) {
        Scene plain = scene;
        plain.material->springDamping = 0;
        const auto [error, effect] =
            effectError(gpu, runGpu(plain, steps), reference, runReference(plain, steps));
        std::printf("; the damping moved it %.3g, the gpu's effect is off by %.3g of it",
                    effect / extent, error / effect);
        EXPECT_GT(effect / extent, 1e-5);
        EXPECT_LT(error, 0.25 * effect);
    }
    std::printf("\n");
}

INSTANTIATE_TEST_SUITE_P(Methods, GpuSpringDamping,
                         ::testing::Values(Method::ExplicitEuler, Method::SymplecticEuler,
                                           Method::Verlet, Method::Rk4, Method::ImplicitEuler),
                         [](const ::testing::TestParamInfo<Method>& p) {
                             return std::string(methodName(p.param));
                         });

// Implicit Euler where only the damping's Jacobian in the system keeps it stable: Δt = 1e-3 s and
// β = 1e-3 s give hβω²_max ≈ 110, so a damping taken explicitly would blow up at once (as on the
// CPU, tests/cpu/spring_damping_test.cpp). Every solve converges and the reference agrees to
// 1e-3 of the extent: float conjugate gradients stopped at 1e-6 over 200 such steps leave
// 2e-4 (the CPU float backend lands 2.3e-4 from the reference as well).
TEST_F(GpuSpringDamping, ImplicitEulerWithTheDampingJacobianIsStable) {
    Scene scene = materialScene(Method::ImplicitEuler, 1e-3);
    scene.material->springDamping = 1e-3;
    scene.integrator.tolerance = 1e-6;
    scene.integrator.maxIterations = 2000;
    std::unique_ptr<Solver> solver = makeGpuSolver(scene, {});
    const StepResult r = solver->step(200);
    ASSERT_FALSE(r.unstable) << r.reason;
    const SolveStats& st = solver->solveStats();
    const double off =
        maxDeviationOverExtent(solver->read(), runReference(scene, 200), scene.grid().extent());
    std::printf(
        "gpu implicit Euler dt 1e-3, beta 1e-3: %ld solves, %ld misses, most %d "
        "iterations; %.3g off the reference\n",
        st.solves, st.misses, st.mostIterations, off);
    EXPECT_EQ(st.misses, 0);
    EXPECT_LT(off, 1e-3);
}

// What a scene does not declare costs nothing: without spring damping no kernel has its code.
TEST_F(GpuSpringDamping, OnlyADampedSceneCompilesTheSpringDamping) {
    Scene with = dampedScene(Method::ImplicitEuler), without = with;
    without.material->springDamping = 0;
    auto defines = [](const Scene& s) {
        std::string all;
        for (const auto& [name, value] : gpuDefines(s, {16, 16}, {})) all += name + " ";
        return all;
    };
    EXPECT_NE(defines(with).find("HAS_SPRING_DAMPING"), std::string::npos);
    EXPECT_EQ(defines(without).find("HAS_SPRING_DAMPING"), std::string::npos);
}

}  // namespace
}  // namespace cloth::test
