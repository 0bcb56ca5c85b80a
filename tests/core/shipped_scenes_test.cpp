// Every shipped scene sits inside its integrator's predicted stability bound (DESIGN.md §2) and
// stays stable, on the CPU in double and in float, for its whole duration.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/diagnostics.h"
#include "core/scene_loader.h"
#include "core/stability.h"

namespace cloth {
namespace {

std::vector<std::string> shippedScenes() {
    std::vector<std::string> paths;
    for (const auto& e : std::filesystem::directory_iterator(CLOTH_SOURCE_DIR "/scenes"))
        if (e.path().extension() == ".json") paths.push_back(e.path().string());
    std::sort(paths.begin(), paths.end());
    return paths;
}

class ShippedScene : public testing::TestWithParam<std::string> {};

TEST_P(ShippedScene, TimeStepIsInsideThePredictedBound) {
    const Scene scene = loadScene(GetParam());
    EXPECT_LT(scene.integrator.dt, stableDt(scene)) << stabilityAdvice(scene);
}

TEST_P(ShippedScene, StaysStableForItsWholeDuration) {
    const Scene scene = loadScene(GetParam());
    for (Precision p : {Precision::Double, Precision::Float}) {
        auto solver = makeCpuSolver(scene, {p, 2});
        const StepResult r = solver->step(scene.defaultSteps());
        EXPECT_FALSE(r.unstable) << precisionName(p) << ": " << r.reason;
        EXPECT_EQ(r.stepsTaken, scene.defaultSteps());
        const SimState s = solver->read();
        EXPECT_TRUE(allFinite(s));
        // Settled or settling: nothing moves anywhere near max_speed.
        for (const glm::dvec3& v : s.velocities) ASSERT_LT(glm::length(v), 10.0);
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, testing::ValuesIn(shippedScenes()),
                         [](const testing::TestParamInfo<std::string>& param) {
                             return std::filesystem::path(param.param).stem().string();
                         });

TEST(ShippedScenes, AllFiveExist) {
    for (const char* name : {"spring", "chain", "hanging", "drape", "flag"})
        EXPECT_TRUE(
            std::filesystem::exists(std::string(CLOTH_SOURCE_DIR "/scenes/") + name + ".json"))
            << name;
}

}  // namespace
}  // namespace cloth
