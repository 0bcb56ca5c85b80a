// The per-vertex end of every integrator's update in the CPU backend: the acceleration, then
// pins and colliders (DESIGN.md §2), then the instability check. Shared by the CPU backend's
// step files (cpu_steps.cpp, cpu_implicit.cpp, cpu_forces.cpp, cpu_solver.cpp); included only
// by them.
#pragma once

#include <cmath>
#include <variant>

#include "cpu/cpu_solver.h"
#include "model/spring_math.h"

namespace cloth {

// a = F w_k − c v + g (model/spring_math.h accelerationComponent, component by component).
template <typename T>
inline Vec3<T> CpuSolver<T>::acceleration(std::int64_t k, const Vec3<T>& v) const {
    const Vec3<T> f = f_.get(k);
    const T w = inverseMass_[std::size_t(k)];
    Vec3<T> a;
    for (int c = 0; c < 3; ++c)
        a[c] = accelerationComponent(f[c], v[c], dampingRate_, w, gravity_[c]);
    return a;
}

// A pinned vertex goes back to its pin, at the pin's velocity (0, or a followed collider's).
template <typename T>
inline void CpuSolver<T>::applyPin(std::int64_t k, Vec3<T>& p, Vec3<T>& v) const {
    if (pinned_[k]) {
        p = pinPosition_[k];
        v = pinVelocity(k);
    }
}

// Pins, then colliders in scene order (DESIGN.md §2); stores the vertex.
template <typename T>
inline void CpuSolver<T>::constrain(std::int64_t k, Vec3<T>& p, Vec3<T>& v) {
    applyPin(k, p, v);
    applyColliders(p, v);
    x_.set(k, p);
    v_.set(k, v);
}

template <typename T>
inline void CpuSolver<T>::applyColliders(Vec3<T>& p, Vec3<T>& v) const {
    colliders_.apply(p, v);
}

// DESIGN.md §2's instability test on the stored vertex: true while stable; otherwise reported.
template <typename T>
inline bool CpuSolver<T>::checkStability(Band& band, std::int64_t k, const Vec3<T>& p,
                                         const Vec3<T>& v) const {
    if (!badVertex(p.x, p.y, p.z, v.x, v.y, v.z, maxSpeed2_)) return true;
    reportBad(band, k, p, glm::dot(v, v));
    return false;  // the rest of the band is not advanced: the run stops at this step
}

// The end of a step (shaders/compute/step_end.glsl's finishStep): the constraints, then the
// instability check.
template <typename T>
inline bool CpuSolver<T>::finishStep(Band& band, std::int64_t k, Vec3<T> p, Vec3<T> v) {
    constrain(k, p, v);
    return checkStability(band, k, p, v);
}

}  // namespace cloth
