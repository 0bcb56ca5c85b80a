// Self-collision on the GPU backend (shaders/compute/self_*.comp, docs/physics.md
// "Self-collision"): the same contacts as the CPU backend in float at the first contact steps,
// and the shipped pile (coarse, as the CPU test runs it) never crossing itself, checked by the
// independent checker of tests/reference/self_intersection.h; without self-collision it does.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "gpu_test_support.h"
#include "support/collapsed_cloth.h"
#include "support/self_collision_check.h"

namespace cloth::test {
namespace {

using GpuSelfCollision = GpuTest;

Scene coarsePile() {
    return loadScene(std::string(CLOTH_SOURCE_DIR) + "/scenes/pile.json",
                     {"cloth.resolution=[12,24]", "integrator.dt=5e-4"});
}

// Parity: step by step from the first contact on, both backends (the CPU in float) find the
// same vertices in contact and keep the same state to float rounding, until the pile's folds
// amplify the rounding (the contact sets are compared while the states agree within 1e-4 m).
// A contact that starts exactly at the threshold (0.99 h) may start a step apart on the two:
// all but two of the compared steps must have equal sets, and all together the same vertices.
TEST_F(GpuSelfCollision, TheFirstContactsAreTheCpusContacts) {
    const Scene scene = coarsePile();
    auto gpu = makeGpuSolver(scene, {});
    auto cpu = makeCpuSolver(scene, CpuOptions{Precision::Float, 1});
    long step = 0, compared = 0, equal = 0;
    std::set<std::int64_t> gpuAll, cpuAll;
    while (step < 500 && compared < 40) {
        ASSERT_FALSE(gpu->step(1).unstable);
        ASSERT_FALSE(cpu->step(1).unstable);
        ++step;
        const std::vector<std::int64_t> g = gpu->selfContactVertices(),
                                        c = cpu->selfContactVertices();
        if (g.empty() && c.empty()) continue;
        const SimState a = gpu->read(), b = cpu->read();
        double worst = 0;
        for (std::size_t k = 0; k < a.positions.size(); ++k)
            worst = std::max(worst, glm::length(a.positions[k] - b.positions[k]));
        if (worst > 1e-4) break;
        if (compared == 0) std::printf("first contact at step %ld: %zu vertices\n", step, c.size());
        if (g != c)
            std::printf("step %ld: gpu %zu, cpu %zu vertices in contact (states %.2g m apart)\n",
                        step, g.size(), c.size(), worst);
        equal += g == c;
        gpuAll.insert(g.begin(), g.end());
        cpuAll.insert(c.begin(), c.end());
        ++compared;
    }
    std::printf("contact sets compared at %ld steps, equal at %ld; %zu vertices in all\n", compared,
                equal, cpuAll.size());
    EXPECT_GE(compared, 10) << "too few contact steps compared: the test would show nothing";
    EXPECT_GE(equal, compared - 2);
    EXPECT_EQ(gpuAll, cpuAll);
    EXPECT_EQ(gpu->selfCollisionStats().stepsOverBound, 0);
}

// Law: no crossing and no pair closer than h/2 at the end of any checked step; without
// self-collision the same run crosses itself.
TEST_F(GpuSelfCollision, ThePileNeverCrossesItselfAndCrossesWithoutIt) {
    const Scene scene = coarsePile();
    const double h = scene.selfCollision->thickness;
    auto on = makeGpuSolver(scene, {});
    const SelfCheck o = runAndCheck(*on, 900, 50, h);
    std::printf(
        "gpu pile: %ld crossings at worst, closest %.3g m (h = %g m), %.2f substeps a "
        "step, %.1f contacts an iteration\n",
        o.worstCrossings, o.closest, h, double(o.stats.substeps) / double(o.stats.steps),
        double(o.stats.contacts) / double(std::max(1L, o.stats.iterations)));
    EXPECT_EQ(o.worstCrossings, 0);
    EXPECT_GE(o.closest, 0.5 * h);
    EXPECT_GT(o.stats.contacts, 0);
    auto off = makeGpuSolver(withoutSelfCollision(scene), {});
    const SelfCheck x = runAndCheck(*off, 900, 50, h);
    std::printf("gpu pile without self-collision: %ld frames crossed, %ld crossings at worst\n",
                x.crossedFrames, x.worstCrossings);
    EXPECT_GT(x.worstCrossings, 0);
}

// As on the CPU (SelfCollision.ACollapsedClothStopsAtOnceNamingACrowdedVertex): a cloth
// collapsed onto itself stops at its first step with the same reason, frozen where the
// integrator left it, and stays stopped; a fresh state runs on.
TEST_F(GpuSelfCollision, ACollapsedClothStopsAtOnceNamingACrowdedVertex) {
    const Scene scene = coarsePile();
    auto plain = makeGpuSolver(withoutSelfCollision(scene), {});
    const SimState start = plain->read();
    const SimState collapsed = collapsedCloth(start, {0, 0.5, 0}, 0.01);
    plain->write(collapsed);
    ASSERT_FALSE(plain->step(1).unstable);
    auto gpu = makeGpuSolver(scene, {});
    gpu->write(collapsed);
    const StepResult r = gpu->step(5);
    std::printf("gpu: %s\n", r.reason.c_str());
    ASSERT_TRUE(r.unstable);
    EXPECT_EQ(r.firstBadStep, 1);
    EXPECT_EQ(r.stepsTaken, 1);
    EXPECT_EQ(r.reason.rfind("self-collision: vertex (", 0), 0u) << r.reason;
    EXPECT_NE(r.reason.find("collapsed onto itself"), std::string::npos) << r.reason;
    EXPECT_EQ(gpu->selfCollisionStats().iterations, 0);
    const SimState s = gpu->read(), p = plain->read();
    for (std::size_t k = 0; k < s.positions.size(); ++k)
        ASSERT_EQ(s.positions[k], p.positions[k]) << "vertex " << k;
    EXPECT_TRUE(gpu->step(1).unstable);  // still frozen
    gpu->write(start);
    EXPECT_FALSE(gpu->step(20).unstable);
    EXPECT_GT(gpu->selfCollisionStats().iterations, 0);
}

}  // namespace
}  // namespace cloth::test
