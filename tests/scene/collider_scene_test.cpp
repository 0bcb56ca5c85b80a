// The collider keys of docs/colliders.md §5 in the scene format: every key survives a save and a
// load bit for bit, and each bad value is refused naming its key path.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "model/collider_mesh.h"
#include "model/errors.h"
#include "scene/collider_validate.h"
#include "scene/scene_json.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/process.h"

namespace cloth {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

// A scene using every collider key, with its OBJ beside it.
fs::path everyKeyScene() {
    const fs::path dir = test::freshTempDir("ColliderScene", "every_key");
    writeMeshesObj((dir / "block.obj").string(),
                   {{"block", boxMesh({{0, 0, 0}, {0.2, 0.1, 0.3}, glm::dmat3(1)})}});
    std::ofstream(dir / "scene.json") << R"({
      "cloth": { "resolution": [4, 3], "size": [1, 1], "origin": [0, 2, 0] },
      "integrator": { "dt": 0.001 },
      "colliders": [
        { "type": "box", "center": [0, 0.4, 0], "half_extents": [0.5, 0.02, 0.3],
          "rotation": { "axis": [1, 2, 0], "degrees": 15 }, "thickness": 0.005, "friction": 0.6 },
        { "type": "capsule", "a": [0, 0.8, 0], "b": [0, 1.4, 0], "radius": 0.12,
          "motion": { "type": "rotation", "axis": [0, 3, 0], "pivot": [0.1, 0, 0],
                      "degrees_per_second": 45 } },
        { "type": "mesh", "file": "block.obj", "cell": 0.05, "band": 0.1,
          "translation": [0, 0.2, 0], "rotation": { "axis": [0, 1, 0], "degrees": 30 },
          "thickness": 0.01 },
        { "type": "sphere", "center": [0, 0.5, 0], "radius": 0.3, "friction": 0.1,
          "motion": { "type": "oscillation", "axis": [1, 0, 0], "amplitude": 0.2,
                      "frequency": 0.5, "phase_degrees": 10 } },
        { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "thickness": 0.001,
          "motion": { "type": "linear", "velocity": [0, 0.1, 0] } } ]
    })";
    return dir / "scene.json";
}

// sceneToJson writes every key back; loading it gives the same scene, and saving that the same
// text (a fixed point), including the baked mesh found again by its absolute path.
TEST(ColliderScene, EveryKeyRoundTripsExactly) {
    const Scene a = loadScene(everyKeyScene().string());
    const std::string saved = sceneToJson(a);
    const Scene b = parseScene(saved, "saved elsewhere");
    EXPECT_EQ(saved, sceneToJson(b));
    ASSERT_EQ(b.colliders.size(), 5u);
    for (size_t k = 0; k < a.colliders.size(); ++k) {
        const Collider &x = a.colliders[k], &y = b.colliders[k];
        EXPECT_EQ(x.shape.index(), y.shape.index()) << k;
        EXPECT_EQ(x.thickness, y.thickness) << k;
        EXPECT_EQ(x.friction, y.friction) << k;
        ASSERT_EQ(x.motion.has_value(), y.motion.has_value()) << k;
        if (x.motion) {
            EXPECT_EQ(x.motion->type, y.motion->type);
            EXPECT_EQ(x.motion->velocity, y.motion->velocity);
            EXPECT_EQ(x.motion->axis, y.motion->axis);
            EXPECT_EQ(x.motion->pivot, y.motion->pivot);
            EXPECT_EQ(x.motion->degreesPerSecond, y.motion->degreesPerSecond);
            EXPECT_EQ(x.motion->amplitude, y.motion->amplitude);
            EXPECT_EQ(x.motion->frequency, y.motion->frequency);
            EXPECT_EQ(x.motion->phaseDegrees, y.motion->phaseDegrees);
        }
    }
    const Box &ba = *a.colliders[0].as<Box>(), &bb = *b.colliders[0].as<Box>();
    EXPECT_EQ(ba.halfExtents, bb.halfExtents);
    EXPECT_EQ(ba.rotation.axis, bb.rotation.axis);
    EXPECT_EQ(ba.rotation.degrees, bb.rotation.degrees);
    EXPECT_NEAR(glm::length(ba.rotation.axis), 1, 1e-15);  // normalised by the loader
    const Capsule& cap = *b.colliders[1].as<Capsule>();
    EXPECT_EQ(cap.radius, 0.12);
    EXPECT_EQ(b.colliders[1].motion->axis, glm::dvec3(0, 1, 0));
    const MeshCollider &ma = *a.colliders[2].as<MeshCollider>(),
                       &mb = *b.colliders[2].as<MeshCollider>();
    EXPECT_TRUE(fs::path(mb.path).is_absolute());
    EXPECT_EQ(ma.path, mb.path);
    EXPECT_EQ(ma.translation, mb.translation);
    EXPECT_EQ(ma.baked->grid.values, mb.baked->grid.values);
    EXPECT_EQ(ma.baked->mesh.triangles.size(), 12u);
    // Copying a scene shares the baked grid instead of copying it.
    const Scene c = a;
    EXPECT_EQ(c.colliders[2].as<MeshCollider>()->baked.get(), ma.baked.get());
    const Features f = Features::of(a);
    EXPECT_EQ(f.boxes, 1);
    EXPECT_EQ(f.capsules, 1);
    EXPECT_EQ(f.meshes, 1);
    EXPECT_EQ(f.contactExtras, 5);
}

// A scene without the new keys saves as it always did: no thickness, friction or motion keys.
TEST(ColliderScene, DefaultsStayAbsentWhenSaved) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [2, 2], "size": [1, 1]},
        "integrator": {"dt": 0.01}, "colliders": [
        {"type": "sphere", "center": [0, 0, 0], "radius": 1}]})",
                               "plain");
    EXPECT_TRUE(s.colliders[0].plain());
    const std::string text = sceneToJson(s);
    for (const char* key : {"thickness", "friction", "motion"})
        EXPECT_EQ(text.find(key), std::string::npos) << key;
}

// Each bad collider value → InputError naming the scene file and the key path.
TEST(ColliderScene, BadValuesNameTheirKey) {
    const fs::path scene = everyKeyScene();
    const fs::path dir = scene.parent_path();
    std::ofstream(dir / "empty.obj") << "# nothing\n";
    std::ofstream(dir / "open.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const Json base = Json::parse(std::ifstream(scene));
    struct Bad {
        std::string pointer;
        Json value;
        std::string key;
    };
    const Bad bad[] = {
        {"/colliders/1/radius", -0.1, "colliders[1].radius"},
        {"/colliders/3/radius", -0.1, "colliders[3].radius"},
        {"/colliders/0/half_extents/1", 0, "colliders[0].half_extents"},
        {"/colliders/0/rotation/axis", Json::array({0, 0, 0}), "colliders[0].rotation.axis"},
        {"/colliders/0/rotation/degrees", "ten", "colliders[0].rotation.degrees"},
        {"/colliders/0/friction", -1, "colliders[0].friction"},
        {"/colliders/4/thickness", -0.01, "colliders[4].thickness"},
        {"/colliders/2/file", "missing.obj", "colliders[2].file"},
        {"/colliders/2/file", "empty.obj", "colliders[2].file"},
        {"/colliders/2/file", "open.obj", "colliders[2].file"},
        {"/colliders/2/thickness", 0.5, "colliders[2].thickness"},
        {"/colliders/2/cell", 0, "colliders[2].cell"},
        {"/colliders/1/motion/axis", Json::array({0, 0, 0}), "colliders[1].motion.axis"},
        {"/colliders/1/motion/type", "spiral", "colliders[1].motion.type"},
        {"/colliders/3/motion/frequency", -1, "colliders[3].motion.frequency"},
        {"/colliders/0/colour", "red", "colliders[0].colour"},
        {"/colliders/1/motion/speed", 1, "colliders[1].motion.speed"},
    };
    for (const Bad& b : bad) {
        Json j = base;
        j[Json::json_pointer(b.pointer)] = b.value;
        try {
            parseScene(j.dump(), scene.string());
            ADD_FAILURE() << b.pointer << " = " << b.value.dump() << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.key(), b.key) << e.what();
            EXPECT_EQ(e.file(), scene.string()) << e.what();
        }
    }
}

}  // namespace
}  // namespace cloth
