#include "model/collider_speed.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "model/mesh_sdf.h"

namespace cloth {

BoundingSphere boundingSphere(const Collider& c) {
    if (const Sphere* s = c.as<Sphere>()) return {s->center, s->radius};
    if (const Box* b = c.as<Box>()) return {b->center, glm::length(b->halfExtents)};
    if (const Capsule* k = c.as<Capsule>())
        return {0.5 * (k->a + k->b), 0.5 * glm::length(k->b - k->a) + k->radius};
    if (const MeshCollider* m = c.as<MeshCollider>()) {
        if (!m->baked || m->baked->mesh.vertices.empty()) return {m->translation, 0};
        const glm::dmat3 r = m->rotation.matrix();
        glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
        for (const glm::dvec3& v : m->baked->mesh.vertices) {
            const glm::dvec3 w = r * v + m->translation;
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
        BoundingSphere b{0.5 * (lo + hi), 0};
        for (const glm::dvec3& v : m->baked->mesh.vertices)
            b.radius = std::max(b.radius, glm::length(r * v + m->translation - b.center));
        return b;
    }
    return {std::get<Plane>(c.shape).point, std::numeric_limits<double>::infinity()};
}

double maxMotionSpeed(const Collider& c) {
    if (!c.motion) return 0;
    const ColliderMotion& m = *c.motion;
    switch (m.type) {
        case MotionType::Still:
            return 0;
        case MotionType::Linear:
            return glm::length(m.velocity);
        case MotionType::Oscillation:
            return 2 * std::numbers::pi * m.frequency * std::abs(m.amplitude);
        case MotionType::Rotation: {
            const double omega = std::abs(m.degreesPerSecond) * std::numbers::pi / 180;
            if (omega == 0) return 0;
            const BoundingSphere b = boundingSphere(c);
            const glm::dvec3 a = glm::normalize(m.axis), r = b.center - m.pivot;
            const double fromAxis = glm::length(r - glm::dot(r, a) * a);
            return omega * (fromAxis + b.radius);
        }
    }
    return 0;
}

}  // namespace cloth
