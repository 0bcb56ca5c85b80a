// implicit_euler's contacts inside the solve (docs/integrators.md, "Contact in the solve"):
// Baraff & Witkin's filter, with Coulomb friction as stick and slip. Before the solve, each free
// vertex's predicted end of step p* = x + h v + h² g (and v* = v + h g) goes through the scene's
// colliders, the same response as at the end of every step. A vertex the colliders push out by
// d ≠ 0 gets a constraint: its velocity change along n = d/|d| is fixed to
//
//   z = ⟨n, p' − x⟩/h − ⟨n, v⟩,   so that ⟨n, x + h (v + Δv)⟩ = ⟨n, p'⟩,
//
// the end of the step lands on the surface (p' the pushed prediction), and the conjugate
// gradient runs in the other two directions only: S = I − n nᵀ filters its residual, search
// directions and preconditioned residual. Friction depends on what the contact did in the last
// step, its grip:
//   - held (static friction held it): the tangential velocity is fixed too, to the collider's
//     surface velocity v_c; the filter is 0 and the solve leaves the vertex alone;
//   - sliding with the normal impulse J_n of the last solve: the colliders' Coulomb law with that
//     impulse takes at most c_f J_n from v*'s tangential momentum, an impulse in b (kinetic
//     friction, lagged one step);
//   - new: the same with the normal speed the response removes from v* (gravity's load).
// After the solve the constraint's impulse J = (A Δv)_k − b_k decides the next step: J_n ≤ 0
// lets go; a held vertex stays held while friction can supply its tangential impulse,
// |J_t| ≤ c_f J_n, and slides with J_n otherwise; a sliding one is held once its friction has
// stopped it (the response took the static branch, returning v_c). The friction that holds a sheet
// wrapped on a sphere is its own tension's, which no prediction from v* contains. c_f is the
// colliders': every friction test goes through their response (coulomb() below); v_c is theirs too.
// The colliders still act at the end of the step as for every scheme; after the solve the vertex
// ends on the surface, where that is a rounding-level correction.
// shaders/compute/solve_contact.glsl is the GPU's copy.
#pragma once

#include "model/grid.h"

namespace cloth {

template <typename T>
struct SolveContact {
    Vec3<T> normal{0};  // unit normal n; 0: no constraint
    T speed = 0;        // z = ⟨n, Δv⟩ [m/s]
    Vec3<T> hold{0};    // held: S (v_c − v), the tangential part of Δv [m/s]; else 0
    Vec3<T> load{0};    // b_k [kg m/s], for J = (A Δv)_k − b_k after the solve
    // Kept from step to step: 0 no contact in the last step; > 0 sliding, J_n of the last solve
    // [kg m/s]; < 0 held (−J_n).
    T grip = 0;
    bool held = false;   // the whole Δv is fixed (static friction)
    bool stuck = false;  // the friction in b stopped the slide: held in the next step
};

// S w = w − n ⟨n, w⟩: the part of w the solve may change (w itself where n = 0).
template <typename T>
Vec3<T> filterContact(const Vec3<T>& n, const Vec3<T>& w) {
    return w - n * glm::dot(n, w);
}

// The same for a contact: 0 where it is held.
template <typename T>
Vec3<T> filterContact(const SolveContact<T>& c, const Vec3<T>& w) {
    return c.held ? Vec3<T>(0) : filterContact(c.normal, w);
}

// The part of Δv a contact fixes: z n, and the tangential change of a held one.
template <typename T>
Vec3<T> fixedChange(const SolveContact<T>& c) {
    return c.speed * c.normal + c.hold;
}

// Coulomb's law of the colliders (collide(p, v), the end-of-step response in scene order) at
// the prediction p*, on a tangential velocity `slide` (⟨n, slide⟩ = 0) that approaches the
// surface at `approach` ≥ 0 [m/s]: the tangential velocity they leave, S v'. A first run finds
// the collider's normal velocity (the response leaves the normal velocity relative to it 0).
// The static branch returns the collider's v_c exactly.
template <typename T, typename Collide>
Vec3<T> coulomb(const Vec3<T>& pStar, const Vec3<T>& n, const Vec3<T>& slide, T approach,
                const Collide& collide) {
    Vec3<T> q = pStar, w = slide;
    collide(q, w);
    q = pStar;
    w = slide + (glm::dot(n, w) - approach) * n;
    collide(q, w);
    return filterContact(n, w);
}

// The constraint of a free vertex of mass m at (x, v) under gravity g for a step h, given its
// grip from the last step, the colliders as collide(p, v) and the velocity of the surface that
// touches p last as surface(p) (v_c; 0 for a still one). Returns the friction's velocity change
// (0 without contact, or held); the caller adds m times it to b and stores b in contact.load.
template <typename T, typename Collide, typename Surface>
Vec3<T> predictContact(const Vec3<T>& x, const Vec3<T>& v, const Vec3<T>& g, T h, T m,
                       const Collide& collide, const Surface& surface, SolveContact<T>& contact) {
    const T grip = contact.grip;
    contact = {};
    contact.grip = grip;
    const Vec3<T> vStar = v + h * g, pStar = x + h * vStar;
    Vec3<T> p = pStar, w = vStar;
    collide(p, w);
    const Vec3<T> d = p - pStar;
    const T length = glm::length(d);
    if (!(length > T(0))) return Vec3<T>(0);
    const Vec3<T> n = d / length;
    contact.normal = n;
    contact.speed = glm::dot(n, p - x) / h - glm::dot(n, v);
    const Vec3<T> slide = filterContact(n, vStar), still = filterContact(n, surface(pStar));
    if (grip < T(0)) {
        contact.held = true;
        contact.hold = still - filterContact(n, v);
        return Vec3<T>(0);
    }
    const Vec3<T> kept =
        grip > T(0) ? coulomb(pStar, n, slide, grip / m, collide) : filterContact(n, w);
    // Held next where the response took its static branch (which returns v_c exactly) and the
    // vertex did not already move with the surface.
    contact.stuck = kept == still && slide != still;
    return kept - slide;
}

// The grip for the next step of a contact whose solve ended with (A Δv)_k = `ap` (unfiltered),
// for a vertex of mass m that started the step at (x, v).
template <typename T, typename Collide>
T nextGrip(const SolveContact<T>& c, const Vec3<T>& x, const Vec3<T>& v, const Vec3<T>& g, T h, T m,
           const Vec3<T>& ap, const Collide& collide) {
    if (c.normal == Vec3<T>(0)) return T(0);
    const Vec3<T> impulse = ap - c.load;
    const T jn = glm::dot(c.normal, impulse);
    if (!(jn > T(0))) return T(0);  // the collider would pull: let go
    if (!c.held) return c.stuck ? -jn : jn;
    // Held: would Coulomb's law with J_n supply J_t? The response on the velocity the vertex
    // would have without J_t, at the approach J_n/m, removes all of J_t/m iff |J_t| ≤ c_f J_n.
    const Vec3<T> jt = filterContact(c.normal, impulse) / m;
    const Vec3<T> free = filterContact(c.normal, v) + c.hold - jt;
    const Vec3<T> kept = coulomb(x + h * (v + h * g), c.normal, free, jn / m, collide);
    return glm::length(kept - free) >= T(0.999) * glm::length(jt) ? -jn : jn;
}

// The velocity a contact leaves its vertex with after the solve, v_new = v + Δv, of a vertex
// that started the step at (x, v): less any normal part that takes it away from the surface
// faster than the surface moves (v_c = surface(p*)). The solve's z lands the end of the step on
// the surface; a vertex that started inside gets there at depth/h, and that is a position
// correction, kept as no velocity, as the explicit schemes' projection keeps none. A vertex the
// collider pushes moves with it: its normal part is v_c's and stays.
template <typename T, typename Surface>
Vec3<T> contactVelocity(const SolveContact<T>& c, const Vec3<T>& x, const Vec3<T>& v,
                        const Vec3<T>& g, T h, const Vec3<T>& vNew, const Surface& surface) {
    if (c.normal == Vec3<T>(0)) return vNew;
    const T away = glm::dot(c.normal, vNew - surface(x + h * (v + h * g)));
    return away > T(0) ? vNew - away * c.normal : vNew;
}

}  // namespace cloth
