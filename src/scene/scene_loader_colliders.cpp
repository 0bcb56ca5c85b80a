// The collider keys of docs/colliders.md §5: plane, sphere, box, capsule and mesh, each with an
// optional thickness, friction and motion, validated by scene/collider_validate.h.
#include <filesystem>
#include <iterator>
#include <memory>

#include "scene/collider_validate.h"
#include "scene/key_path.h"
#include "scene/scene_reader.h"

namespace cloth::detail {
namespace {

// The keys every collider type takes besides its shape's (docs/colliders.md §5).
constexpr const char* kContactKeys[] = {"type", "thickness", "friction", "motion"};

}  // namespace

void SceneReader::expectCollider(const Json& j, const std::string& path,
                                 std::initializer_list<const char*> shapeKeys) const {
    std::vector<const char*> allowed(std::begin(kContactKeys), std::end(kContactKeys));
    allowed.insert(allowed.end(), shapeKeys.begin(), shapeKeys.end());
    expectKeys(j, path, allowed);
}

AxisAngle SceneReader::readRotation(const Json& j, const std::string& path) const {
    expectObject(j, path, {"axis", "degrees"});
    AxisAngle r;
    const glm::dvec3 axis = vec3(required(j, "axis", path), child(path, "axis"));
    r.degrees = number(required(j, "degrees", path), child(path, "degrees"));
    checkRotation({source_, path}, axis, r.degrees);  // names .axis: zero, NaN, infinite
    r.axis = unitKeepingBits(axis);
    return r;
}

ColliderMotion SceneReader::readMotion(const Json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, "expected a motion object, got " + describe(j));
    const Json& type = required(j, "type", path);
    const std::string t = type.is_string() ? type.get<std::string>() : "";
    ColliderMotion m;
    auto num = [&](const char* key) { return number(required(j, key, path), child(path, key)); };
    auto v3 = [&](const char* key) { return vec3(required(j, key, path), child(path, key)); };
    if (t == "linear") {
        expectObject(j, path, {"type", "velocity"});
        m.type = MotionType::Linear;
        m.velocity = v3("velocity");
    } else if (t == "rotation") {
        expectObject(j, path, {"type", "axis", "pivot", "degrees_per_second"});
        m.type = MotionType::Rotation;
        m.axis = v3("axis");
        if (j.contains("pivot")) m.pivot = v3("pivot");
        m.degreesPerSecond = num("degrees_per_second");
    } else if (t == "oscillation") {
        expectObject(j, path, {"type", "axis", "amplitude", "frequency", "phase_degrees"});
        m.type = MotionType::Oscillation;
        m.axis = v3("axis");
        m.amplitude = num("amplitude");
        m.frequency = num("frequency");
        if (j.contains("phase_degrees")) m.phaseDegrees = num("phase_degrees");
    } else {
        fail(child(path, "type"),
             "unknown motion type " + describe(type) + "; known: linear, rotation, oscillation");
    }
    checkMotion({source_, path}, m.motion());  // axis non-zero, frequency >= 0, finite
    m.axis = unitKeepingBits(m.axis);
    return m;
}

ColliderShape SceneReader::readShape(const Json& j, const std::string& path, const std::string& t,
                                     double thickness) const {
    auto v3 = [&](const char* key) { return vec3(required(j, key, path), child(path, key)); };
    auto num = [&](const char* key) { return number(required(j, key, path), child(path, key)); };
    if (t == "plane") {
        expectCollider(j, path, {"point", "normal"});
        Plane plane;
        plane.point = v3("point");
        plane.normal = direction(required(j, "normal", path), child(path, "normal"));
        return plane;
    }
    if (t == "sphere") {
        expectCollider(j, path, {"center", "radius"});
        Sphere sphere;
        sphere.center = v3("center");
        sphere.radius = param(j, "radius", child(path, "radius"), "colliders[].radius");
        return sphere;
    }
    if (t == "box") {
        expectCollider(j, path, {"center", "half_extents", "rotation"});
        Box box;
        box.center = v3("center");
        box.halfExtents =
            checkHalfExtents({source_, child(path, "half_extents")}, v3("half_extents"));
        if (j.contains("rotation"))
            box.rotation = readRotation(j["rotation"], child(path, "rotation"));
        return box;
    }
    if (t == "capsule") {
        expectCollider(j, path, {"a", "b", "radius"});
        Capsule cap;
        cap.a = v3("a");
        cap.b = v3("b");
        cap.radius = checkRadius({source_, child(path, "radius")}, num("radius"));
        return cap;
    }
    if (t == "mesh") {
        expectCollider(j, path, {"file", "cell", "band", "translation", "rotation"});
        MeshCollider mesh;
        const Json& file = required(j, "file", path);
        if (!file.is_string())
            fail(child(path, "file"), "expected a string, got " + describe(file));
        mesh.file = file.get<std::string>();
        mesh.cell = num("cell");
        mesh.band = num("band");
        if (j.contains("translation")) mesh.translation = v3("translation");
        if (j.contains("rotation"))
            mesh.rotation = readRotation(j["rotation"], child(path, "rotation"));
        auto baked = std::make_shared<BakedMesh>(
            checkMeshCollider({source_, path}, mesh.file, mesh.cell, mesh.band, thickness));
        mesh.baked = std::move(baked);
        namespace fs = std::filesystem;
        fs::path obj(mesh.file);
        if (obj.is_relative()) obj = fs::path(source_).parent_path() / obj;
        mesh.path = fs::absolute(obj).lexically_normal().string();
        return mesh;
    }
    fail(child(path, "type"),
         "unknown collider type \"" + t + "\"; known: plane, sphere, box, capsule, mesh");
}

Collider SceneReader::readCollider(const Json& j, const std::string& path) const {
    if (!j.is_object()) fail(path, "expected a collider object, got " + describe(j));
    const Json& type = required(j, "type", path);
    if (!type.is_string()) fail(child(path, "type"), "expected a string, got " + describe(type));
    Collider c;
    if (j.contains("thickness"))
        c.thickness = checkThickness({source_, child(path, "thickness")},
                                     number(j["thickness"], child(path, "thickness")));
    if (j.contains("friction"))
        c.friction = checkFriction({source_, child(path, "friction")},
                                   number(j["friction"], child(path, "friction")));
    c.shape = readShape(j, path, type.get<std::string>(), c.thickness);
    if (j.contains("motion")) c.motion = readMotion(j["motion"], child(path, "motion"));
    return c;
}

}  // namespace cloth::detail
