// Throughput of the GPU backend on bench/hanging_per_vertex.json (the speed benchmark's scene,
// the seed's per-vertex hanging cloth) at 64², 256² and 1024² vertices, as quoted in docs/gpu.md.
// Disabled by default (seconds on llvmpipe); run with
//   cloth_tests --gtest_also_run_disabled_tests --gtest_filter='GpuBenchmark.*'
#include <cstdio>

#include "gpu/gpu_solver.h"
#include "gpu/gpu_test_support.h"

namespace cloth::test {
namespace {

class GpuBenchmark : public GpuTest {};

TEST_F(GpuBenchmark, DISABLED_HangingVertexStepsPerSecond) {
    std::printf("%s", describeGpu().c_str());
    for (const auto& [n, steps] : {std::pair{64, 2000L}, {256, 200L}, {1024, 20L}}) {
        Scene scene = loadScene(CLOTH_SOURCE_DIR "/bench/hanging_per_vertex.json");
        scene.cloth.nu = scene.cloth.nv = n;
        auto solver = makeGpuSolver(scene);
        auto* gpu = dynamic_cast<GpuSolver*>(solver.get());
        ASSERT_NE(gpu, nullptr);
        ASSERT_FALSE(solver->step(steps / 10).unstable);  // warm-up: caches, first-use costs
        ASSERT_FALSE(solver->step(steps).unstable);
        const double perStep = gpu->lastSecondsPerStep();
        std::printf("hanging %4dx%-4d %6ld steps: %8.1f us/step, %.3g vertex-steps/s (%s, %s)\n", n,
                    n, steps, perStep * 1e6, double(n) * n / perStep, gpu->timingSource(),
                    solver->name().c_str());
    }
}

}  // namespace
}  // namespace cloth::test
