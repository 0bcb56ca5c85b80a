#include "scene/scene_loader.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "model/collider_limits.h"
#include "model/errors.h"
#include "model/machine_memory.h"
#include "model/material_presets.h"
#include "model/output_file.h"
#include "model/pin_follow.h"
#include "scene/key_path.h"
#include "scene/params.h"
#include "scene/scene_overrides.h"
#include "scene/scene_reader.h"
#include "scene/scene_text.h"

namespace cloth {
namespace detail {

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

// The row of scene/params.cpp gives the range, the default and whether the key is required.
double SceneReader::param(const Json& obj, const std::string& key, const std::string& path,
                          const char* specPath) const {
    const ParamSpec& spec = paramSpec(specPath);
    if (!obj.contains(key)) {
        if (spec.required) fail(path, "required key is missing");
        return spec.defaultValue;
    }
    const double x = number(obj.at(key), path);
    const std::string why = checkRange(spec, x);
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
    cloth.mass = param(j, "mass", "cloth.mass", "cloth.mass");
}

void SceneReader::readSprings(const Json& j, SpringStiffness& springs) const {
    expectObject(j, "springs", {"structural", "shear", "bend"});
    springs.structural = param(j, "structural", "springs.structural", "springs.structural");
    springs.shear = param(j, "shear", "springs.shear", "springs.shear");
    springs.bend = param(j, "bend", "springs.bend", "springs.bend");
}

// docs/physics.md "Materials": a preset, each key given overriding it; without a preset,
// density, stretch and shear are required.
Material SceneReader::readMaterial(const Json& j) const {
    expectObject(
        j, "material",
        {"preset", "density", "stretch", "shear", "bend", "air_damping", "spring_damping"});
    Material m;
    if (j.contains("preset")) {
        const Json& name = j["preset"];
        if (!name.is_string()) fail("material.preset", "expected a string, got " + describe(name));
        const std::optional<Material> preset = materialPreset(name.get<std::string>());
        if (!preset)
            fail("material.preset", "unknown preset \"" + name.get<std::string>() +
                                        "\"; known: " + materialPresetList());
        m = *preset;
    }
    auto read = [&](const char* key, double& value) {
        const std::string path = std::string("material.") + key;
        if (m.preset.empty() || j.contains(key)) value = param(j, key, path, path.c_str());
    };
    read("density", m.density);
    read("stretch", m.stretch);
    read("shear", m.shear);
    read("bend", m.bend);
    read("air_damping", m.airDamping);
    read("spring_damping", m.springDamping);
    return m;
}

void SceneReader::readIntegrator(const Json& j, IntegratorSpec& integrator) const {
    expectObject(j, "integrator",
                 {"method", "dt", "substeps", "tolerance", "max_iterations", "preconditioner",
                  "iterations", "chebyshev_rho", "translation_sweeps", "translation_levels",
                  "translation_level_passes", "translation_block_width", "max_step_strain"});
    if (j.contains("method")) {
        const Json& m = j["method"];
        if (!m.is_string()) fail("integrator.method", "expected a string, got " + describe(m));
        const std::optional<Method> method = methodFromName(m.get<std::string>());
        if (!method)
            fail("integrator.method",
                 "unknown method \"" + m.get<std::string>() + "\"; known: " + methodList());
        integrator.method = *method;
    }
    if (j.contains("preconditioner")) {
        const Json& p = j["preconditioner"];
        if (!p.is_string())
            fail("integrator.preconditioner", "expected a string, got " + describe(p));
        const std::optional<Preconditioner> preconditioner =
            preconditionerFromName(p.get<std::string>());
        if (!preconditioner)
            fail("integrator.preconditioner", "unknown preconditioner \"" + p.get<std::string>() +
                                                  "\"; known: none, jacobi, multigrid");
        integrator.preconditioner = *preconditioner;
    }
    // Every scalar key here is "integrator.<key>" in the parameter table.
    const auto number = [&](const char* key) {
        const std::string path = std::string("integrator.") + key;
        return param(j, key, path, path.c_str());
    };
    integrator.tolerance = number("tolerance");
    integrator.maxIterations = int(number("max_iterations"));
    integrator.dt = number("dt");
    integrator.substeps = int(number("substeps"));
    integrator.iterations = int(number("iterations"));
    integrator.chebyshevRho = number("chebyshev_rho");
    integrator.translationSweeps = int(number("translation_sweeps"));
    integrator.translationLevels = int(number("translation_levels"));
    integrator.translationLevelPasses = int(number("translation_level_passes"));
    integrator.translationBlockWidth = int(number("translation_block_width"));
    integrator.maxStepStrain = number("max_step_strain");
}

// A pin is [i, j], or {"at": [i, j], "follow": n} to follow colliders[n] (checked once the
// colliders are read: checkFollowPins).
std::vector<Pin> SceneReader::readPins(const Json& j, const ClothSpec& cloth) const {
    if (!j.is_array())
        fail("pins", "expected an array of [i, j] pairs or {\"at\": [i, j], \"follow\": n}, got " +
                         describe(j));
    std::vector<Pin> pins;
    std::set<std::pair<int, int>> seen;
    for (size_t n = 0; n < j.size(); ++n) {
        std::string path = element("pins", n);
        const Json* p = &j[n];
        int follow = -1;
        if (p->is_object()) {
            expectObject(*p, path, {"at", "follow"});
            if (p->contains("follow")) {
                follow = integer((*p)["follow"], child(path, "follow"));
                if (follow < 0) fail(child(path, "follow"), "must be a collider index >= 0");
            }
            p = &required(*p, "at", path);
            path = child(path, "at");
        }
        if (!p->is_array() || p->size() != 2)
            fail(path, "expected a pair [i, j] of grid indices, got " + describe(*p));
        int i = integer((*p)[0], element(path, 0)), jj = integer((*p)[1], element(path, 1));
        const int ri = i < 0 ? i + cloth.nu : i, rj = jj < 0 ? jj + cloth.nv : jj;
        if (ri < 0 || ri >= cloth.nu || rj < 0 || rj >= cloth.nv) {
            fail(path, "[" + std::to_string(i) + ", " + std::to_string(jj) + "] is outside the " +
                           std::to_string(cloth.nu) + " x " + std::to_string(cloth.nv) +
                           " grid (negative indices count from -1 = last)");
        }
        if (!seen.insert({ri, rj}).second)
            fail(path, "pins vertex (" + std::to_string(ri) + ", " + std::to_string(rj) +
                           ") a second time");
        pins.push_back({ri, rj, follow});
    }
    return pins;
}

Wind SceneReader::readWind(const Json& j) const {
    expectObject(j, "wind", {"direction", "strength"});
    Wind wind;
    wind.direction = direction(required(j, "direction", "wind"), "wind.direction");
    wind.strength = param(j, "strength", "wind.strength", "wind.strength");
    return wind;
}

// docs/physics.md "Self-collision": a sheet whose elements beyond two rings of each other are
// further apart at rest than the thickness, or its rest state would already be in contact.
SelfCollision SceneReader::readSelfCollision(const Json& j, const ClothSpec& cloth) const {
    expectObject(j, "self_collision", {"thickness", "friction"});
    if (cloth.nu < 2 || cloth.nv < 2)
        fail("self_collision", "needs a sheet of at least 2 x 2 vertices (a chain has no faces)");
    SelfCollision self;
    self.thickness = param(j, "thickness", "self_collision.thickness", "self_collision.thickness");
    self.friction = param(j, "friction", "self_collision.friction", "self_collision.friction");
    const double cell = std::min(cloth.size.x / (cloth.nu - 1), cloth.size.y / (cloth.nv - 1));
    if (!(self.thickness < cell)) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "%g m is not below the grid's cell size %g m: the sheet at rest would "
                      "already be in contact with itself",
                      self.thickness, cell);
        fail("self_collision.thickness", buf);
    }
    return self;
}

Scene SceneReader::read(const Json& doc) {
    expectObject(
        doc, "",
        {"name", "cloth", "material", "springs", "damping", "gravity", "pins", "integrator",
         "colliders", "wind", "self_collision", "max_speed", "max_strain", "duration"});
    Scene scene;
    scene.source = source_;
    scene.name = std::filesystem::path(source_).stem().string();
    if (doc.contains("name")) {
        if (!doc["name"].is_string())
            fail("name", "expected a string, got " + describe(doc["name"]));
        scene.name = doc["name"].get<std::string>();
        if (!isFileNamePart(scene.name))  // it names the --frames files and the OBJ's object
            fail("name", "names files: 1-200 bytes, no '/', '\\' or control characters; got " +
                             describe(doc["name"]));
    }
    readCloth(required(doc, "cloth", ""), scene.cloth);
    if (doc.contains("material")) {
        // One form or the other: a material's masses and springs replace the per-vertex keys.
        const Json& cloth = doc["cloth"];
        for (const char* key : {"springs", "damping"})
            if (doc.contains(key))
                fail(key, std::string("a scene gives either material or the per-vertex form "
                                      "(cloth.mass, springs, damping), not both: remove ") +
                              key + " or material");
        if (cloth.contains("mass"))
            fail("cloth.mass",
                 "a scene gives either material or the per-vertex form (cloth.mass, springs, "
                 "damping), not both: remove cloth.mass or material");
        if (scene.cloth.nu < 2 || scene.cloth.nv < 2)
            fail("material",
                 "a material needs a sheet of at least 2 x 2 vertices; a single "
                 "spring or a chain keeps the per-vertex form (cloth.mass, springs)");
        scene.material = readMaterial(doc["material"]);
    } else {
        if (doc.contains("springs")) readSprings(doc["springs"], scene.springs);
        scene.damping = param(doc, "damping", "damping", "damping");
    }
    if (doc.contains("gravity")) scene.gravity = vec3(doc["gravity"], "gravity");
    if (doc.contains("pins")) scene.pins = readPins(doc["pins"], scene.cloth);
    readIntegrator(required(doc, "integrator", ""), scene.integrator);
    if (doc.contains("colliders")) {
        const Json& list = doc["colliders"];
        if (!list.is_array()) fail("colliders", "expected an array, got " + describe(list));
        for (size_t n = 0; n < list.size(); ++n)
            scene.colliders.push_back(readCollider(list[n], element("colliders", n)));
    }
    checkFollowPins(scene);
    checkColliderMotionStep(scene);  // docs/colliders.md §7: no collider outruns the limit
    if (doc.contains("wind")) scene.wind = readWind(doc["wind"]);
    if (doc.contains("self_collision"))
        scene.selfCollision = readSelfCollision(doc["self_collision"], scene.cloth);
    scene.maxSpeed = param(doc, "max_speed", "max_speed", "max_speed");
    scene.maxStrain = param(doc, "max_strain", "max_strain", "max_strain");
    scene.duration = param(doc, "duration", "duration", "duration");
    checkDerivedFinite(scene);
    return scene;
}

}  // namespace detail

Scene parseScene(const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides) {
    detail::Json doc = parseSceneText(text, source);
    std::vector<std::string> keys;
    for (const std::string& o : overrides) keys.push_back(applyOverride(doc, o, source));
    try {
        return detail::SceneReader(source).read(doc);
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
