// The GPU backend with a material's bending energy (HAS_BENDING: shaders/compute/bending.glsl,
// mirroring model/bending.h): against the reference and the CPU float backend to the material
// sheet's tolerances (gpu_material_test.cpp), in the force pass and in implicit Euler's Hessian;
// a scene without bending compiles no bending code.
#include <cmath>
#include <cstdio>

#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "support/material_scene.h"

namespace cloth::test {
namespace {

constexpr double kReferenceTolerance = 1e-4;  // max |p − p_ref| / extent (gpu_parity_test)
constexpr double kCpuFloatTolerance = 1e-5;   // max |p_gpu − p_cpu| / extent (integrator parity)

// The sheet of tests/cpu/bending_solver_test.cpp with B = 3e-3 N·m, which moves it by far more
// than these tolerances within the run (1e-3 N·m moved it by 8e-4 of its extent once its border
// springs had their half stiffness: too close to 10× the tolerance).
Scene bendingScene(Method method) {
    Scene s = materialScene(method, 1e-4);
    s.material->bend = 3e-3;
    s.integrator.tolerance = 1e-6;
    s.integrator.maxIterations = 500;
    return s;
}

class GpuBending : public GpuTest, public ::testing::WithParamInterface<Method> {};

TEST_P(GpuBending, MatchesTheReferenceAndTheCpuFloatBackend) {
    const Method method = GetParam();
    const Scene scene = bendingScene(method);
    const long steps = 1000;
    const double extent = scene.grid().extent();
    const SimState gpu = runGpu(scene, steps);
    const double toReference = maxDeviationOverExtent(gpu, runReference(scene, steps), extent);
    const double toCpu = maxDifferenceOverExtent(gpu, runCpuFloat(scene, steps), extent);
    Scene flat = scene;
    flat.material->bend = 0;
    const double bendingEffect = maxDeviationOverExtent(gpu, runReference(flat, steps), extent);
    std::printf("%-16s gpu vs reference %.3g, vs cpu float %.3g, bending moved it %.3g\n",
                methodName(method), toReference, toCpu, bendingEffect);
    EXPECT_LT(toReference, kReferenceTolerance);
    EXPECT_LT(toCpu, kCpuFloatTolerance);
    EXPECT_GT(bendingEffect, 10 * kReferenceTolerance);
}

INSTANTIATE_TEST_SUITE_P(Methods, GpuBending,
                         ::testing::Values(Method::SymplecticEuler, Method::Verlet, Method::Rk4,
                                           Method::ImplicitEuler),
                         [](const ::testing::TestParamInfo<Method>& p) {
                             return std::string(methodName(p.param));
                         });

// What a scene does not declare costs nothing: without bending the kernels have no bending code.
TEST_F(GpuBending, OnlyABendingSceneCompilesTheBendingStencil) {
    Scene with = bendingScene(Method::ImplicitEuler), without = with;
    without.material->bend = 0;
    auto defines = [](const Scene& s) {
        std::string all;
        for (const auto& [name, value] : gpuDefines(s, {16, 16}, {})) all += name + " ";
        return all;
    };
    EXPECT_NE(defines(with).find("HAS_BENDING"), std::string::npos);
    EXPECT_EQ(defines(without).find("HAS_BENDING"), std::string::npos);
}

}  // namespace
}  // namespace cloth::test
