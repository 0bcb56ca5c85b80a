#include "core/scene_loader.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/collider_validate.h"
#include "core/errors.h"
#include "core/key_path.h"
#include "core/params.h"
#include "core/scene_overrides.h"
#include "core/scene_text.h"

namespace cloth {
namespace {

using Json = nlohmann::json;

glm::dvec3 unitKeepingBits(const glm::dvec3& d);

std::string describe(const Json& j) {
    switch (j.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return "a boolean";
        case Json::value_t::string: {
            std::string s = j.get<std::string>();
            if (s.size() > 40) s = s.substr(0, 40) + "...";
            return "the string \"" + s + "\"";
        }
        case Json::value_t::array:
            return "an array of " + std::to_string(j.size());
        case Json::value_t::object:
            return "an object";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float:
            return "the number " + j.dump();
        default:
            return "a value of another type";
    }
}

// Reads one JSON document into a Scene, naming the file and key path in every complaint.
class SceneReader {
public:
    explicit SceneReader(std::string source) : source_(std::move(source)) {}

    Scene read(const Json& doc);

private:
    [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
        throw InputError(source_, path, reason);
    }

    void expectObject(const Json& j, const std::string& path,
                      std::initializer_list<const char*> allowed) const {
        expectKeys(j, path, std::vector<const char*>(allowed));
    }
    void expectKeys(const Json& j, const std::string& path,
                    const std::vector<const char*>& allowed) const;
    double number(const Json& j, const std::string& path) const;
    double param(const Json& obj, const std::string& key, const std::string& path, const char* spec,
                 double fallback) const;
    glm::dvec3 vec3(const Json& j, const std::string& path) const;
    glm::dvec3 direction(const Json& j, const std::string& path) const;
    int integer(const Json& j, const std::string& path) const;
    const Json& required(const Json& obj, const std::string& key, const std::string& path) const;

    void readCloth(const Json& j, ClothSpec& cloth) const;
    void readSprings(const Json& j, SpringStiffness& springs) const;
    void readIntegrator(const Json& j, IntegratorSpec& integrator) const;
    std::vector<Pin> readPins(const Json& j, const ClothSpec& cloth) const;
    Collider readCollider(const Json& j, const std::string& path) const;
    ColliderShape readShape(const Json& j, const std::string& path, const std::string& type,
                            double thickness) const;
    void expectCollider(const Json& j, const std::string& path,
                        std::initializer_list<const char*> shapeKeys) const;
    AxisAngle readRotation(const Json& j, const std::string& path) const;
    ColliderMotion readMotion(const Json& j, const std::string& path) const;
    Wind readWind(const Json& j) const;

    std::string source_;
};

void SceneReader::expectKeys(const Json& j, const std::string& path,
                             const std::vector<const char*>& allowed) const {
    if (!j.is_object()) fail(path, "expected an object, got " + describe(j));
    for (const auto& [key, value] : j.items()) {
        bool known = false;
        for (const char* a : allowed) known = known || key == a;
        if (known) continue;
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(child(path, key),
             "unknown key (a typo would silently disable a feature); "
             "allowed here: " +
                 list);
    }
}

double SceneReader::number(const Json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "expected a number, got " + describe(j));
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(path, "must be a finite number, got " + j.dump());
    return x;
}

double SceneReader::param(const Json& obj, const std::string& key, const std::string& path,
                          const char* spec, double fallback) const {
    if (!obj.contains(key)) return fallback;
    const double x = number(obj.at(key), path);
    const std::string why = checkRange(*findParam(spec), x);
    if (!why.empty()) fail(path, why);
    return x;
}

int SceneReader::integer(const Json& j, const std::string& path) const {
    if (!j.is_number_integer()) fail(path, "expected an integer, got " + describe(j));
    if (j.is_number_unsigned() && j.get<std::uint64_t>() > std::uint64_t(INT32_MAX))
        fail(path, "integer " + j.dump() + " is too large");
    const std::int64_t x = j.get<std::int64_t>();
    if (x > INT32_MAX || x < INT32_MIN) fail(path, "integer " + j.dump() + " is too large");
    return int(x);
}

glm::dvec3 SceneReader::vec3(const Json& j, const std::string& path) const {
    if (!j.is_array() || j.size() != 3)
        fail(path, "expected an array of 3 numbers, got " + describe(j));
    return {number(j[0], element(path, 0)), number(j[1], element(path, 1)),
            number(j[2], element(path, 2))};
}

// A vector already unit to rounding is kept as it is, so a saved scene loads back bit for bit
// (dividing by a length of 1 − 1e-16 would move the last bit each time). d is finite, non-zero.
glm::dvec3 unitKeepingBits(const glm::dvec3& d) {
    const double len = glm::length(d);
    if (std::abs(len - 1) <= 4 * std::numeric_limits<double>::epsilon()) return d;
    return d / len;
}

glm::dvec3 SceneReader::direction(const Json& j, const std::string& path) const {
    const glm::dvec3 d = vec3(j, path);
    const double len = glm::length(d);
    if (!(len > 1e-12) || !std::isfinite(len)) fail(path, "must be a non-zero direction");
    return unitKeepingBits(d);
}

const Json& SceneReader::required(const Json& obj, const std::string& key,
                                  const std::string& path) const {
    if (!obj.contains(key)) fail(child(path, key), "required key is missing");
    return obj.at(key);
}

double physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? double(pages) * double(pageSize) : 8e9;
}

void SceneReader::readCloth(const Json& j, ClothSpec& cloth) const {
    expectObject(j, "cloth", {"resolution", "size", "origin", "u_axis", "v_axis", "mass"});
    const Json& res = required(j, "resolution", "cloth");
    if (!res.is_array() || res.size() != 2)
        fail("cloth.resolution", "expected an array of 2 integers [nu, nv], got " + describe(res));
    cloth.nu = integer(res[0], "cloth.resolution[0]");
    cloth.nv = integer(res[1], "cloth.resolution[1]");
    if (cloth.nu < 1 || cloth.nv < 1) fail("cloth.resolution", "each side must be >= 1");
    const double vertices = double(cloth.nu) * double(cloth.nv);
    if (vertices < 2) fail("cloth.resolution", "a cloth needs at least 2 vertices");
    // Refused before anything is allocated (the whole point of checking here).
    const double need = vertices * kBytesPerVertex, have = physicalMemoryBytes();
    if (need > have) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "%d x %d = %.3g vertices need about %.3g GB, more than this machine's "
                      "%.3g GB of memory",
                      cloth.nu, cloth.nv, vertices, need / 1e9, have / 1e9);
        fail("cloth.resolution", buf);
    }
    const Json& size = required(j, "size", "cloth");
    if (!size.is_array() || size.size() != 2)
        fail("cloth.size",
             "expected an array of 2 numbers [size_u, size_v], got " + describe(size));
    cloth.size = {number(size[0], "cloth.size[0]"), number(size[1], "cloth.size[1]")};
    if (!(cloth.size.x > 0) || !(cloth.size.y > 0)) fail("cloth.size", "both sizes must be > 0 m");
    if (j.contains("origin")) cloth.origin = vec3(j["origin"], "cloth.origin");
    if (j.contains("u_axis")) cloth.uAxis = direction(j["u_axis"], "cloth.u_axis");
    if (j.contains("v_axis")) cloth.vAxis = direction(j["v_axis"], "cloth.v_axis");
    if (glm::length(glm::cross(cloth.uAxis, cloth.vAxis)) < 1e-6)
        fail("cloth.v_axis", "is parallel to cloth.u_axis; the axes must span a plane");
    cloth.mass = param(j, "mass", "cloth.mass", "cloth.mass", cloth.mass);
}

void SceneReader::readSprings(const Json& j, SpringStiffness& springs) const {
    expectObject(j, "springs", {"structural", "shear", "bend"});
    springs.structural = param(j, "structural", "springs.structural", "springs.structural", 0);
    springs.shear = param(j, "shear", "springs.shear", "springs.shear", 0);
    springs.bend = param(j, "bend", "springs.bend", "springs.bend", 0);
}

void SceneReader::readIntegrator(const Json& j, IntegratorSpec& integrator) const {
    expectObject(j, "integrator", {"method", "dt", "substeps", "tolerance", "max_iterations"});
    if (j.contains("method")) {
        const Json& m = j["method"];
        if (!m.is_string()) fail("integrator.method", "expected a string, got " + describe(m));
        const std::optional<Method> method = methodFromName(m.get<std::string>());
        if (!method)
            fail("integrator.method",
                 "unknown method \"" + m.get<std::string>() + "\"; known: " + methodList());
        integrator.method = *method;
    }
    integrator.tolerance =
        param(j, "tolerance", "integrator.tolerance", "integrator.tolerance", integrator.tolerance);
    integrator.maxIterations = int(param(j, "max_iterations", "integrator.max_iterations",
                                         "integrator.max_iterations", integrator.maxIterations));
    required(j, "dt", "integrator");
    integrator.dt = param(j, "dt", "integrator.dt", "integrator.dt", 0);
    integrator.substeps =
        int(param(j, "substeps", "integrator.substeps", "integrator.substeps", 1));
}

std::vector<Pin> SceneReader::readPins(const Json& j, const ClothSpec& cloth) const {
    if (!j.is_array()) fail("pins", "expected an array of [i, j] pairs, got " + describe(j));
    std::vector<Pin> pins;
    std::set<std::pair<int, int>> seen;
    for (size_t n = 0; n < j.size(); ++n) {
        const std::string path = element("pins", n);
        const Json& p = j[n];
        if (!p.is_array() || p.size() != 2)
            fail(path, "expected a pair [i, j] of grid indices, got " + describe(p));
        int i = integer(p[0], element(path, 0)), jj = integer(p[1], element(path, 1));
        const int ri = i < 0 ? i + cloth.nu : i, rj = jj < 0 ? jj + cloth.nv : jj;
        if (ri < 0 || ri >= cloth.nu || rj < 0 || rj >= cloth.nv) {
            fail(path, "[" + std::to_string(i) + ", " + std::to_string(jj) + "] is outside the " +
                           std::to_string(cloth.nu) + " x " + std::to_string(cloth.nv) +
                           " grid (negative indices count from -1 = last)");
        }
        if (!seen.insert({ri, rj}).second)
            fail(path, "pins vertex (" + std::to_string(ri) + ", " + std::to_string(rj) +
                           ") a second time");
        pins.push_back({ri, rj});
    }
    return pins;
}

// The keys every collider type takes besides its shape's (docs/colliders.md §5).
constexpr const char* kContactKeys[] = {"type", "thickness", "friction", "motion"};

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
        required(j, "radius", path);
        sphere.radius = param(j, "radius", child(path, "radius"), "colliders[].radius", 0);
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

Wind SceneReader::readWind(const Json& j) const {
    expectObject(j, "wind", {"direction", "strength"});
    Wind wind;
    wind.direction = direction(required(j, "direction", "wind"), "wind.direction");
    required(j, "strength", "wind");
    wind.strength = param(j, "strength", "wind.strength", "wind.strength", 0);
    return wind;
}

Scene SceneReader::read(const Json& doc) {
    expectObject(doc, "",
                 {"name", "cloth", "springs", "damping", "gravity", "pins", "integrator",
                  "colliders", "wind", "max_speed", "duration"});
    Scene scene;
    scene.source = source_;
    scene.name = std::filesystem::path(source_).stem().string();
    if (doc.contains("name")) {
        if (!doc["name"].is_string())
            fail("name", "expected a string, got " + describe(doc["name"]));
        scene.name = doc["name"].get<std::string>();
    }
    readCloth(required(doc, "cloth", ""), scene.cloth);
    if (doc.contains("springs")) readSprings(doc["springs"], scene.springs);
    scene.damping = param(doc, "damping", "damping", "damping", 0);
    if (doc.contains("gravity")) scene.gravity = vec3(doc["gravity"], "gravity");
    if (doc.contains("pins")) scene.pins = readPins(doc["pins"], scene.cloth);
    readIntegrator(required(doc, "integrator", ""), scene.integrator);
    if (doc.contains("colliders")) {
        const Json& list = doc["colliders"];
        if (!list.is_array()) fail("colliders", "expected an array, got " + describe(list));
        for (size_t n = 0; n < list.size(); ++n)
            scene.colliders.push_back(readCollider(list[n], element("colliders", n)));
    }
    if (doc.contains("wind")) scene.wind = readWind(doc["wind"]);
    scene.maxSpeed = param(doc, "max_speed", "max_speed", "max_speed", scene.maxSpeed);
    scene.duration = param(doc, "duration", "duration", "duration", scene.duration);
    if (scene.duration / scene.integrator.dt > 1e12)
        fail("duration", "needs more than 1e12 steps of integrator.dt");
    return scene;
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides) {
    Json doc = parseSceneText(text, source);
    std::vector<std::string> keys;
    for (const std::string& o : overrides) keys.push_back(applyOverride(doc, o, source));
    try {
        return SceneReader(source).read(doc);
    } catch (const InputError& e) {
        for (const std::string& k : keys)
            if (e.key().rfind(k, 0) == 0 || k.rfind(e.key(), 0) == 0)
                throw InputError(e.file(), e.key(), e.reason() + " (set by --set " + k + ")");
        throw;
    }
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw InputError(path, "", "no such file");
    if (fs::is_directory(st)) throw InputError(path, "", "is a directory, not a scene file");
    if (!fs::is_regular_file(st)) throw InputError(path, "", "is not a regular file");
    const auto bytes = fs::file_size(path, ec);
    if (!ec && bytes > (64u << 20)) throw InputError(path, "", "is larger than 64 MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "", "cannot be opened for reading");
    std::ostringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), path, overrides);
}

}  // namespace cloth
