// The GPU backend (float) settles a material under its own weight as the CPU does (double):
// tests/support/material_statics.h's cantilever, Peirce's cantilever, hanging strip and hanging
// sheet, against the same closed forms as tests/cpu/material_statics_test.cpp, and against the
// CPU's equilibrium. Float: a conjugate gradient to 10⁻⁶ and positions to ~10⁻⁷ m; the sags are
// 0.2–30 mm, so 1% of the CPU's value is a hundred times the float floor.
#include <cmath>
#include <cstdio>

#include "cpu/cpu_solver.h"
#include "gpu/gpu_test_support.h"
#include "support/material_statics.h"

namespace cloth::test {
namespace {

Scene forFloat(Scene s) {
    s.integrator.tolerance = 1e-6;
    s.integrator.maxIterations = 20000;
    return s;
}

struct Both {
    SimState gpu, cpu;
};

Both settleBoth(const Scene& scene) {
    std::unique_ptr<Solver> gpu = makeGpuSolver(forFloat(scene));
    const Settled g = settle(*gpu, 1e-7, 40);
    std::printf("%s: gpu settled to %.2g m in %d steps\n", scene.name.c_str(), g.lastMove, g.steps);
    EXPECT_LE(g.lastMove, 1e-6) << scene.name << ": the GPU did not settle";
    CpuSolver<double> cpu(scene, 2, CpuIsa::Generic);
    return {g.state, settle(cpu, 1e-11, 40).state};
}

class GpuMaterialStatics : public GpuTest {};

TEST_F(GpuMaterialStatics, ACantileverSagsByTheBeamValue) {
    for (int cells : {32, 64}) {
        const Scene scene = cantileverScene(cells, 0.0125, 1.82e-5);
        const Both b = settleBoth(scene);
        const double gpu = cantileverTipSag(scene, b.gpu), cpu = cantileverTipSag(scene, b.cpu);
        const double beam = cantileverBeamSag(scene);
        std::printf("cantilever %d cells: gpu %.4g mm (%+.2f%% off the beam), cpu %.4g mm\n", cells,
                    1e3 * gpu, 100 * (gpu / beam - 1), 1e3 * cpu);
        EXPECT_LT(std::abs(gpu / beam - 1), 0.10) << cells << " cells";
        EXPECT_LT(std::abs(gpu / cpu - 1), 0.01) << cells << " cells";
    }
}

TEST_F(GpuMaterialStatics, ACantileverBentFarFollowsTheElastica) {
    const double bend = 1.82e-5, c = std::cbrt(bend / (0.150 * 9.81));
    const Scene scene = cantileverScene(32, 2 * c, bend);
    const Both b = settleBoth(scene);
    const double gpu = cantileverTipSag(scene, b.gpu), cpu = cantileverTipSag(scene, b.cpu);
    const double elastica = cantileverElasticaSag(scene);
    std::printf("Peirce cantilever: gpu %.4g mm (%+.2f%% off the elastica), cpu %.4g mm\n",
                1e3 * gpu, 100 * (gpu / elastica - 1), 1e3 * cpu);
    EXPECT_LT(std::abs(gpu / elastica - 1), 0.05);
    EXPECT_LT(std::abs(gpu / cpu - 1), 0.01);
}

TEST_F(GpuMaterialStatics, AStripStretchesUnderItsWeightByTheContinuumValue) {
    for (bool alongV : {false, true})
        for (int cells : {16, 64}) {
            const Scene scene = hangingStripScene(cells, alongV);
            const Both b = settleBoth(scene);
            const double gpu = hangingStripStretch(scene, b.gpu);
            const double cpu = hangingStripStretch(scene, b.cpu);
            const double continuum = hangingStripElongation(scene);
            std::printf("%s, %d cells: gpu %.4g mm (%+.2f%%), cpu %.4g mm\n", scene.name.c_str(),
                        cells, 1e3 * gpu, 100 * (gpu / continuum - 1), 1e3 * cpu);
            EXPECT_LT(std::abs(gpu / continuum - 1), 0.05) << scene.name << ", " << cells;
            EXPECT_LT(std::abs(gpu / cpu - 1), 0.01) << scene.name << ", " << cells;
        }
}

TEST_F(GpuMaterialStatics, AHangingSheetSagsAsOnTheCpu) {
    for (int cells : {16, 32}) {
        const Scene scene = hangingSheetScene(cells);
        const Both b = settleBoth(scene);
        const double gpu = hangingSheetSag(scene, b.gpu), cpu = hangingSheetSag(scene, b.cpu);
        std::printf("hanging sheet %d cells: gpu %.5g mm, cpu %.5g mm\n", cells, 1e3 * gpu,
                    1e3 * cpu);
        EXPECT_LT(std::abs(gpu / cpu - 1), 0.01) << cells << " cells";
    }
}

}  // namespace
}  // namespace cloth::test
