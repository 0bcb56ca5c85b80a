// Step control on the GPU backend (solver/step_control.h): it wraps the backend, reads its
// buffers back after every step and writes a thrown-away step's start into them, so the GPU
// holds the stiff sheet through the drape's impact as the CPU does.
#include <cstdio>

#include "gpu/gpu_test_support.h"
#include "support/impact_runs.h"

namespace cloth::test {
namespace {

class GpuStepControl : public GpuTest {};

// The CPU's case (tests/solver/step_control_test.cpp), 20 frames: the GPU's long steps strain the
// sheet by 0.2 at the impact (the CPU's by 0.73: the contact's outcome turns on rounding); with
// the control both stay below 0.15, split in the impact's frames only.
TEST_F(GpuStepControl, HoldsTheStiffSheetThroughTheImpactAsTheCpuDoes) {
    BackendChoice gpu;
    gpu.backend = Backend::Gpu;
    const ImpactRun onGpu = runImpact(stiffDrape(32, 0.1), gpu, 20);
    const ImpactRun onCpu = runImpact(stiffDrape(32, 0.1), {Backend::Cpu, Precision::Float, 1}, 20);
    std::printf(
        "32² drape, stretch 1e6, max_step_strain 0.1, 20 frames: largest strain %.3f on "
        "the GPU (%ld steps split in frames %ld–%ld), %.3f on the CPU (%ld in %ld–%ld)\n",
        onGpu.largest, onGpu.control.split, onGpu.firstSplitFrame, onGpu.lastSplitFrame,
        onCpu.largest, onCpu.control.split, onCpu.firstSplitFrame, onCpu.lastSplitFrame);
    EXPECT_LT(onGpu.largest, 0.15);
    EXPECT_LT(onCpu.largest, 0.15);
    EXPECT_GT(onGpu.control.split, 0);
    EXPECT_GE(onGpu.firstSplitFrame, 13);
}

}  // namespace
}  // namespace cloth::test
