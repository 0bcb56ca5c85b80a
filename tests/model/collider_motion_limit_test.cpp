// The loader's "clamp motion" rule (docs/colliders.md §7, model/collider_limits.h): a moving
// collider whose surface may move further in one step than maxColliderStepTravel is refused,
// naming `colliders[n].motion`; at 99 % of the limit it passes, at 101 % it is refused, whatever
// the shape and the motion; the Δt and the speed the message offers pass; every shipped scene
// passes, with its margin printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include "model/collider_limits.h"
#include "model/collider_mesh.h"
#include "model/collider_speed.h"
#include "model/errors.h"
#include "scene/scene_loader.h"
#include "support/process.h"

namespace cloth {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

struct LimitCase {
    const char* name;
    Json collider;  // with a motion
    double travel;  // what maxColliderStepTravel should be [m]
    double speed;   // what maxMotionSpeed should be [m/s]
};

// Each shape with a motion whose speed is exact in maxMotionSpeed (collider_speed.h).
std::vector<LimitCase> limitCases() {
    const double pi = std::numbers::pi;
    return {
        {"sphere_linear", Json::parse(R"({"type": "sphere", "center": [0, 0.5, 0], "radius": 0.1,
            "thickness": 0.01, "motion": {"type": "linear", "velocity": [3, 4, 0]}})"),
         0.11, 5},
        {"box_oscillation",
         Json::parse(R"({"type": "box", "center": [0, 0.5, 0], "half_extents": [0.3, 0.02, 0.2],
            "thickness": 0.005, "motion": {"type": "oscillation", "axis": [0, 1, 0],
            "amplitude": 0.2, "frequency": 2}})"),
         0.025, 2 * pi * 2 * 0.2},
        {"capsule_rotation",  // the capsule's axis crosses the rotation axis at right angles
         Json::parse(R"({"type": "capsule", "a": [-0.5, 0.5, 0], "b": [0.5, 0.5, 0],
            "radius": 0.04, "motion": {"type": "rotation", "axis": [0, 1, 0],
            "degrees_per_second": 180}})"),
         0.04, pi * (0.5 + 0.04)},
        {"mesh_linear",  // slab.obj: 0.5 × 0.1 × 0.4, so half its smallest extent is 0.05
         Json::parse(R"({"type": "mesh", "file": "slab.obj", "cell": 0.02, "band": 0.06,
            "thickness": 0.01, "translation": [0, 0.5, 0],
            "motion": {"type": "linear", "velocity": [0, 0, 2]}})"),
         0.06, 2},
    };
}

class ColliderMotionLimit : public testing::TestWithParam<LimitCase> {
protected:
    static void SetUpTestSuite() {
        dir_ = test::freshTempDir("ColliderMotionLimit", "mesh");
        writeMeshesObj((dir_ / "slab.obj").string(),
                       {{"slab", boxMesh({{0, 0, 0}, {0.25, 0.05, 0.2}, glm::dmat3(1)})}});
    }
    // A small cloth above a ground plane and the case's collider (colliders[1]), stepping dt.
    static Scene scene(const Json& collider, double dt) {
        Json j = Json::parse(R"({
          "cloth": { "resolution": [4, 3], "size": [0.3, 0.2], "origin": [-0.15, 1, -0.1] },
          "springs": { "structural": 10 }, "damping": 0.5,
          "colliders": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0],
                           "motion": { "type": "linear", "velocity": [0, 1000, 0] } } ]
        })");
        j["integrator"] = {{"method", "explicit_euler"}, {"dt", dt}};
        j["colliders"].push_back(collider);
        return parseScene(j.dump(), (dir_ / "scene.json").string());
    }
    static fs::path dir_;
};
fs::path ColliderMotionLimit::dir_;

// Law: the rule is speed·Δt ≤ maxColliderStepTravel, sharp: 99 % of the limiting Δt passes,
// 101 % is refused naming colliders[1].motion (the plane before it moves at 1 km/s and passes:
// nothing tunnels through a half-space). The refusal gives the speed, Δt and the limit, and the
// Δt and the speed it offers pass.
TEST_P(ColliderMotionLimit, NinetyNinePercentPassesAndOneHundredAndOneIsRefused) {
    const LimitCase& c = GetParam();
    const Scene probe = scene(c.collider, 1e-6);
    ASSERT_NEAR(maxColliderStepTravel(probe.colliders[1]), c.travel, 1e-12);
    ASSERT_NEAR(maxMotionSpeed(probe.colliders[1]), c.speed, 1e-12);
    const double dtLimit = c.travel / c.speed;
    const Scene ok = scene(c.collider, 0.99 * dtLimit);
    EXPECT_NEAR(motionStepMargin(ok.colliders[1], ok.integrator.dt), 1 / 0.99, 1e-9);
    EXPECT_EQ(motionStepMargin(ok.colliders[0], ok.integrator.dt),
              std::numeric_limits<double>::infinity());
    try {
        scene(c.collider, 1.01 * dtLimit);
        ADD_FAILURE() << c.name << ": 101 % of the limit was accepted";
    } catch (const InputError& e) {
        std::printf("%s: %s\n", c.name, e.what());
        EXPECT_EQ(e.key(), "colliders[1].motion");
        EXPECT_NE(e.file().find("scene.json"), std::string::npos);
        const std::string why = e.reason();
        for (const char* part : {"integrator.dt", "tunnelling", "m/s", "docs/colliders.md §7"})
            EXPECT_NE(why.find(part), std::string::npos) << part << " missing: " << why;
        // "... it passes with integrator.dt ≤ X s or a motion of at most Y m/s"
        std::smatch m;
        ASSERT_TRUE(std::regex_search(
            why, m, std::regex(R"(dt ≤ ([0-9.e+-]+) s or a motion of at most ([0-9.e+-]+) m/s)")))
            << why;
        const double dtOffered = std::stod(m[1]), speedOffered = std::stod(m[2]);
        EXPECT_NEAR(dtOffered, dtLimit, 1e-3 * dtLimit);
        EXPECT_NO_THROW(scene(c.collider, dtOffered)) << "the offered Δt must pass";
        EXPECT_NEAR(speedOffered, c.travel / (1.01 * dtLimit), 1e-3 * speedOffered);
        EXPECT_LE(speedOffered * 1.01 * dtLimit, c.travel) << "the offered speed must pass";
    }
}

INSTANTIATE_TEST_SUITE_P(Shapes, ColliderMotionLimit, testing::ValuesIn(limitCases()),
                         [](const testing::TestParamInfo<LimitCase>& p) { return p.param.name; });

// A switched-off collider (the viewer's toggles) is not checked; a still one never is.
TEST(ColliderMotionLimit, SwitchedOffAndStillCollidersAreNotChecked) {
    Scene s;
    s.integrator.dt = 0.01;
    Collider fast = Sphere{glm::dvec3(0), 0.05};
    ColliderMotion m;
    m.velocity = {10, 0, 0};  // 0.1 m per step against 0.05 m
    fast.motion = m;
    s.colliders = {Collider{Sphere{glm::dvec3(0), 0.001}}, fast};
    EXPECT_THROW(checkColliderMotionStep(s), InputError);
    EXPECT_THROW(checkColliderMotionStep(s, {true}), InputError);  // missing entries: on
    EXPECT_NO_THROW(checkColliderMotionStep(s, {true, false}));
    s.colliders.pop_back();
    EXPECT_NO_THROW(checkColliderMotionStep(s));
}

// Every shipped scene loads (so it passes the rule) with its moving colliders far inside the
// limit: the smallest margin maxColliderStepTravel / (maxMotionSpeed·Δt) is printed.
TEST(ColliderMotionLimit, EveryShippedScenePassesWithAMargin) {
    std::vector<fs::path> scenes;
    for (const auto& e : fs::directory_iterator(CLOTH_SOURCE_DIR "/scenes"))
        if (e.path().extension() == ".json") scenes.push_back(e.path());
    std::sort(scenes.begin(), scenes.end());
    ASSERT_GE(scenes.size(), 8u);
    for (const fs::path& path : scenes) {
        Scene s;
        ASSERT_NO_THROW(s = loadScene(path.string())) << path;
        double margin = std::numeric_limits<double>::infinity();
        int which = -1;
        for (std::size_t n = 0; n < s.colliders.size(); ++n) {
            const double m = motionStepMargin(s.colliders[n], s.integrator.dt);
            if (m < margin) margin = m, which = int(n);
        }
        if (which < 0) {
            std::printf("%-14s no moving collider that could be tunnelled\n",
                        path.filename().c_str());
            continue;
        }
        const Collider& c = s.colliders[std::size_t(which)];
        std::printf(
            "%-14s margin %.0fx: colliders[%d] at up to %.3g m/s, %.3g mm per step of "
            "%.3g ms against %.3g mm\n",
            path.filename().c_str(), margin, which, maxMotionSpeed(c),
            1e3 * maxMotionSpeed(c) * s.integrator.dt, 1e3 * s.integrator.dt,
            1e3 * maxColliderStepTravel(c));
        EXPECT_GT(margin, 10.0) << path;
    }
}

}  // namespace
}  // namespace cloth
