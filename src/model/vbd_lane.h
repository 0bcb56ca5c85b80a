// The per-vertex arithmetic of Vertex Block Descent's local step (model/vbd_local.h) on plain
// scalars, as model/spring_math.h is for the forces: the scalar path (vbd_local.h's Vec3
// functions call these) and the vbd row kernel of every instruction set
// (cpu/isa/cpu_rows_isa.cpp) compute the same operations in the same order, so a vertex's Newton
// step has the same bits on every path. always_inline for the reason spring_math.h gives.
#pragma once

#include <cmath>

#include "model/spring_math.h"

namespace cloth {

// The gradient g = ∂G/∂x_k and the six entries of the Hessian H = ∂²G/∂x_k² of one vertex. A
// trivial aggregate (VbdLane<T>{} is zero): no constructor that a kernel compiled for a wider
// instruction set could emit out of line.
template <typename T>
struct VbdLane {
    T gx, gy, gz;
    T xx, yy, zz, xy, xz, yz;
};

// H += s I
template <typename T>
CLOTH_LANE void vbdAddDiagonal(T s, VbdLane<T>& a) {
    a.xx += s;
    a.yy += s;
    a.zz += s;
}

// H += c d dᵀ (model/sym3.h addOuter's order)
template <typename T>
CLOTH_LANE void vbdAddOuter(T c, T dx, T dy, T dz, VbdLane<T>& a) {
    const T cx = c * dx, cy = c * dy, cz = c * dz;
    a.xx += cx * dx;
    a.xy += cx * dy;
    a.xz += cx * dz;
    a.yy += cy * dy;
    a.yz += cy * dz;
    a.zz += cz * dz;
}

// Inertia and air drag on the step's displacement d = x − x_n (the iterate, so that a float
// cloth far from the origin keeps its small steps): g += m/h² (d − ŷ) + m c/h d with
// ŷ = y − x_n = h v_n + h² a_ext, H += (m/h² + m c/h) I; one component of g from d, ŷ's (the row
// kernel's loops take one component at a time).
template <typename T>
CLOTH_LANE T vbdInertiaWeight(T mass, T h) {
    return mass / (h * h);
}
template <typename T>
CLOTH_LANE T vbdDragWeight(T mass, T h, T dampingRate) {
    return mass * dampingRate / h;
}
template <typename T>
CLOTH_LANE T vbdInertiaGradient(T displacement, T target, T inertia, T drag) {
    return inertia * (displacement - target) + drag * displacement;
}

// The spring along d = x_q − x_k: g −= K (|d| − L)/|d| d, H += t I + (K − t)/|d|² d dᵀ with
// t = K max(0, (|d| − L)/|d|); nothing below |d| = 1e-12 L. One division, 1/|d|, for the three
// quotients (|d| − L is exact near the rest length, so the strain keeps float's precision).
template <typename T>
CLOTH_LANE void vbdSpringLane(T dx, T dy, T dz, T stiffness, T restLength, VbdLane<T>& a) {
    const T len = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(len >= T(1e-12) * restLength)) return;
    const T inverse = T(1) / len;
    const T strain = (len - restLength) * inverse;
    const T c = stiffness * strain;
    a.gx -= c * dx;
    a.gy -= c * dy;
    a.gz -= c * dz;
    const T transverse = stiffness * (T(0) < strain ? strain : T(0));  // std::max's order
    vbdAddDiagonal(transverse, a);
    vbdAddOuter((stiffness - transverse) * inverse * inverse, dx, dy, dz, a);
}

// The spring's damping on the step's displacement: d = x_q,n − x_k,n at the step's start, w the
// displacement difference (d is x_q − x_k − w: the positions now, less the step's difference).
// With e = βK/|d|² (spring_math.h's springDampingCoefficient over (w·d)): g −= e (w·d) d/h,
// H += e/h d dᵀ; nothing where |d| < 1e-12 L. One division, e (1/h is the caller's loop
// invariant).
template <typename T>
CLOTH_LANE void vbdSpringDampingLane(T dx, T dy, T dz, T wx, T wy, T wz, T dampingK, T restLength,
                                     T inverseH, VbdLane<T>& a) {
    const T d2 = dx * dx + dy * dy + dz * dz, floor = T(1e-12) * restLength;
    if (!(d2 >= floor * floor)) return;
    const T e = dampingK / d2;
    const T c = e * (wx * dx + wy * dy + wz * dz) * inverseH;
    a.gx -= c * dx;
    a.gy -= c * dy;
    a.gz -= c * dz;
    vbdAddOuter(e * inverseH, dx, dy, dz, a);
}

// ε_v [m/s]: below this slide speed against the surface vbd's friction holds (vbdFrictionLane).
inline constexpr double kVbdStickSpeed = 1e-3;

// Friction as an energy of the local problem (docs/integrators.md "vbd", friction; IPC's lagged
// friction, as the VBD paper takes it): D = w f0(|t|), w = c_f λ [N] with the normal force λ and
// the unit normal n of the vertex's last projection (lagged), t = S u the tangential part of
// u = x − x_n − h v_c, its slide over the step against the surface (S = I − n nᵀ). f0's
// derivative is IPC's mollifier f1(y) = 2y/ε − y²/ε² below ε, 1 above (ε = ε_v h: stuck below
// the slide speed ε_v): g += s t, H += s S with s = w f1(|t|)/|t|, the positive semi-definite
// part of D's Hessian. Without a branch (w = 0 adds zeros), so that the row kernel vectorises.
template <typename T>
CLOTH_LANE void vbdFrictionLane(T ux, T uy, T uz, T nx, T ny, T nz, T weight, T epsilon,
                                VbdLane<T>& a) {
    const T un = ux * nx + uy * ny + uz * nz;
    const T tx = ux - un * nx, ty = uy - un * ny, tz = uz - un * nz;
    const T slide = std::sqrt(tx * tx + ty * ty + tz * tz);
    const bool stuck = slide < epsilon;
    const T inverseEpsilon = T(1) / epsilon;
    const T ratio =
        stuck ? (T(2) - slide * inverseEpsilon) * inverseEpsilon : T(1) / (stuck ? T(1) : slide);
    const T s = weight * ratio;
    a.gx += s * tx;
    a.gy += s * ty;
    a.gz += s * tz;
    vbdAddDiagonal(s, a);
    vbdAddOuter(-s, nx, ny, nz, a);
}

// nᵀ H n: the local problem's stiffness along a unit n [N/m]. A projection that moves the Newton
// step's x by d along n holds it there with the normal force λ = d nᵀ H n.
template <typename T>
CLOTH_LANE T vbdNormalStiffness(const VbdLane<T>& a, T nx, T ny, T nz) {
    return a.xx * nx * nx + a.yy * ny * ny + a.zz * nz * nz +
           T(2) * (a.xy * nx * ny + a.xz * nx * nz + a.yz * ny * nz);
}

// The Newton step s = −H⁻¹g, solved in double and rounded to T once, for the caller to add to
// the position and to the displacement alike; H⁻¹ by the adjugate (glm::inverse's operations).
// s = 0, and false, where |det H| ≤ 1e-12 floor³ (vbdNewtonStep says why). Without a branch, so
// that the row kernel's loop vectorises.
template <typename T>
CLOTH_LANE bool vbdNewtonLane(const VbdLane<T>& a, double floor, T& sx, T& sy, T& sz) {
    const double d00 = a.xx, d01 = a.xy, d02 = a.xz, d11 = a.yy, d12 = a.yz, d22 = a.zz;
    const double c0 = d11 * d22 - d12 * d12, c1 = d01 * d22 - d12 * d02;
    const double c2 = d01 * d12 - d11 * d02;
    const double det = d00 * c0 - d01 * c1 + d02 * c2;
    const bool step = std::abs(det) > 1e-12 * floor * floor * floor;
    const double s = 1.0 / (step ? det : 1.0);
    const double i00 = c0 * s, i10 = -(d01 * d22 - d02 * d12) * s, i20 = c2 * s;
    const double i01 = -c1 * s, i11 = (d00 * d22 - d02 * d02) * s;
    const double i21 = -(d00 * d12 - d02 * d01) * s, i02 = c2 * s;
    const double i12 = -(d00 * d12 - d01 * d02) * s, i22 = (d00 * d11 - d01 * d01) * s;
    const double gx = a.gx, gy = a.gy, gz = a.gz;
    const T nx = T(-(i00 * gx + i10 * gy + i20 * gz));
    const T ny = T(-(i01 * gx + i11 * gy + i21 * gz));
    const T nz = T(-(i02 * gx + i12 * gy + i22 * gz));
    sx = step ? nx : T(0);
    sy = step ? ny : T(0);
    sz = step ? nz : T(0);
    return step;
}

}  // namespace cloth
