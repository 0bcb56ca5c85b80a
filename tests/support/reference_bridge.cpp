#include "support/reference_bridge.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <variant>

#include "model/pin_follow.h"
#include "scene/collider_validate.h"
#include "scene/scene_loader.h"

namespace cloth {
namespace {

ref::V3 toV3(const glm::dvec3& v) {
    return {v.x, v.y, v.z};
}

ref::Motion toReference(const ColliderMotion& m) {
    ref::Motion r;
    switch (m.type) {
        case MotionType::Still:
            break;
        case MotionType::Linear:
            r.type = ref::Motion::Type::Linear;
            break;
        case MotionType::Rotation:
            r.type = ref::Motion::Type::Rotation;
            break;
        case MotionType::Oscillation:
            r.type = ref::Motion::Type::Oscillation;
            break;
    }
    r.velocity = toV3(m.velocity);
    r.axis = toV3(m.axis);
    r.pivot = toV3(m.pivot);
    r.degreesPerSecond = m.degreesPerSecond;
    r.amplitude = m.amplitude;
    r.frequency = m.frequency;
    r.phaseDegrees = m.phaseDegrees;
    return r;
}

// DESIGN.md §2's plane and sphere stay the reference's own §2 code; anything docs/colliders.md
// adds goes through ref::collideMoving. The mesh's baked grid is data, handed over as numbers.
ref::Collider toReference(const Collider& c) {
    ref::Collider out;
    out.extended = !c.plain() || !(c.as<Plane>() || c.as<Sphere>());
    out.thickness = c.thickness;
    out.friction = c.friction;
    if (c.motion) out.motion = toReference(*c.motion);
    if (const Plane* p = c.as<Plane>()) {
        out.plane = {toV3(p->point), toV3(p->normal)};
        out.shape = ref::Collider::Shape::Plane;
    } else if (const Sphere* s = c.as<Sphere>()) {
        out.isSphere = true;
        out.sphere = {toV3(s->center), s->radius};
        out.shape = ref::Collider::Shape::Sphere;
    } else if (const Box* b = c.as<Box>()) {
        out.box = {toV3(b->center), toV3(b->halfExtents), toV3(b->rotation.axis),
                   b->rotation.degrees};
        out.shape = ref::Collider::Shape::Box;
    } else if (const Capsule* cap = c.as<Capsule>()) {
        out.capsule = {toV3(cap->a), toV3(cap->b), cap->radius};
        out.shape = ref::Collider::Shape::Capsule;
    } else if (const MeshCollider* m = c.as<MeshCollider>()) {
        const SdfGrid& g = m->baked->grid;
        out.grid = {toV3(g.origin), g.cell, {g.count.x, g.count.y, g.count.z}, g.values};
        out.gridAxis = toV3(m->rotation.axis);
        out.gridDegrees = m->rotation.degrees;
        out.gridTranslation = toV3(m->translation);
        out.shape = ref::Collider::Shape::Grid;
    }
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
        case Method::Vbd:  // converged, vbd is backward Euler
            return ref::Method::BackwardEuler;
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
    if (scene.material) {
        // The reference lumps the masses from the density itself; the springs' constants are
        // the scene's mapping of the material (Scene::slotStiffness), slot by slot.
        p.density = scene.material->density;
        p.damping = 0;
        p.dampingRate = scene.dampingRate();
        p.springDamping = scene.springDamping();
        p.bend = scene.material->bend;
        p.cellShares = true;
        for (std::size_t s = 0; s < kSpringOffsets.size(); ++s)
            p.offsetStiffness.push_back(
                {kSpringOffsets[s].di, kSpringOffsets[s].dj, scene.slotStiffness(int(s))});
    }
    p.gravity = toV3(scene.gravity);
    for (const Pin& pin : scene.pins) {
        p.pins.push_back({pin.i, pin.j});
        p.pinFollow.push_back(follows(scene, pin) ? pin.follow : -1);  // as the solvers do
    }
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
