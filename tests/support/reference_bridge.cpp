#include "support/reference_bridge.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "core/scene_loader.h"

namespace cloth {
namespace {

ref::V3 toV3(const glm::dvec3& v) {
    return {v.x, v.y, v.z};
}

ref::Collider toReference(const Collider& c) {
    ref::Collider out;
    std::visit(
        [&out](const auto& shape) {
            using T = std::decay_t<decltype(shape)>;
            if constexpr (std::is_same_v<T, Plane>) {
                out.plane = {toV3(shape.point), toV3(shape.normal)};
            } else {
                out.isSphere = true;
                out.sphere = {toV3(shape.center), shape.radius};
            }
        },
        c);
    return out;
}

ref::Method toReference(Method m) {
    switch (m) {
        case Method::ExplicitEuler:
            return ref::Method::ExplicitEuler;
        case Method::SymplecticEuler:
            return ref::Method::SymplecticEuler;
        case Method::Verlet:
            return ref::Method::Verlet;
        case Method::Rk4:
            return ref::Method::Rk4;
        case Method::ImplicitEuler:
            return ref::Method::ImplicitEuler;
    }
    return ref::Method::ExplicitEuler;
}

}  // namespace

ref::Params toReference(const Scene& scene) {
    ref::Params p;
    p.nu = scene.cloth.nu;
    p.nv = scene.cloth.nv;
    p.sizeU = scene.cloth.size.x;
    p.sizeV = scene.cloth.size.y;
    p.origin = toV3(scene.cloth.origin);
    p.uAxis = toV3(scene.cloth.uAxis);
    p.vAxis = toV3(scene.cloth.vAxis);
    p.mass = scene.cloth.mass;
    p.kStructural = scene.springs.structural;
    p.kShear = scene.springs.shear;
    p.kBend = scene.springs.bend;
    p.damping = scene.damping;
    p.gravity = toV3(scene.gravity);
    for (const Pin& pin : scene.pins) p.pins.push_back({pin.i, pin.j});
    if (scene.wind) {
        p.wind = true;
        p.windDirection = toV3(scene.wind->direction);
        p.windStrength = scene.wind->strength;
    }
    for (const Collider& c : scene.colliders) p.colliders.push_back(toReference(c));
    p.method = toReference(scene.integrator.method);
    p.dt = scene.integrator.dt;
    p.cgTolerance = scene.integrator.tolerance;
    p.cgMaxIterations = scene.integrator.maxIterations;
    p.maxSpeed = scene.maxSpeed;
    return p;
}

double maxDeviationOverExtent(const SimState& s, const ref::Simulation& r, double extent) {
    const std::vector<ref::V3>& q = r.positions();
    if (s.positions.size() != q.size()) return INFINITY;
    double worst = 0;
    for (std::size_t k = 0; k < q.size(); ++k) {
        const glm::dvec3 d = s.positions[k] - glm::dvec3(q[k][0], q[k][1], q[k][2]);
        const double dist = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        if (std::isnan(dist)) return NAN;  // a NaN never hides behind a max
        worst = std::max(worst, dist);
    }
    return worst / extent;
}

Scene loadShippedScene(const std::string& name) {
    return loadScene(std::string(CLOTH_SOURCE_DIR) + "/scenes/" + name + ".json");
}

std::vector<ref::V3> toReferenceVectors(const std::vector<glm::dvec3>& v) {
    std::vector<ref::V3> out(v.size());
    std::transform(v.begin(), v.end(), out.begin(), [](const glm::dvec3& x) { return toV3(x); });
    return out;
}

double totalEnergy(const ref::Simulation& model, const SimState& s) {
    const std::vector<ref::V3> p = toReferenceVectors(s.positions);
    return model.kineticEnergy(toReferenceVectors(s.velocities)) + model.springEnergy(p) +
           model.gravityEnergy(p);
}

}  // namespace cloth
