// Signed distance φ(p) and outward unit normal n(p) of the colliders beyond plane and sphere
// (docs/colliders.md §1): the oriented box, the capsule and a baked signed-distance grid. Pure
// functions over T = float or double, shared by the CPU solver and mirrored by the GLSL shaders.
// Inside is negative; n is ∇φ normalised (for the box and capsule, ∇φ is already unit length).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "model/colliders.h"
#include "model/grid.h"

namespace cloth {

template <typename T>
using Mat3 = glm::mat<3, 3, T, glm::defaultp>;

// What a shape tells the contact response (model/collider_contact.h): φ [m] and the unit normal.
template <typename T>
struct ContactT {
    T phi;
    Vec3<T> normal;
};

// The rotation of angle `radians` about the unit `axis` (Rodrigues), as a matrix whose columns
// are the rotated x, y, z axes. The scene writes {"axis": [x, y, z], "degrees": a}.
template <typename T>
Mat3<T> axisAngle(const Vec3<T>& axis, T radians) {
    const T c = std::cos(radians), s = std::sin(radians), t = T(1) - c;
    const Vec3<T> a = axis;
    Mat3<T> r;  // glm is column-major: r[col][row]
    r[0] = Vec3<T>(t * a.x * a.x + c, t * a.x * a.y + s * a.z, t * a.x * a.z - s * a.y);
    r[1] = Vec3<T>(t * a.x * a.y - s * a.z, t * a.y * a.y + c, t * a.y * a.z + s * a.x);
    r[2] = Vec3<T>(t * a.x * a.z + s * a.y, t * a.y * a.z - s * a.x, t * a.z * a.z + c);
    return r;
}

// ---- plane and sphere: the rules of DESIGN.md §2 as (φ, n) -----------------------------------

template <typename T>
ContactT<T> contact(const PlaneT<T>& plane, const Vec3<T>& p) {
    return {glm::dot(p - plane.point, plane.normal), plane.normal};
}

// n = (p − c)/|p − c|, (0, 1, 0) at the very centre (DESIGN.md §2).
template <typename T>
ContactT<T> contact(const SphereT<T>& sphere, const Vec3<T>& p) {
    const Vec3<T> r = p - sphere.center;
    const T len = glm::length(r);
    return {len - sphere.radius, len > T(0) ? r / len : Vec3<T>(0, 1, 0)};
}

// ---- oriented box ----------------------------------------------------------------------------

template <typename T>
struct BoxT {
    Vec3<T> center;
    Vec3<T> halfExtents;  // > 0 [m]
    Mat3<T> rotation;     // local → world; columns are the box's axes
};

// The exact SDF of an oriented box. In the box frame q = Rᵀ(p − c), d = |q| − h componentwise:
// outside, φ = |max(d, 0)| and n = sign(q)·max(d, 0)/|max(d, 0)| (face, edge or corner region
// by how many d_i are positive); inside, φ = max_i d_i and n = sign(q_i) e_i of the nearest face
// (the first of equal ones, x before y before z). sign(0) is +1.
template <typename T>
ContactT<T> contact(const BoxT<T>& box, const Vec3<T>& p) {
    const Vec3<T> q = glm::transpose(box.rotation) * (p - box.center);
    const Vec3<T> sign(q.x < T(0) ? T(-1) : T(1), q.y < T(0) ? T(-1) : T(1),
                       q.z < T(0) ? T(-1) : T(1));
    const Vec3<T> d = glm::abs(q) - box.halfExtents;
    const Vec3<T> outside = glm::max(d, Vec3<T>(0));
    const T outLen = glm::length(outside);
    if (outLen > T(0)) return {outLen, box.rotation * (sign * outside / outLen)};
    int axis = 0;
    if (d.y > d[axis]) axis = 1;
    if (d.z > d[axis]) axis = 2;
    Vec3<T> n(0);
    n[axis] = sign[axis];
    return {d[axis], box.rotation * n};
}

// ---- capsule ---------------------------------------------------------------------------------

template <typename T>
struct CapsuleT {
    Vec3<T> a, b;  // end points of the axis segment [m]
    T radius;      // > 0 [m]
};

// φ = |p − q| − R with q the closest point of the segment ab to p, n = (p − q)/|p − q|. On the
// axis itself (|p − q| = 0) n is a fixed unit vector perpendicular to the axis ((0, 1, 0) when
// the capsule is a sphere, a = b).
template <typename T>
ContactT<T> contact(const CapsuleT<T>& cap, const Vec3<T>& p) {
    const Vec3<T> ab = cap.b - cap.a;
    const T len2 = glm::dot(ab, ab);
    const T t = len2 > T(0) ? std::clamp(glm::dot(p - cap.a, ab) / len2, T(0), T(1)) : T(0);
    const Vec3<T> r = p - (cap.a + t * ab);
    const T len = glm::length(r);
    if (len > T(0)) return {len - cap.radius, r / len};
    if (len2 == T(0)) return {-cap.radius, Vec3<T>(0, 1, 0)};
    // Perpendicular to the axis: cross with the coordinate axis least aligned with it.
    const Vec3<T> u = glm::abs(ab);
    const Vec3<T> e = u.x <= u.y && u.x <= u.z ? Vec3<T>(1, 0, 0)
                      : u.y <= u.z             ? Vec3<T>(0, 1, 0)
                                               : Vec3<T>(0, 0, 1);
    return {-cap.radius, glm::normalize(glm::cross(ab, e))};
}

// ---- signed-distance grid (a baked mesh, model/mesh_sdf.h) --------------------------------------

// Samples φ at origin + (i, j, k)·cell, i fastest: index (k·ny + j)·nx + i. At least 2 per axis.
struct SdfGrid {
    glm::dvec3 origin{0};  // the sample (0, 0, 0) [m]
    double cell = 1;       // sample spacing [m]
    glm::ivec3 count{2};   // samples per axis
    std::vector<double> values;
    double band = 0;  // how far beyond the mesh's bounds the grid reaches [m]

    std::int64_t index(int i, int j, int k) const {
        return (std::int64_t(k) * count.y + j) * count.x + i;
    }
    double at(int i, int j, int k) const { return values[size_t(index(i, j, k))]; }
};

// A grid placed in the world by a rigid pose: p_grid = rotationᵀ(p − translation).
template <typename T>
struct SdfColliderT {
    const SdfGrid* grid;
    Mat3<T> rotation{T(1)};
    Vec3<T> translation{T(0)};
};

// Trilinear interpolation of the grid and its analytic gradient (the exact gradient of that
// piecewise-trilinear interpolant, per cell). A point outside the grid is clamped onto its box
// q, and φ(p) = φ(q) + |p − q| with n from the gradient at q: outside the band the value only
// needs to be positive and growing, the contact never happens there (thickness < band).
template <typename T>
ContactT<T> contact(const SdfColliderT<T>& c, const Vec3<T>& pWorld) {
    const SdfGrid& g = *c.grid;
    const Vec3<T> p = glm::transpose(c.rotation) * (pWorld - c.translation);
    const T cell = T(g.cell);
    const Vec3<T> u = (p - Vec3<T>(g.origin)) / cell;  // grid coordinates
    const Vec3<T> hi = Vec3<T>(g.count - 1);
    const Vec3<T> uc = glm::clamp(u, Vec3<T>(0), hi);
    const T away = glm::length(u - uc) * cell;
    glm::ivec3 i0;
    Vec3<T> f;
    for (int a = 0; a < 3; ++a) {
        i0[a] = std::min(int(std::floor(uc[a])), g.count[a] - 2);
        f[a] = uc[a] - T(i0[a]);
    }
    T phi = 0;
    Vec3<T> grad(0);
    for (int corner = 0; corner < 8; ++corner) {
        const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
        const T v = T(g.at(i0.x + dx, i0.y + dy, i0.z + dz));
        const T wx = dx ? f.x : T(1) - f.x, wy = dy ? f.y : T(1) - f.y, wz = dz ? f.z : T(1) - f.z;
        const T sx = dx ? T(1) : T(-1), sy = dy ? T(1) : T(-1), sz = dz ? T(1) : T(-1);
        phi += wx * wy * wz * v;
        grad += v * Vec3<T>(sx * wy * wz, wx * sy * wz, wx * wy * sz);
    }
    const T len = glm::length(grad);
    const Vec3<T> n = len > T(0) ? grad / len : Vec3<T>(0, 1, 0);
    return {phi + away, c.rotation * n};
}

}  // namespace cloth
