// Where a scene's collider is at time t: its rest shape (the scene's, at t = 0) moved by its
// motion's pose (model/collider_motion.h), then translated by the viewer's drag when it has one
// (Solver::setColliderDrag, docs/colliders.md §3). Shared by the CPU solver, which poses the
// colliders every step, and the renderer and the viewer's picking, which pose them per frame at
// the solver's time.
#pragma once

#include <glm/glm.hpp>
#include <variant>

#include "model/collider_motion.h"
#include "model/collider_shapes.h"
#include "model/mesh_sdf.h"
#include "model/scene.h"

namespace cloth {

// The displacement the viewer's drag adds on top of a collider's own motion: offset +
// velocity·(t − since), its surface moving at `velocity` more.
struct ColliderDrag {
    glm::dvec3 offset{0};    // [m] at t = since
    glm::dvec3 velocity{0};  // [m/s]
    double since = 0;        // [s] the solver's time when the drag was set
    glm::dvec3 at(double t) const { return offset + velocity * (t - since); }
};

// The scene's shapes in the form the contact code takes, at their rest pose.
using ShapeD = std::variant<PlaneT<double>, SphereT<double>, BoxT<double>, CapsuleT<double>,
                            SdfColliderT<double>>;

inline ShapeD restShape(const ColliderShape& shape) {
    if (const Plane* p = std::get_if<Plane>(&shape)) return PlaneT<double>{p->point, p->normal};
    if (const Sphere* s = std::get_if<Sphere>(&shape)) return SphereT<double>{s->center, s->radius};
    if (const Box* b = std::get_if<Box>(&shape))
        return BoxT<double>{b->center, b->halfExtents, b->rotation.matrix()};
    if (const Capsule* c = std::get_if<Capsule>(&shape))
        return CapsuleT<double>{c->a, c->b, c->radius};
    const MeshCollider& m = std::get<MeshCollider>(shape);
    return SdfColliderT<double>{&m.baked->grid, m.rotation.matrix(), m.translation};
}

// The rigid pose at time t [s]: the motion's (identity without one), then the drag's translation.
inline Pose colliderPose(const Collider& c, double t, const ColliderDrag* drag = nullptr) {
    Pose q = c.motion ? poseAt(c.motion->motion(), t) : Pose{};
    if (drag != nullptr) q.translation += drag->at(t);
    return q;
}

// The velocity field of colliderPose's motion at time t: the motion's, plus the drag's velocity.
inline RigidVelocity colliderVelocity(const Collider& c, double t,
                                      const ColliderDrag* drag = nullptr) {
    RigidVelocity v = c.motion ? velocityAt(c.motion->motion(), t) : RigidVelocity{};
    if (drag != nullptr) v.linear += drag->velocity;
    return v;
}

// The collider's shape at time t.
inline ShapeD posedShape(const Collider& c, double t, const ColliderDrag* drag = nullptr) {
    const Pose q = colliderPose(c, t, drag);
    return std::visit([&](const auto& s) { return ShapeD(moved(s, q)); }, restShape(c.shape));
}

}  // namespace cloth
