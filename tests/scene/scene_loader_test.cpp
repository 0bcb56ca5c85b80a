// The loader's semantics on valid input (DESIGN.md §4): defaults, normalisation, negative pin
// indices, and --set overrides validated like the file.
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include "model/errors.h"
#include "scene/params.h"
#include "scene/scene_overrides.h"

namespace cloth {
namespace {

constexpr const char* kMinimal =
    R"({"cloth": {"resolution": [4, 3], "size": [3, 1]}, "integrator": {"dt": 0.01}})";

TEST(SceneLoader, AbsentKeysTakeTheDocumentedDefaultsAndModelNothingExtra) {
    const Scene s = parseScene(kMinimal, "minimal.json");
    EXPECT_EQ(s.name, "minimal");
    EXPECT_EQ(s.cloth.mass, 1.0);
    EXPECT_EQ(s.gravity, glm::dvec3(0, -9.81, 0));
    EXPECT_EQ(s.springs.structural + s.springs.shear + s.springs.bend, 0.0);
    EXPECT_EQ(s.damping, 0.0);
    EXPECT_FALSE(s.wind.has_value());
    EXPECT_TRUE(s.colliders.empty());
    EXPECT_TRUE(s.pins.empty());
    EXPECT_EQ(s.maxSpeed, 1e4);
    const Grid g = s.grid();
    EXPECT_DOUBLE_EQ(g.du, 1.0);  // size / (n − 1)
    EXPECT_DOUBLE_EQ(g.dv, 0.5);
}

TEST(SceneLoader, AxesAndDirectionsAreNormalised) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [2, 2], "size": [1, 1],
        "u_axis": [3, 0, 4], "v_axis": [0, -2, 0]}, "integrator": {"dt": 0.01},
        "wind": {"direction": [0, 0, 5], "strength": 2},
        "colliders": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 10, 0]}]})",
                               "axes");
    EXPECT_NEAR(glm::length(s.cloth.uAxis), 1.0, 1e-15);
    EXPECT_NEAR(s.cloth.uAxis.x, 0.6, 1e-15);
    EXPECT_EQ(s.cloth.vAxis, glm::dvec3(0, -1, 0));
    EXPECT_EQ(s.wind->direction, glm::dvec3(0, 0, 1));
    EXPECT_EQ(s.colliders[0].as<Plane>()->normal, glm::dvec3(0, 1, 0));
}

TEST(SceneLoader, NegativePinIndicesCountFromTheEnd) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [5, 4], "size": [1, 1]},
        "integrator": {"dt": 0.01}, "pins": [[-1, 0], [0, -1], [-5, -4]]})",
                               "pins");
    ASSERT_EQ(s.pins.size(), 3u);
    EXPECT_EQ(s.pins[0].i, 4);
    EXPECT_EQ(s.pins[0].j, 0);
    EXPECT_EQ(s.pins[1].j, 3);
    EXPECT_EQ(s.pins[2].i, 0);
    EXPECT_EQ(s.pins[2].j, 0);
}

TEST(SceneLoader, ColliderOrderIsKept) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [2, 2], "size": [1, 1]},
        "integrator": {"dt": 0.01}, "colliders": [
        {"type": "sphere", "center": [0, 0, 0], "radius": 1},
        {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
        {"type": "sphere", "center": [1, 0, 0], "radius": 2}]})",
                               "order");
    ASSERT_EQ(s.colliders.size(), 3u);
    EXPECT_TRUE(s.colliders[0].as<Sphere>() != nullptr);
    EXPECT_TRUE(s.colliders[1].as<Plane>() != nullptr);
    EXPECT_EQ(s.colliders[2].as<Sphere>()->radius, 2.0);
    EXPECT_EQ(s.planeCount(), 1);
    EXPECT_EQ(s.sphereCount(), 2);
}

TEST(Overrides, SetChangesTheKeyAndCreatesSections) {
    const Scene s = parseScene(kMinimal, "o",
                               {"integrator.dt=0.002", "springs.bend=7",
                                "wind={\"direction\":[1,0,0],"
                                "\"strength\":3}"});
    EXPECT_EQ(s.integrator.dt, 0.002);
    EXPECT_EQ(s.springs.bend, 7.0);
    ASSERT_TRUE(s.wind.has_value());
    EXPECT_EQ(s.wind->strength, 3.0);
}

TEST(Overrides, ListEntriesAreReachedByIndexInEitherSpelling) {
    const std::string text = R"({"cloth": {"resolution": [2, 2], "size": [1, 1]},
        "integrator": {"dt": 0.01}, "colliders": [
        {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
        {"type": "sphere", "center": [0, 0, 0], "radius": 1}]})";
    EXPECT_EQ(parseScene(text, "o", {"colliders.1.radius=0.5"}).colliders[1].as<Sphere>()->radius,
              0.5);
    EXPECT_EQ(parseScene(text, "o", {"colliders[1].radius=0.25"}).colliders[1].as<Sphere>()->radius,
              0.25);
}

// An index into a list the scene lacks names the missing list, not an object the --set made.
TEST(Overrides, AnIndexIntoAListTheSceneLacksNamesTheList) {
    try {
        parseScene(kMinimal, "o.json", {"colliders.1.radius=0.4"});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "o.json");
        EXPECT_EQ(e.key(), "colliders.1.radius");
        EXPECT_NE(e.reason().find("the scene has no colliders, so '1' is not an index of it"),
                  std::string::npos)
            << e.reason();
    }
}

TEST(Overrides, BadOverrideIsRejectedLikeTheFileWouldBe) {
    try {
        parseScene(kMinimal, "o.json", {"springs.bnd=3"});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "o.json");
        EXPECT_EQ(e.key(), "springs.bnd");
        EXPECT_NE(e.reason().find("unknown key"), std::string::npos);
        EXPECT_NE(e.reason().find("--set"), std::string::npos);
    }
    try {
        parseScene(kMinimal, "o.json", {"integrator.dt=-1"});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "integrator.dt");
        EXPECT_NE(e.reason().find("> 0"), std::string::npos);
    }
}

TEST(Params, TableRangesAreEnforcedWithUnits) {
    const ParamSpec* dt = findParam("integrator.dt");
    ASSERT_NE(dt, nullptr);
    EXPECT_EQ(checkRange(*dt, 0.001), "");
    EXPECT_NE(checkRange(*dt, 0.0).find("> 0 s"), std::string::npos);
    const ParamSpec* substeps = findParam("integrator.substeps");
    ASSERT_NE(substeps, nullptr);
    EXPECT_NE(checkRange(*substeps, 1.5).find("integer"), std::string::npos);
    for (const ParamSpec& p : paramTable())
        EXPECT_GT(std::string(p.description).size(), 5u) << p.path;
}

// A --set replaced by a later one (same key in either spelling, or a key inside the later
// one's value) gets one notice naming both; other keys get none. The later still wins.
TEST(SceneLoader, RepeatedOverrideIsNoticedAndTheLaterWins) {
    const std::vector<std::string> earlier = {"springs.bend=100", "colliders.1.radius=0.4",
                                              "damping=1"};
    const std::vector<std::string> same = replacedOverrides(earlier, "springs.bend=0");
    ASSERT_EQ(same.size(), 1u);
    EXPECT_NE(same[0].find("springs.bend=100"), std::string::npos) << same[0];
    EXPECT_NE(same[0].find("springs.bend=0"), std::string::npos) << same[0];
    EXPECT_EQ(replacedOverrides(earlier, "colliders[1].radius=0.5").size(), 1u);
    EXPECT_EQ(replacedOverrides(earlier, "springs={}").size(), 1u);
    EXPECT_TRUE(replacedOverrides(earlier, "springs.shear=1").empty());
    EXPECT_TRUE(replacedOverrides(earlier, "nokey").empty());
    EXPECT_EQ(parseScene(kMinimal, "o", {"springs.bend=100", "springs.bend=0"}).springs.bend, 0);
}

}  // namespace
}  // namespace cloth
