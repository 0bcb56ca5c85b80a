// Collision response of DESIGN.md §2: project the vertex out, cancel the normal velocity.
#pragma once

#include "model/grid.h"

namespace cloth {

template <typename T>
struct PlaneT {
    Vec3<T> point, normal;  // unit normal
};
template <typename T>
struct SphereT {
    Vec3<T> center;
    T radius;
};

// Seed Q12: s = ⟨p − c, n̂⟩; below the plane, p ← p − s n̂ and v ← v − ⟨v, n̂⟩ n̂.
template <typename T>
void collide(const PlaneT<T>& plane, Vec3<T>& p, Vec3<T>& v) {
    const T s = glm::dot(p - plane.point, plane.normal);
    if (s < T(0)) {
        p -= s * plane.normal;
        v -= glm::dot(v, plane.normal) * plane.normal;
    }
}

// Seed Q13: inside the sphere, p ← c + R n̂ and v ← v − ⟨v, n̂⟩ n̂, n̂ = (p − c)/|p − c|
// ((0, 1, 0) at the very centre): the cloth slides on the surface.
template <typename T>
void collide(const SphereT<T>& sphere, Vec3<T>& p, Vec3<T>& v) {
    const Vec3<T> r = p - sphere.center;
    const T len = glm::length(r);
    if (len < sphere.radius) {
        const Vec3<T> n = len > T(0) ? r / len : Vec3<T>(0, 1, 0);
        p = sphere.center + sphere.radius * n;
        v -= glm::dot(v, n) * n;
    }
}

}  // namespace cloth
