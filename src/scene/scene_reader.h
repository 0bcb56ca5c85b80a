// The scene reader shared by scene_loader.cpp (the cloth, springs, integrator, pins, wind) and
// scene_loader_colliders.cpp (docs/colliders.md §5): one JSON document into a Scene, naming
// the file and key path in every complaint. Internal to those two files.
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/errors.h"
#include "model/scene.h"

namespace cloth::detail {

using Json = nlohmann::json;

std::string describe(const Json& j);  // "the number 3", "an array of 2", ... for messages

// A vector already unit to rounding is kept as it is, so a saved scene loads back bit for bit
// (dividing by a length of 1 − 1e-16 would move the last bit each time). d is finite, non-zero.
glm::dvec3 unitKeepingBits(const glm::dvec3& d);

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
    // A scalar of scene/params.cpp's table: its row `spec` checks it and gives its default.
    double param(const Json& obj, const std::string& key, const std::string& path,
                 const char* spec) const;
    glm::dvec3 vec3(const Json& j, const std::string& path) const;
    glm::dvec3 direction(const Json& j, const std::string& path) const;
    int integer(const Json& j, const std::string& path) const;
    const Json& required(const Json& obj, const std::string& key, const std::string& path) const;

    void readCloth(const Json& j, ClothSpec& cloth) const;
    void readSprings(const Json& j, SpringStiffness& springs) const;
    Material readMaterial(const Json& j) const;
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
    SelfCollision readSelfCollision(const Json& j, const ClothSpec& cloth) const;
    void checkDerivedFinite(const Scene& scene) const;  // scene_loader_finite.cpp

    std::string source_;
};

}  // namespace cloth::detail
