// The GPU backend on a cloth of a material (tests/support/material_scene.h): each vertex's own
// inverse mass in position.w, each spring slot's own K in Params, the drag rate c. Against the
// reference and the CPU float backend to gpu_parity_test.cpp's and gpu_integrator_parity_test.cpp's
// tolerances; the masses it models, measured, also after the viewer's changes (new masses, a pin
// released); a free fall against the drag law.
#include <cmath>
#include <cstdio>

#include "gpu/gpu_test_support.h"
#include "support/material_scene.h"

namespace cloth::test {
namespace {

constexpr long kSteps = 1000;
constexpr double kReferenceTolerance = 1e-4;  // max |p − p_ref| / extent (gpu_parity_test)
constexpr double kCpuFloatTolerance = 1e-5;   // max |p_gpu − p_cpu| / extent (integrator parity)

// As tests/cpu/material_test.cpp: explicit Euler, which has no stable Δt here, runs 200 steps of
// 1e-5 s; the CGs stop well below the differences measured.
Scene sceneFor(Method method) {
    Scene s = materialScene(method, method == Method::ExplicitEuler ? 1e-5 : 1e-4);
    s.integrator.tolerance = 1e-6;
    s.integrator.maxIterations = 500;
    return s;
}

class GpuMaterial : public GpuTest, public ::testing::WithParamInterface<Method> {};

TEST_P(GpuMaterial, MatchesTheReferenceAndTheCpuFloatBackend) {
    const Method method = GetParam();
    if (method == Method::Vbd) {
        // Ten sweeps are not vbd's reference (backward Euler, to which it converges:
        // tests/cpu/vbd_test.cpp), and its velocity, a difference of positions over h, carries
        // float's rounding / h at 1e-4 s: it is checked against the CPU at its own 1/60 s, with
        // and without the bending energy, over 5 steps. Ten sweeps on this stiff sheet at 1/60 s
        // amplify a rounding difference about tenfold every 5 steps (seen: 4e-7 after 1 step,
        // 2e-5 after 20, 0.13 of the extent after 120): the trajectory, not the step, diverges.
        for (double bend : {0.0, 1e-3}) {
            Scene scene = sceneFor(method);
            scene.integrator.dt = 1.0 / 60;
            scene.material->bend = bend;
            const double toCpu = maxDifferenceOverExtent(runGpu(scene, 5), runCpuFloat(scene, 5),
                                                         scene.grid().extent());
            std::printf("vbd, dt 1/60 s, bend %g N m, 5 steps: gpu vs cpu float %.3g (/ extent)\n",
                        bend, toCpu);
            EXPECT_LT(toCpu, kCpuFloatTolerance) << "bend " << bend;
        }
        return;
    }
    const Scene scene = sceneFor(method);
    const long steps = method == Method::ExplicitEuler ? 200 : kSteps;
    const double extent = scene.grid().extent();
    const SimState gpu = runGpu(scene, steps);
    const double toReference = maxDeviationOverExtent(gpu, runReference(scene, steps), extent);
    const double toCpu = maxDifferenceOverExtent(gpu, runCpuFloat(scene, steps), extent);
    std::printf("%-16s gpu vs reference %.3g, vs cpu float %.3g (/ extent)\n", methodName(method),
                toReference, toCpu);
    EXPECT_LT(toReference, kReferenceTolerance);
    EXPECT_LT(toCpu, kCpuFloatTolerance);
}

// The wind as a pressure (tests/cpu/material_test.cpp WindIsAPressureAtEveryResolution): the
// shader's windStrengthAt gives each vertex its share of the area.
TEST_F(GpuMaterial, WindIsAPressureAtEveryResolution) {
    for (int cells : {8, 32, 128}) {
        const Scene scene = windSheetScene(cells);
        const WindImpulse w = windImpulse(scene, runGpu(scene, 1));
        std::printf("%3d cells: impulse / (dt P A cos) = %.7f, speeds spread %.2g\n", cells,
                    w.ofPressure, w.spread);
        EXPECT_NEAR(w.ofPressure, 1, 1e-4) << cells << " cells";
        EXPECT_LT(w.spread, 1e-4) << cells << " cells";
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, GpuMaterial, ::testing::ValuesIn(kMethods),
                         [](const ::testing::TestParamInfo<Method>& p) {
                             return std::string(methodName(p.param));
                         });

// The masses in position.w: lumped; after setParameters with twice the density, twice each
// (every ratio kept); a corner pinned and released again gets its own mass back. Each change is
// made to the state at rest and read off the next step (a write() would set position.w afresh).
// Float: the rest lengths' rounding and the wind's, 1e-5.
TEST_F(GpuMaterial, ModelsTheLumpedMassesAndKeepsThemThroughTheControls) {
    Scene probe = massProbeScene(materialScene(Method::SymplecticEuler));
    std::unique_ptr<Solver> gpu = makeGpuSolver(probe);
    const SimState rest = gpu->read();
    const double density = probe.material->density;
    expectLumpedMasses(probe, density, stepMasses(*gpu, probe), 1e-5, "as built");
    gpu->write(rest);
    probe.material->density = 2 * density;
    gpu->setParameters(probe);
    expectLumpedMasses(probe, 2 * density, stepMasses(*gpu, probe), 1e-5, "density doubled");
    gpu->write(rest);
    gpu->setPinned(0, 0, true);
    gpu->setPinned(0, 0, false);
    expectLumpedMasses(probe, 2 * density, stepMasses(*gpu, probe), 1e-5,
                       "corner pinned and released");
}

// As on the CPU (tests/cpu/material_test.cpp): the unpinned sheet falls as one, its centre of
// mass at v(t) = g/c (1 − e^{−ct}) to the first-order schemes' error and float's rounding of v
// over 5000 steps; float's rounding of the positions ripples it at the 1e-7 m scale.
TEST_F(GpuMaterial, FreeFallFollowsTheDragLaw) {
    const double c = 4, t = 0.5, h = 1e-4, g = 9.81;
    const double law = g / c * (1 - std::exp(-c * t));
    const double firstOrder = 0.5 * g * c * h * t * std::exp(-c * t);
    for (Method method : kMethods) {
        if (method == Method::ExplicitEuler) continue;  // no stable Δt on this cloth
        // vbd's velocity is a difference of positions over h: at 1e-4 s in float it carries
        // their rounding / h (tests/cpu/material_test.cpp; its law: tests/cpu/vbd_test.cpp).
        if (method == Method::Vbd) continue;
        Scene scene = fallingMaterialScene(method, c, h);
        scene.integrator.tolerance = 1e-6;
        const FallingSheet f = fallingSheet(scene, runGpu(scene, std::lround(t / h)));
        std::printf(
            "%-16s gpu: v = %.9g m/s, drag law %.9g, spread %.3g m/s, |v_xz| %.3g m/s, strain "
            "%.3g\n",
            methodName(method), -f.velocity.y, law, f.spread, f.sideways, f.strain);
        EXPECT_NEAR(-f.velocity.y, law, 2 * firstOrder + 1e-4 * law) << methodName(method);
        EXPECT_LT(f.sideways, 1e-5 * law) << methodName(method);
        EXPECT_LT(f.strain, 1e-4) << methodName(method);
    }
}

}  // namespace
}  // namespace cloth::test
