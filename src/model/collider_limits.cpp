#include "model/collider_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "model/collider_speed.h"
#include "model/errors.h"
#include "model/mesh_sdf.h"

namespace cloth {
namespace {

std::string number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

// x > 0 rounded down to 4 significant digits: a bound that is printed still passes.
std::string below(double x) {
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 3);
    return number(std::floor(x / unit) * unit);
}

// What maxColliderStepTravel is made of, for messages.
std::string travelText(const Collider& c) {
    const char* what = c.as<Box>()            ? "its smallest half extent"
                       : c.as<MeshCollider>() ? "half its mesh's smallest extent"
                                              : "its radius";
    return std::string(what) + " + thickness " + number(c.thickness) + " m";
}

}  // namespace

double maxColliderStepTravel(const Collider& c) {
    const double h = c.thickness;
    if (c.as<Plane>() != nullptr) return std::numeric_limits<double>::infinity();
    if (const Sphere* s = c.as<Sphere>()) return s->radius + h;
    if (const Capsule* cap = c.as<Capsule>()) return cap->radius + h;
    if (const Box* b = c.as<Box>())
        return std::min({b->halfExtents.x, b->halfExtents.y, b->halfExtents.z}) + h;
    // The OBJ's own bounds (its frame; the grid around them is a band wider on every side).
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const glm::dvec3& v : std::get<MeshCollider>(c.shape).baked->mesh.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const glm::dvec3 extent = glm::max(hi - lo, glm::dvec3(0));
    return 0.5 * std::min({extent.x, extent.y, extent.z}) + h;
}

double motionStepMargin(const Collider& c, double dt) {
    // A plane (infinite travel) passes whatever its speed, even a turning one's infinite one.
    if (c.as<Plane>() != nullptr) return std::numeric_limits<double>::infinity();
    const double step = maxMotionSpeed(c) * dt;
    return step > 0 ? maxColliderStepTravel(c) / step : std::numeric_limits<double>::infinity();
}

void checkColliderMotionStep(const Scene& scene, const std::vector<bool>& on) {
    const double dt = scene.integrator.dt;
    for (std::size_t n = 0; n < scene.colliders.size(); ++n) {
        const Collider& c = scene.colliders[n];
        if ((n < on.size() && !on[n]) || !(motionStepMargin(c, dt) < 1)) continue;
        const double speed = maxMotionSpeed(c), limit = maxColliderStepTravel(c);
        throw InputError(
            scene.source, "colliders[" + std::to_string(n) + "].motion",
            "the collider's surface moves at up to " + number(speed) + " m/s, " +
                number(speed * dt) + " m in one step of integrator.dt = " + number(dt) +
                " s, more than the " + number(limit) + " m (" + travelText(c) +
                ") it may move per step without cloth tunnelling through it "
                "(docs/colliders.md §7); it passes with integrator.dt ≤ " +
                below(limit / speed) + " s or a motion of at most " + below(limit / dt) + " m/s");
    }
}

}  // namespace cloth
