// Moving colliders (docs/colliders.md §3): a motion gives the collider's rigid pose at time t in
// closed form, x(t) = R(t)·x₀ + T(t) for a point x₀ of the collider at t = 0, and the velocity
// of any point attached to it, v_c(p) = v_lin + ω × (p − o) (o a point on the rotation axis).
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <numbers>

#include "model/collider_shapes.h"

namespace cloth {

enum class MotionType { Still, Linear, Rotation, Oscillation };

struct Motion {
    MotionType type = MotionType::Still;
    glm::dvec3 velocity{0};    // linear: constant velocity [m/s]
    glm::dvec3 axis{0, 1, 0};  // rotation, oscillation: unit axis
    glm::dvec3 pivot{0};       // rotation: a point on the rotation axis [m]
    double angularSpeed = 0;   // rotation: [rad/s], right-handed about axis
    double amplitude = 0;      // oscillation: [m]
    double frequency = 0;      // oscillation: [Hz]
    double phase = 0;          // oscillation: [rad] at t = 0
};

struct Pose {
    glm::dmat3 rotation{1};
    glm::dvec3 translation{0};
    glm::dvec3 apply(const glm::dvec3& x0) const { return rotation * x0 + translation; }
};

// The velocity field of a rigid motion at one instant: v(p) = linear + angular × (p − origin).
struct RigidVelocity {
    glm::dvec3 linear{0}, angular{0}, origin{0};
    glm::dvec3 at(const glm::dvec3& p) const { return linear + glm::cross(angular, p - origin); }
};

// linear: T = v t. rotation: R = rot(axis, ω t), T = o − R o (the pivot o stays put).
// oscillation: T = A sin(2π f t + φ₀) â. (At t = 0 an oscillation is displaced by A sin φ₀.)
inline Pose poseAt(const Motion& m, double t) {
    Pose pose;
    switch (m.type) {
        case MotionType::Still:
            break;
        case MotionType::Linear:
            pose.translation = m.velocity * t;
            break;
        case MotionType::Rotation:
            pose.rotation = axisAngle(m.axis, m.angularSpeed * t);
            pose.translation = m.pivot - pose.rotation * m.pivot;
            break;
        case MotionType::Oscillation: {
            const double w = 2 * std::numbers::pi * m.frequency;
            pose.translation = m.amplitude * std::sin(w * t + m.phase) * m.axis;
            break;
        }
    }
    return pose;
}

// The time derivative of poseAt, as a velocity field.
inline RigidVelocity velocityAt(const Motion& m, double t) {
    RigidVelocity v;
    switch (m.type) {
        case MotionType::Still:
            break;
        case MotionType::Linear:
            v.linear = m.velocity;
            break;
        case MotionType::Rotation:
            v.angular = m.angularSpeed * m.axis;
            v.origin = m.pivot;
            break;
        case MotionType::Oscillation: {
            const double w = 2 * std::numbers::pi * m.frequency;
            v.linear = m.amplitude * w * std::cos(w * t + m.phase) * m.axis;
            break;
        }
    }
    return v;
}

// The shapes moved by a pose (their rest description is their pose at t = 0).
inline PlaneT<double> moved(const PlaneT<double>& s, const Pose& q) {
    return {q.apply(s.point), q.rotation * s.normal};
}
inline SphereT<double> moved(const SphereT<double>& s, const Pose& q) {
    return {q.apply(s.center), s.radius};
}
inline BoxT<double> moved(const BoxT<double>& s, const Pose& q) {
    return {q.apply(s.center), s.halfExtents, q.rotation * s.rotation};
}
inline CapsuleT<double> moved(const CapsuleT<double>& s, const Pose& q) {
    return {q.apply(s.a), q.apply(s.b), s.radius};
}
inline SdfColliderT<double> moved(const SdfColliderT<double>& s, const Pose& q) {
    return {s.grid, q.rotation * s.rotation, q.apply(s.translation)};
}

}  // namespace cloth
