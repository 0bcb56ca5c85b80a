// Step control on the GPU backend (solver/step_control.h): it wraps the backend, whose own
// StepCheck (solver/step_check.h) keeps a step's start in a buffer, measures the step in a
// reduction pass and copies the start back where the step fails, so the GPU holds the stiff
// sheet through the drape's impact as the CPU does, and reads no state back to do it.
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "gpu/gpu_test_support.h"
#include "solver/diagnostics.h"
#include "solver/step_check.h"
#include "support/impact_runs.h"
#include "support/same_bits.h"

namespace cloth::test {
namespace {

class GpuStepControl : public GpuTest {};

// A 21 × 13 sheet of springs, 5 cm by 6 cm cells (work groups of 16 × 16 cut at both edges) with
// step control, hanging from two corners: `method` steps it.
Scene controlledSheet(const char* method) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "cloth": { "resolution": [21, 13], "size": [1.0, 0.72], "origin": [0, 1, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.05 },
      "springs": { "structural": 300, "shear": 100, "bend": 10 }, "damping": 0.01,
      "gravity": [0, -9.81, 0], "pins": [[0, 0], [-1, 0]],
      "integrator": { "method": "symplectic_euler", "dt": 0.001, "max_step_strain": 0.1 }
    })");
    j["integrator"]["method"] = method;
    return parseScene(j.dump(), "controlled sheet (test)");
}

SimState restState(const Scene& scene) {
    const Grid g = scene.grid();
    SimState s{g.nu, g.nv, {}, {}, 0};
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) s.positions.push_back(g.restPosition(i, j));
    s.velocities.assign(s.positions.size(), glm::dvec3(0));
    return s;
}

// The device's measure is the host's (largestStretchGrowth, in double) to float rounding: the
// largest growth wherever it lies, along u or v, in the last row or column of work groups, and
// +inf where a position is not finite, now or at the kept start.
TEST_F(GpuStepControl, DeviceCheckMeasuresWhatTheHostMeasures) {
    const Scene scene = controlledSheet("symplectic_euler");
    std::unique_ptr<Solver> gpu = makeGpuSolver(scene);
    StepCheck* check = gpu->stepCheck();
    ASSERT_NE(check, nullptr);
    const Grid g = scene.grid();
    const SimState before = restState(scene);
    gpu->write(before);
    check->keep();
    struct Move {
        int i, j;
        glm::dvec3 by;  // in rest lengths along u and v
    };
    // One after another: (3,4)-(4,4) along u stretched by 0.02; (19,11)-(19,12) along v by 0.05
    // (the last work groups'); (20,1)-(20,2) by 0.03; (19,5)-(20,5) squeezed by 0.3.
    const Move moves[] = {{4, 4, {0.02, 0, 0}},
                          {19, 12, {0, 0.05, 0}},
                          {20, 1, {0, -0.03, 0}},
                          {20, 5, {-0.3, 0, 0}}};
    const double expected[] = {0.02, 0.05, 0.05, 0.05};
    SimState after = before;
    for (std::size_t m = 0; m < std::size(moves); ++m) {
        glm::dvec3& x = after.positions[std::size_t(g.index(moves[m].i, moves[m].j))];
        x += moves[m].by.x * g.restLength(1, 0) * g.u + moves[m].by.y * g.restLength(0, 1) * g.v;
        gpu->write(after);  // the kept start stays kept
        const double host = largestStretchGrowth(scene, before, after).strain;
        const double device = check->stretchGrowth();
        EXPECT_NEAR(host, expected[m], 1e-9) << "move " << m;
        EXPECT_NEAR(device, host, 1e-5) << "move " << m;
    }
    const double inf = std::numeric_limits<double>::infinity();
    SimState torn = after;
    torn.positions[std::size_t(g.index(10, 6))].y = std::nan("");
    gpu->write(torn);
    EXPECT_EQ(check->stretchGrowth(), inf);
    EXPECT_EQ(largestStretchGrowth(scene, before, torn).strain, inf);
    SimState huge = after;  // a length of +inf (not NaN) at the start, a finite one now
    huge.positions[std::size_t(g.index(10, 6))].y = 1e300;
    gpu->write(huge);
    check->keep();
    gpu->write(after);
    EXPECT_EQ(check->stretchGrowth(), inf);
    EXPECT_EQ(largestStretchGrowth(scene, huge, after).strain, inf);
}

// restore() puts the kept state back bit for bit, with its time, for every integrator whose
// buffers it must also reset (vbd's history, implicit_euler's last solution); from there the
// steps are those of a solver written that state.
TEST_F(GpuStepControl, RestoreIsTheKeptStateAndStepsOnAsAfterAWrite) {
    for (const char* method : {"symplectic_euler", "vbd", "implicit_euler"}) {
        const Scene scene = controlledSheet(method);
        std::unique_ptr<Solver> gpu = makeGpuSolver(scene);
        ASSERT_FALSE(gpu->step(5).unstable) << method;
        const SimState kept = gpu->read();
        gpu->stepCheck()->keep();
        ASSERT_FALSE(gpu->step(3).unstable) << method;
        gpu->stepCheck()->restore();
        const SimState restored = gpu->read();
        EXPECT_EQ(restored.time, kept.time) << method;
        expectSameBits(restored, kept, std::string(method) + ", restored");
        ASSERT_FALSE(gpu->step(4).unstable) << method;
        std::unique_ptr<Solver> written = makeGpuSolver(scene);
        ASSERT_FALSE(written->step(5).unstable) << method;
        written->write(kept);
        ASSERT_FALSE(written->step(4).unstable) << method;
        expectSameBits(gpu->read(), written->read(), std::string(method) + ", stepped on");
    }
}

// Without the key, the GPU compiles no check and offers none.
TEST_F(GpuStepControl, ASceneWithoutTheKeyHasNoDeviceCheck) {
    Scene scene = controlledSheet("symplectic_euler");
    scene.integrator.maxStepStrain = 0;
    EXPECT_EQ(makeGpuSolver(scene)->stepCheck(), nullptr);
}

// The CPU's case (tests/solver/step_control_test.cpp) at 32², 20 frames: the long steps strain
// the sheet by 0.29 at the impact on either backend; with the control both stay below 0.15,
// split in the impact's frames only.
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
