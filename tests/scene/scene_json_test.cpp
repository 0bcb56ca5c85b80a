// Saving a scene and loading it back gives the same scene: what the viewer saves, `run` replays.
#include "scene/scene_json.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "scene/scene_loader.h"

namespace cloth {
namespace {

void expectSameScene(const Scene& a, const Scene& b) {
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.cloth.nu, b.cloth.nu);
    EXPECT_EQ(a.cloth.nv, b.cloth.nv);
    EXPECT_EQ(a.cloth.size, b.cloth.size);
    EXPECT_EQ(a.cloth.origin, b.cloth.origin);
    EXPECT_EQ(a.cloth.uAxis, b.cloth.uAxis);
    EXPECT_EQ(a.cloth.vAxis, b.cloth.vAxis);
    EXPECT_EQ(a.cloth.mass, b.cloth.mass);
    for (Family f : {Family::Structural, Family::Shear, Family::Bend})
        EXPECT_EQ(a.springs.of(f), b.springs.of(f));
    EXPECT_EQ(a.damping, b.damping);
    ASSERT_EQ(a.material.has_value(), b.material.has_value());
    if (a.material) {
        EXPECT_EQ(a.material->density, b.material->density);
        EXPECT_EQ(a.material->stretch, b.material->stretch);
        EXPECT_EQ(a.material->shear, b.material->shear);
        EXPECT_EQ(a.material->bend, b.material->bend);
        EXPECT_EQ(a.material->airDamping, b.material->airDamping);
    }
    EXPECT_EQ(a.gravity, b.gravity);
    ASSERT_EQ(a.pins.size(), b.pins.size());
    for (size_t n = 0; n < a.pins.size(); ++n) {
        EXPECT_EQ(a.pins[n].i, b.pins[n].i);
        EXPECT_EQ(a.pins[n].j, b.pins[n].j);
    }
    EXPECT_EQ(a.integrator.method, b.integrator.method);
    EXPECT_EQ(a.integrator.dt, b.integrator.dt);
    EXPECT_EQ(a.integrator.substeps, b.integrator.substeps);
    ASSERT_EQ(a.colliders.size(), b.colliders.size());
    EXPECT_EQ(a.planeCount(), b.planeCount());
    EXPECT_EQ(a.sphereCount(), b.sphereCount());
    EXPECT_EQ(a.wind.has_value(), b.wind.has_value());
    if (a.wind && b.wind) {
        EXPECT_EQ(a.wind->direction, b.wind->direction);
        EXPECT_EQ(a.wind->strength, b.wind->strength);
    }
    EXPECT_EQ(a.maxSpeed, b.maxSpeed);
    EXPECT_EQ(a.duration, b.duration);
}

TEST(SceneJson, EveryShippedSceneRoundTripsExactly) {
    for (const auto& e : std::filesystem::directory_iterator(CLOTH_SOURCE_DIR "/scenes")) {
        SCOPED_TRACE(e.path().string());
        const Scene a = loadScene(e.path().string());
        const Scene b = parseScene(sceneToJson(a), "saved");
        expectSameScene(a, b);
        EXPECT_EQ(sceneToJson(a), sceneToJson(b));  // a fixed point
    }
}

TEST(SceneJson, EditedParametersSurviveTheRoundTrip) {
    Scene a = loadScene(CLOTH_SOURCE_DIR "/scenes/drape.json");  // the material form (cotton)
    a.material->bend = 0;
    a.material->airDamping = 0.1234567890123;
    a.pins.push_back({3, 5});
    a.colliders[1].as<Sphere>()->radius = 0.41;
    a.wind = Wind{{0, 0, 1}, 0.5};
    expectSameScene(a, parseScene(sceneToJson(a), "saved"));
    // The same scene in the per-vertex form: a family not modelled must stay absent, not come
    // back as 0-stiffness springs.
    a.material.reset();
    a.cloth.mass = 0.006;
    a.springs = {400, 100, 0};
    a.damping = 0.1234567890123;
    const Scene b = parseScene(sceneToJson(a), "saved");
    expectSameScene(a, b);
    EXPECT_EQ(sceneToJson(a).find("\"bend\""), std::string::npos);
}

}  // namespace
}  // namespace cloth
