// The per-vertex end of every integrator's update in the CPU backend: the acceleration, then
// pins and colliders (DESIGN.md §2), then the instability check. Shared by cpu_solver.cpp and
// cpu_implicit.cpp; included only by them.
#pragma once

#include <cmath>
#include <variant>

#include "model/spring_math.h"

#include "cpu/cpu_solver.h"

namespace cloth {

template <typename T>
inline Vec3<T> CpuSolver<T>::acceleration(std::int64_t k, const Vec3<T>& v) const {
    return (f_.get(k) - damping_ * v) * inverseMass_ + gravity_;
}

// Pins, then colliders in scene order (DESIGN.md §2); stores the vertex.
template <typename T>
inline void CpuSolver<T>::constrainVertex(std::int64_t k, Vec3<T>& p, Vec3<T>& v) {
    if (pinned_[k]) {
        p = pinPosition_[k];
        v = pinVelocity(k);
    }
    collideVertex(p, v);
    x_.set(k, p);
    v_.set(k, v);
}

template <typename T>
inline void CpuSolver<T>::collideVertex(Vec3<T>& p, Vec3<T>& v) const {
    colliders_.apply(p, v);
}

// The end of a step: the constraints, then the instability check.
template <typename T>
inline bool CpuSolver<T>::finishVertex(Band& band, std::int64_t k, Vec3<T> p, Vec3<T> v) {
    constrainVertex(k, p, v);
    if (!badVertex(p.x, p.y, p.z, v.x, v.y, v.z, maxSpeed2_)) return true;
    reportBad(band, k, p, glm::dot(v, v));
    return false;  // the rest of the band is not advanced: the run stops at this step
}

}  // namespace cloth
