// The shipped cape, table, windsock and real-time scenes on the GPU: the cape and the windsock
// have follow pins on moving capsules (docs/colliders.md §10), the table boxes with friction, the
// real-time sheet vbd's one step a frame. Shorter than the scenes' own durations
// (tests/scene/shipped_scenes_test.cpp runs those on the CPU): the cape for 2 s, by which it lies
// over the shoulders and hangs down the back, the windsock for 2 s, by which the wind has blown it
// out, the real-time sheet for 1.5 s, by which it lies on the sphere and its hem on the ground.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gpu_test_support.h"
#include "model/pin_follow.h"
#include "support/reference_bridge.h"
#include "support/shipped_outcomes.h"

namespace cloth {
namespace {

// Without self-collision, whose passes cost some 30 ms a step on llvmpipe: the cape's outcome is
// its colliders' (gpu_self_collision_test.cpp tests self-collision on the GPU).
Scene shipped(const char* name, double seconds) {
    return withoutSelfCollision(loadScene(std::string(CLOTH_SOURCE_DIR "/scenes/") + name + ".json",
                                          {"duration=" + std::to_string(seconds)}));
}

using test::worstClearance;

std::unique_ptr<Solver> runOnGpu(const Scene& scene) {
    auto solver = makeGpuSolver(scene, {});
    const StepResult r = solver->step(scene.defaultSteps());
    EXPECT_FALSE(r.unstable) << r.reason;
    return solver;
}

using GpuShippedScene = test::GpuTest;

// The cape: no vertex inside any body part (to float rounding), the follow-pinned top edge where
// the shoulders' pose puts it, the hem behind the torso in the figure's turning frame.
TEST_F(GpuShippedScene, CapeDrapesOverTheTurningFiguresBack) {
    const Scene scene = shipped("cape", 2.0);
    auto solver = runOnGpu(scene);
    const double t = solver->time();
    const SimState s = solver->read();
    const double clear = worstClearance(scene, *solver);
    double pinError = 0;
    for (const FollowPin& f : followPins(scene))
        pinError = std::max(
            pinError, glm::length(s.positions[size_t(f.vertex)] - followPinAt(f, t).position));
    const Grid g = scene.grid();
    const glm::dvec3 local = test::capeHemInFiguresFrame(scene, s, t);
    std::printf(
        "gpu cape (%.1f s): worst clearance %.3g m, pins off by %.3g m, hem at (%.3f, %.3f, %.3f) "
        "in the figure's frame\n",
        t, clear, pinError, local.x, local.y, local.z);
    EXPECT_EQ(followPins(scene).size(), size_t(g.nu));
    EXPECT_GT(clear, -1e-6);
    EXPECT_LT(pinError, 2e-6);
    EXPECT_LT(local.z, -0.14);
    EXPECT_LT(local.y, 1.0);
}

// The table (3 s, its whole duration): the tablecloth's centre rests on the top at h, its edges
// hang below it, nothing inside a box; with a frictionless top the same cloth slides off.
TEST_F(GpuShippedScene, TableclothStaysOnTheTableByFriction) {
    const Scene scene = shipped("table", 3.0);
    auto solver = runOnGpu(scene);
    const auto [top, topY, centre, lowest, clear] = test::tableOutcome(scene, *solver);
    Scene slippery = scene;
    slippery.colliders[0].friction = 0;
    const glm::dvec3 slid = test::clothCentre(slippery, runOnGpu(slippery)->read());
    std::printf(
        "gpu table (3 s): centre at (%.4f, %.4f, %.4f), top at y = %.3f, lowest vertex %.3f m, "
        "worst clearance %.3g m; frictionless: centre at (%.3f, %.3f, %.3f)\n",
        centre.x, centre.y, centre.z, topY, lowest, clear, slid.x, slid.y, slid.z);
    EXPECT_LT(std::abs(centre.x - top.center.x), top.halfExtents.x - 0.2);
    EXPECT_LT(std::abs(centre.z - top.center.z), top.halfExtents.z - 0.2);
    EXPECT_NEAR(centre.y, topY + scene.colliders[0].thickness, 2e-3);
    EXPECT_LT(lowest, topY - 0.1);
    EXPECT_GT(clear, -1e-6);
    EXPECT_LT(slid.y, topY - 0.1);
}

// The windsock: blown along the wind against the same run without it (the shift along the wind
// averaged over the frames from 1 to 2 s, as the CPU test does), nothing inside the pole or the
// ground, the pins on the swaying pole.
TEST_F(GpuShippedScene, WindsockIsBlownAlongTheWind) {
    const Scene scene = shipped("windsock", 2.0);
    Scene calm = scene;
    calm.wind.reset();
    auto windy = makeGpuSolver(scene, {}), still = makeGpuSolver(calm, {});
    std::string bad;
    const test::WindShift blown = test::shiftAlongWindOver(scene, *windy, 1.0, 2.0, bad);
    EXPECT_EQ(bad, "");
    const test::WindShift hangs = test::shiftAlongWindOver(scene, *still, 1.0, 2.0, bad);
    EXPECT_EQ(bad, "");
    const double clear = worstClearance(scene, *windy);
    double pinError = 0;
    const SimState s = windy->read();
    for (const FollowPin& f : followPins(scene))
        pinError = std::max(pinError, glm::length(s.positions[size_t(f.vertex)] -
                                                  followPinAt(f, windy->time()).position));
    std::printf(
        "gpu windsock: shift along the wind from 1 to 2 s: mean %.3f m, least %.3f m (without "
        "wind: mean %.3f m), worst clearance %.3g m, pins off by %.3g m\n",
        blown.mean, blown.least, hangs.mean, clear, pinError);
    EXPECT_GT(blown.mean, hangs.mean + 0.3);
    EXPECT_GT(blown.least, hangs.mean + 0.15);
    EXPECT_GT(clear, -1e-6);
    EXPECT_LT(pinError, 2e-6);
}

// The real-time sheet (1.5 s, 90 frames of one vbd step; about 10 s on llvmpipe): it holds in
// every frame, its most strained spring far under max_strain (0.40 on llvmpipe, 0.43 on the CPU
// in float), and lies on the sphere's top with its hem on the ground, nothing inside either.
TEST_F(GpuShippedScene, RealtimeSheetHoldsInEveryFrameAndDrapesOverTheSphere) {
    const Scene scene = shipped("realtime", 1.5);
    auto solver = makeGpuSolver(scene, {});
    std::string bad;
    const test::RealtimeOutcome o = test::realtimeOutcome(scene, *solver, scene.duration, bad);
    std::printf(
        "gpu realtime (%.2f s): worst strain of any frame %.3f, highest vertex %.2e m above the "
        "sphere's top, lowest at %.4f m, worst clearance %.3g m\n",
        solver->time(), o.worstStrain, o.aboveTop, o.lowest, o.clear);
    EXPECT_EQ(bad, "");
    EXPECT_LT(o.worstStrain, 0.75 * scene.maxStrain);
    EXPECT_LT(std::abs(o.aboveTop), 2e-3);
    EXPECT_LT(o.lowest, scene.colliders[0].thickness + 1e-3);
    EXPECT_GT(o.clear, -1e-6);
}

}  // namespace
}  // namespace cloth
