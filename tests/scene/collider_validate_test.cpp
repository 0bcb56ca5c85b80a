// The collider checks of scene/collider_validate.h, ready for the scene loader: every bad value
// (negative radius, non-positive half extents, NaN or zero rotation axis, missing mesh file,
// empty OBJ, bad friction or thickness, bad motion) is an InputError naming the scene file and
// the exact key path; good values come back validated (axes normalised).
#include "scene/collider_validate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>

#include "model/collider_mesh.h"
#include "model/errors.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using D3 = glm::dvec3;
const double kNaN = std::nan("");
const KeyRef kAt{"scenes/x.json", "colliders[2]"};

KeyRef at(const std::string& key) {
    return {kAt.file, kAt.key + "." + key};
}

// The key path of the InputError `f` throws ("" and a test failure if it throws none).
std::string keyOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), kAt.file);
        return e.key();
    }
    ADD_FAILURE() << "no InputError";
    return "";
}

TEST(ColliderValidate, BadShapeNumbersNameTheirKey) {
    EXPECT_EQ(keyOf([] { checkRadius(at("radius"), -0.1); }), "colliders[2].radius");
    EXPECT_EQ(keyOf([] { checkRadius(at("radius"), 0); }), "colliders[2].radius");
    EXPECT_EQ(keyOf([] { checkRadius(at("radius"), kNaN); }), "colliders[2].radius");
    EXPECT_EQ(keyOf([] { checkHalfExtents(at("half_extents"), D3(1, 0, 1)); }),
              "colliders[2].half_extents");
    EXPECT_EQ(keyOf([] { checkHalfExtents(at("half_extents"), D3(1, -2, 1)); }),
              "colliders[2].half_extents");
    EXPECT_EQ(keyOf([] { checkFinite(at("a"), D3(0, INFINITY, 0)); }), "colliders[2].a");
    EXPECT_EQ(keyOf([] { checkThickness(at("thickness"), -1e-3); }), "colliders[2].thickness");
    EXPECT_EQ(keyOf([] { checkFriction(at("friction"), -0.5); }), "colliders[2].friction");
    EXPECT_EQ(keyOf([] { checkFriction(at("friction"), kNaN); }), "colliders[2].friction");
    EXPECT_EQ(checkRadius(at("radius"), 0.3), 0.3);
    EXPECT_EQ(checkFriction(at("friction"), 0), 0);
    EXPECT_EQ(checkThickness(at("thickness"), 0), 0);
}

TEST(ColliderValidate, RotationNeedsAFiniteNonZeroAxisAndAFiniteAngle) {
    EXPECT_EQ(keyOf([] { checkRotation(at("rotation"), D3(0), 30); }),
              "colliders[2].rotation.axis");
    EXPECT_EQ(keyOf([] { checkRotation(at("rotation"), D3(kNaN, 1, 0), 30); }),
              "colliders[2].rotation.axis");
    EXPECT_EQ(keyOf([] { checkRotation(at("rotation"), D3(0, 1, 0), kNaN); }),
              "colliders[2].rotation.degrees");
    // A valid one: 90° about an unnormalised z takes x to y.
    const glm::dmat3 r = checkRotation(at("rotation"), D3(0, 0, 5), 90);
    EXPECT_NEAR(glm::length(r * D3(1, 0, 0) - D3(0, 1, 0)), 0, 1e-15);
}

TEST(ColliderValidate, MotionNumbersNameTheirKey) {
    Motion m;
    m.type = MotionType::Rotation;
    m.axis = D3(0);
    EXPECT_EQ(keyOf([&] { checkMotion(at("motion"), m); }), "colliders[2].motion.axis");
    m.axis = D3(0, 2, 0);
    m.angularSpeed = kNaN;
    EXPECT_EQ(keyOf([&] { checkMotion(at("motion"), m); }),
              "colliders[2].motion.degrees_per_second");
    m.type = MotionType::Oscillation;
    m.frequency = -1;
    EXPECT_EQ(keyOf([&] { checkMotion(at("motion"), m); }), "colliders[2].motion.frequency");
    m.frequency = 1;
    EXPECT_NEAR(glm::length(checkMotion(at("motion"), m).axis - D3(0, 1, 0)), 0, 1e-15);
    m.type = MotionType::Linear;
    m.velocity = D3(kNaN);
    EXPECT_EQ(keyOf([&] { checkMotion(at("motion"), m); }), "colliders[2].motion.velocity");
}

TEST(ColliderValidate, MeshFileProblemsNameTheFileKey) {
    const fs::path dir = test::testTempDir();
    const KeyRef mesh{(dir / "scene.json").string(), "colliders[2]"};
    const auto key = [&](const std::function<void()>& f) {
        try {
            f();
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), mesh.file);
            return e.key() + ": " + e.reason();
        }
        ADD_FAILURE() << "no InputError";
        return std::string();
    };
    EXPECT_EQ(key([&] {
                  checkMeshCollider(mesh, "nope.obj", 0.05, 0.1, 0);
              }).rfind("colliders[2].file: '", 0),
              0u);
    std::ofstream(dir / "empty.obj") << "# empty\n";
    EXPECT_NE(key([&] { checkMeshCollider(mesh, "empty.obj", 0.05, 0.1, 0); }).find("no triangles"),
              std::string::npos);
    // A good mesh, relative to the scene's folder; then bad grid numbers.
    writeMeshesObj((dir / "box.obj").string(), {{"box", boxMesh({D3(0), D3(0.2), glm::dmat3(1)})}});
    const BakedMesh baked = checkMeshCollider(mesh, "box.obj", 0.05, 0.1, 0.01);
    EXPECT_EQ(baked.mesh.triangles.size(), 12u);
    // The grid's corner sample is a band away from the box along each axis.
    EXPECT_NEAR(baked.grid.at(0, 0, 0), std::sqrt(3.0) * 0.1, 1e-9);
    EXPECT_EQ(
        key([&] { checkMeshCollider(mesh, "box.obj", 0, 0.1, 0); }).rfind("colliders[2].cell", 0),
        0u);
    EXPECT_EQ(
        key([&] { checkMeshCollider(mesh, "box.obj", 0.05, -1, 0); }).rfind("colliders[2].band", 0),
        0u);
    EXPECT_EQ(key([&] {
                  checkMeshCollider(mesh, "box.obj", 0.05, 0.1, 0.2);
              }).rfind("colliders[2].thickness", 0),
              0u);
    EXPECT_EQ(key([&] {
                  checkMeshCollider(mesh, "box.obj", 1e-5, 0.1, 0);
              }).rfind("colliders[2].cell", 0),
              0u);
}

}  // namespace
}  // namespace cloth
