// implicit_euler's contacts inside the solve (docs/integrators.md, "Contact in the solve"):
// Baraff & Witkin's filter. Before the solve, each free vertex's predicted end of step
// p* = x + h v + h² g (and v* = v + h g) goes through the scene's colliders, the same response
// as at the end of every step. A vertex the colliders push out by d ≠ 0 gets a constraint: its
// velocity change along n = d/|d| is fixed to
//
//   z = ⟨n, p' − x⟩/h − ⟨n, v⟩,   so that ⟨n, x + h (v + Δv)⟩ = ⟨n, p'⟩,
//
// the end of the step lands on the surface (p' the pushed prediction), and the conjugate
// gradient runs in the other two directions only: S = I − n nᵀ filters its residual, search
// directions and preconditioned residual. The friction the response took from v*'s tangential
// part, S (v' − v*), enters the right-hand side as the impulse m S (v' − v*): Coulomb friction
// at the normal speed the contact removes (μ g h a step for a sheet resting on a floor). The
// colliders still act at the end of the step as for every scheme; after the solve the vertex
// ends on the surface, where that is a rounding-level correction.
// shaders/compute/solve_contact.glsl is the GPU's copy.
#pragma once

#include "model/grid.h"

namespace cloth {

template <typename T>
struct SolveContact {
    Vec3<T> normal{0};  // unit normal n; 0: no constraint
    T speed = 0;        // z = ⟨n, Δv⟩ [m/s]
};

// S w = w − n ⟨n, w⟩: the part of w the solve may change (w itself where n = 0).
template <typename T>
Vec3<T> filterContact(const Vec3<T>& n, const Vec3<T>& w) {
    return w - n * glm::dot(n, w);
}

// The constraint of a free vertex at (x, v) under gravity g for a step h, given the colliders as
// collide(p, v) (the end-of-step response, in scene order). Returns the friction's velocity
// change S (v' − v*), 0 without contact.
template <typename T, typename Collide>
Vec3<T> predictContact(const Vec3<T>& x, const Vec3<T>& v, const Vec3<T>& g, T h,
                       const Collide& collide, SolveContact<T>& contact) {
    const Vec3<T> vStar = v + h * g, pStar = x + h * vStar;
    Vec3<T> p = pStar, w = vStar;
    collide(p, w);
    const Vec3<T> d = p - pStar;
    const T length = glm::length(d);
    contact = {};
    if (!(length > T(0))) return Vec3<T>(0);
    contact.normal = d / length;
    contact.speed = glm::dot(contact.normal, p - x) / h - glm::dot(contact.normal, v);
    return filterContact(contact.normal, w - vStar);
}

}  // namespace cloth
