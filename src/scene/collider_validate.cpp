#include "scene/collider_validate.h"

#include <cmath>
#include <filesystem>
#include <numbers>

#include "model/collider_shapes.h"
#include "model/errors.h"
#include "scene/key_path.h"

namespace cloth {
namespace {

[[noreturn]] void fail(const KeyRef& at, const std::string& reason) {
    throw InputError(at.file, at.key, reason);
}

KeyRef member(const KeyRef& at, const std::string& key) {
    return {at.file, child(at.key, key)};
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

glm::dvec3 checkFinite(const KeyRef& at, const glm::dvec3& v) {
    if (!finite(v)) fail(at, "every component must be a finite number");
    return v;
}

double checkRadius(const KeyRef& at, double radius) {
    if (!std::isfinite(radius) || !(radius > 0)) fail(at, "the radius must be > 0 (metres)");
    return radius;
}

glm::dvec3 checkHalfExtents(const KeyRef& at, const glm::dvec3& half) {
    if (!finite(half) || !(half.x > 0 && half.y > 0 && half.z > 0))
        fail(at, "every half extent must be > 0 (metres)");
    return half;
}

double checkThickness(const KeyRef& at, double thickness) {
    if (!std::isfinite(thickness) || !(thickness >= 0))
        fail(at, "the thickness must be ≥ 0 (metres)");
    return thickness;
}

double checkFriction(const KeyRef& at, double friction) {
    if (!std::isfinite(friction) || !(friction >= 0))
        fail(at, "the friction coefficient must be ≥ 0");
    return friction;
}

glm::dvec3 checkAxis(const KeyRef& at, const glm::dvec3& axis) {
    if (!finite(axis)) fail(at, "the axis must be finite");
    const double len = glm::length(axis);
    if (!(len > 1e-12)) fail(at, "the axis must not be zero");
    return axis / len;
}

glm::dmat3 checkRotation(const KeyRef& at, const glm::dvec3& axis, double degrees) {
    const glm::dvec3 unit = checkAxis(member(at, "axis"), axis);
    if (!std::isfinite(degrees)) fail(member(at, "degrees"), "the angle must be finite");
    return axisAngle(unit, degrees * std::numbers::pi / 180);
}

BakedMesh checkMeshCollider(const KeyRef& at, const std::string& objFile, double cell, double band,
                            double thickness) {
    namespace fs = std::filesystem;
    const KeyRef fileKey = member(at, "file");
    if (objFile.empty()) fail(fileKey, "the mesh file name is empty");
    fs::path path(objFile);
    if (path.is_relative() && !at.file.empty()) path = fs::path(at.file).parent_path() / path;
    if (!std::isfinite(cell) || !(cell > 0)) fail(member(at, "cell"), "the grid cell must be > 0");
    if (!std::isfinite(band) || !(band > 0)) fail(member(at, "band"), "the band must be > 0");
    if (!(thickness < band))
        fail(member(at, "thickness"), "the thickness must be smaller than the mesh's band");
    BakedMesh baked;
    baked.mesh = loadObjMesh(path.string(), {fileKey.file, fileKey.key});
    baked.grid = bakeSdf(baked.mesh, cell, band, {at.file, member(at, "cell").key});
    return baked;
}

Motion checkMotion(const KeyRef& at, const Motion& m) {
    Motion out = m;
    switch (m.type) {
        case MotionType::Still:
            break;
        case MotionType::Linear:
            checkFinite(member(at, "velocity"), m.velocity);
            break;
        case MotionType::Rotation:
            out.axis = checkAxis(member(at, "axis"), m.axis);
            checkFinite(member(at, "pivot"), m.pivot);
            if (!std::isfinite(m.angularSpeed))
                fail(member(at, "degrees_per_second"), "the angular speed must be finite");
            break;
        case MotionType::Oscillation:
            out.axis = checkAxis(member(at, "axis"), m.axis);
            if (!std::isfinite(m.amplitude)) fail(member(at, "amplitude"), "must be finite");
            if (!std::isfinite(m.frequency) || !(m.frequency >= 0))
                fail(member(at, "frequency"), "the frequency must be ≥ 0 (Hz)");
            if (!std::isfinite(m.phase)) fail(member(at, "phase_degrees"), "must be finite");
            break;
    }
    return out;
}

}  // namespace cloth
