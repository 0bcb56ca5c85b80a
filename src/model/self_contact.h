// Self-collision's elements and contacts (docs/physics.md "Self-collision"): which triangles and
// edges of the grid a vertex owns, which elements are topological neighbours, and the position
// correction of one point–triangle or edge–edge contact. Pure functions, no storage: the CPU
// backend calls them, shaders/compute/self_contact.glsl mirrors them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "model/grid.h"

namespace cloth {

// The sheet's triangulation, the one the OBJ writer uses (solver/output.cpp): the quad whose
// lower corner is a = (i, j) has triangles (a, b, c) and (a, c, d), with b = a + (1, 0),
// c = a + (1, 1), d = a + (0, 1). Vertex a owns both, and the edges a–b, a–d and a–c.
struct GridOffset {
    int di, dj;
};
inline constexpr std::array<std::array<GridOffset, 3>, 2> kOwnedTriangles{{
    {{{0, 0}, {1, 0}, {1, 1}}},
    {{{0, 0}, {1, 1}, {0, 1}}},
}};
inline constexpr std::array<GridOffset, 3> kOwnedEdgeEnds{{{1, 0}, {0, 1}, {1, 1}}};

// Elements that share a vertex are neighbours, never in contact: their distance is the sheet's
// own shape, kept by its springs. Every other pair is a candidate, even two rings apart: a
// crease folded flat within a cell or two must not pass through itself either, and a pair that
// lies flat beside each other never makes a contact (a point's projection falls outside the
// triangle; two edges' closest points lie at an end), so the sheet at rest has none
// (docs/physics.md "Self-collision").

// A contact between elements: the relative position r = Σ alpha_j x_j of its (up to) four
// vertices, whose component along `normal` must be at least the thickness.
template <typename T>
struct ContactGeometry {
    std::array<T, 4> alpha{};
    Vec3<T> normal{0};  // unit, pointing the way the side keeps r
    T gap = 0;          // r·normal: the signed distance now
};

template <typename T>
inline T sideOf(T x) {
    return x < T(0) ? T(-1) : T(1);
}

// Point p against triangle (a, b, c). Where p's projection falls inside the triangle the
// contact is along the triangle's normal, on the side `side`: the sign of p's offset along the
// normal where the substep's motion took it (ref positions), before any correction. Elsewhere
// the closest point lies on an edge or a corner, and the contact pushes straight away from it:
// no side to keep there, as nothing passes through an edge or a corner without passing
// through a triangle beside it. False for a degenerate triangle (its neighbours take over).
template <typename T>
inline bool pointTriangle(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c,
                          T side, ContactGeometry<T>& g) {
    const Vec3<T> e0 = b - a, e1 = c - a, ap = p - a;
    const Vec3<T> n = glm::cross(e0, e1);
    const T n2 = glm::dot(n, n);
    if (!(n2 > T(0))) return false;
    // Barycentrics of p's projection (Ericson, Real-Time Collision Detection §3.4).
    const T d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
    const T d20 = glm::dot(ap, e0), d21 = glm::dot(ap, e1);
    const T denominator = d00 * d11 - d01 * d01;
    if (!(denominator > T(0))) return false;
    T v = (d11 * d20 - d01 * d21) / denominator, w = (d00 * d21 - d01 * d20) / denominator;
    T u = T(1) - v - w;
    if (u >= T(0) && v >= T(0) && w >= T(0)) {
        g.normal = side * n / std::sqrt(n2);
        g.gap = glm::dot(ap, g.normal);
        g.alpha = {T(1), -u, -v, -w};
        return true;
    }
    // The closest point on the border: the nearest of the three edges' closest points.
    T best = std::numeric_limits<T>::max();
    const Vec3<T> corner[3] = {a, b, c};
    for (int e = 0; e < 3; ++e) {
        const Vec3<T> s0 = corner[e], s1 = corner[(e + 1) % 3], d = s1 - s0;
        const T t = std::clamp(glm::dot(p - s0, d) / glm::dot(d, d), T(0), T(1));
        const Vec3<T> r = p - (s0 + t * d);
        const T r2 = glm::dot(r, r);
        if (!(r2 < best)) continue;
        best = r2;
        std::array<T, 3> weights{};
        weights[e] = T(1) - t;
        weights[(e + 1) % 3] = t;
        u = weights[0], v = weights[1], w = weights[2];
    }
    const T distance = std::sqrt(best);
    if (!(distance > T(0))) return false;  // on the border itself: no direction to push in
    const Vec3<T> closest = u * a + v * b + w * c;
    g.normal = (p - closest) / distance;
    g.gap = distance;
    g.alpha = {T(1), -u, -v, -w};
    return true;
}

// The side of a point against a triangle: the sign of its offset along the triangle's normal.
template <typename T>
inline T pointTriangleSide(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) {
    return sideOf(glm::dot(glm::cross(b - a, c - a), p - a));
}

// Segments p0p1 and q0q1 whose closest points lie inside both (an end point's contact is a
// point–triangle one), r = p(s) − q(t). `side`: the sign of (e_p × e_q)·(p0 − q0) at the ref
// positions, which flips exactly when one segment's line passes through the other's.
template <typename T>
inline bool edgeEdge(const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& q0, const Vec3<T>& q1,
                     T side, const Vec3<T>& refCross, ContactGeometry<T>& g) {
    const Vec3<T> ep = p1 - p0, eq = q1 - q0, w0 = p0 - q0;
    const T a = glm::dot(ep, ep), b = glm::dot(ep, eq), c = glm::dot(eq, eq);
    const T d = glm::dot(ep, w0), e = glm::dot(eq, w0);
    const T denominator = a * c - b * b;
    // Nearly parallel segments (sin² of their angle below 1e-6) have no single closest pair:
    // their ends' point–triangle contacts hold them.
    if (!(denominator > T(1e-6) * a * c)) return false;
    const T s = (b * e - c * d) / denominator, t = (a * e - b * d) / denominator;
    if (!(s > T(0) && s < T(1) && t > T(0) && t < T(1))) return false;
    Vec3<T> n = glm::cross(ep, eq);
    n /= std::sqrt(glm::dot(n, n));
    if (glm::dot(n, refCross) < T(0)) n = -n;  // the ref's orientation, which `side` refers to
    g.normal = side * n;
    g.gap = glm::dot(w0 + s * ep - t * eq, g.normal);
    g.alpha = {T(1) - s, s, t - T(1), -t};
    return true;
}

// The corrections Δx_j that bring the gap up to h along the normal and, with friction μ, take
// back the tangential slip `slip` = Σ alpha_j (x_j − x_j at the substep's start) up to
// μ·(h − gap) (Coulomb's cone on the displacements; Bridson, Fedkiw, Anderson 2002 §7.2).
// Each vertex moves by alpha_j w_j / Σ alpha² w of the change, w_j its inverse mass (0 pinned):
// the mass-weighted least-norm correction. False when nothing can move (all pinned).
template <typename T>
inline bool contactCorrection(const ContactGeometry<T>& g, const std::array<T, 4>& inverseMass,
                              int count, const Vec3<T>& slip, T h, T friction,
                              std::array<Vec3<T>, 4>& dx) {
    T weight = 0;
    for (int j = 0; j < count; ++j) weight += g.alpha[j] * g.alpha[j] * inverseMass[j];
    if (!(weight > T(0))) return false;
    const T depth = h - g.gap;
    Vec3<T> change = depth * g.normal;
    if (friction > T(0)) {
        const Vec3<T> tangential = slip - glm::dot(slip, g.normal) * g.normal;
        const T length = std::sqrt(glm::dot(tangential, tangential));
        if (length > T(0)) change -= std::min(T(1), friction * depth / length) * tangential;
    }
    for (int j = 0; j < count; ++j) dx[j] = (g.alpha[j] * inverseMass[j] / weight) * change;
    return true;
}

// The contacts one vertex's corrections can be summed over in fixed point (each clamped to ±4h,
// in units that fit this many in 31 bits). A vertex in more at once lies in a cloth collapsed
// onto itself, which the thickness, kept from a state that had it, cannot give: both backends
// stop the step there with this reason (vertex (i, j), its `touches` contacts).
inline constexpr int kSelfMostTouches = 64;
inline std::string selfCollapseReason(int i, int j, int touches) {
    return "self-collision: vertex (" + std::to_string(i) + ", " + std::to_string(j) + ") is in " +
           std::to_string(touches) + " contacts at once, more than the " +
           std::to_string(kSelfMostTouches) +
           " one vertex's sums hold: the cloth lies collapsed onto itself";
}

}  // namespace cloth
