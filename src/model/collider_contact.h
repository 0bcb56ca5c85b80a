// The contact response every collider shares (docs/colliders.md §2): push the vertex out to the
// thickness h, cancel the normal part of its velocity relative to the collider, and let Coulomb
// friction take at most c_f·|normal velocity removed| from the tangential part. With h = 0,
// c_f = 0 and a still collider it is DESIGN.md §2's rule, bit for bit (model/colliders.h).
#pragma once

#include <cmath>

#include "model/collider_shapes.h"
#include "model/colliders.h"
#include "model/contact_math.h"

namespace cloth {

template <typename T>
struct ContactParamsT {
    T thickness = 0;  // h: the cloth stops at φ = h [m], ≥ 0
    T friction = 0;   // c_f: Coulomb coefficient, ≥ 0 (dimensionless)
};

// The velocity part, for a vertex in contact with normal n and a collider whose surface moves at
// v_c there: w = v − v_c, w_n = ⟨w, n⟩ n is removed; w_t = w − w_n keeps
// max(0, 1 − c_f |⟨w, n⟩| / |w_t|) of itself; v ← v_c + w_t'. Computed as v − w_n − (lost part
// of w_t), which is the same number in exact arithmetic and the seed's v − ⟨v, n⟩ n in floating
// point when v_c = 0 and c_f = 0. Static friction sets v = v_c exactly.
//
// The arithmetic is model/contact_math.h's respondVelocityLane, which the row kernels share.
template <typename T>
void respondVelocity(Vec3<T>& v, const Vec3<T>& n, const Vec3<T>& vc, T friction) {
    if (friction > T(0))
        respondVelocityLane<T, true>(v.x, v.y, v.z, n.x, n.y, n.z, vc.x, vc.y, vc.z, friction);
    else
        respondVelocityLane<T, false>(v.x, v.y, v.z, n.x, n.y, n.z, vc.x, vc.y, vc.z, friction);
}

// Where the response puts a vertex at p against a contact (φ, n): if φ < h, p ← p + (h − φ) n.
// Returns whether it touched. The sphere's puts it on the shell (below).
template <typename T>
bool pushOut(const ContactT<T>& c, const ContactParamsT<T>& params, Vec3<T>& p) {
    if (!(c.phi < params.thickness)) return false;
    p += (params.thickness - c.phi) * c.normal;
    return true;
}

// The sphere places the vertex at c + (R + h) n, on the shell to rounding, rather than adding
// (h − φ) n (which would differ from DESIGN.md §2's c + R n in the last bits).
template <typename T>
bool pushOut(const SphereT<T>& sphere, const ContactT<T>& c, const ContactParamsT<T>& params,
             Vec3<T>& p) {
    if (!(c.phi < params.thickness)) return false;
    p = sphere.center + (sphere.radius + params.thickness) * c.normal;
    return true;
}

// The position part alone of collide() below: p pushed out as collide() pushes it.
template <typename T, typename Shape>
bool collidePosition(const Shape& shape, const ContactParamsT<T>& params, Vec3<T>& p) {
    return pushOut(contact(shape, p), params, p);
}
template <typename T>
bool collidePosition(const SphereT<T>& sphere, const ContactParamsT<T>& params, Vec3<T>& p) {
    return pushOut(sphere, contact(sphere, p), params, p);
}

// The whole response for a vertex at (p, v) against a contact (φ, n) of a collider moving at v_c:
// p pushed out (pushOut) and the velocity filtered as above. Returns whether it touched.
template <typename T>
bool respond(const ContactT<T>& c, const ContactParamsT<T>& params, const Vec3<T>& vc, Vec3<T>& p,
             Vec3<T>& v) {
    if (!pushOut(c, params, p)) return false;
    respondVelocity(v, c.normal, vc, params.friction);
    return true;
}

// Plane, box, capsule, grid: the generic response above.
template <typename T, typename Shape>
bool collide(const Shape& shape, const ContactParamsT<T>& params, const Vec3<T>& vc, Vec3<T>& p,
             Vec3<T>& v) {
    return respond(contact(shape, p), params, vc, p, v);
}

template <typename T>
bool collide(const SphereT<T>& sphere, const ContactParamsT<T>& params, const Vec3<T>& vc,
             Vec3<T>& p, Vec3<T>& v) {
    const ContactT<T> c = contact(sphere, p);
    if (!pushOut(sphere, c, params, p)) return false;
    respondVelocity(v, c.normal, vc, params.friction);
    return true;
}

}  // namespace cloth
