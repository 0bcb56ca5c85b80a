// The per-vertex arithmetic of DESIGN.md §2 on plain scalars: one spring's force coefficient, the
// wind on one vertex, one Euler update. The scalar path (model/forces.h) and the row kernels of
// every instruction set (cpu/isa/cpu_rows_isa.cpp) call these same functions, so each lane
// computes the same operations in the same order and the results are bit-identical (the build is
// ISO C++, so no a*b+c is contracted into an FMA).
//
// always_inline: the row kernels are compiled once per instruction set; an out-of-line copy of
// one of these, compiled for AVX-512, must never be what the generic code links against.
#pragma once

#include <cmath>

#define CLOTH_LANE [[gnu::always_inline]] inline

namespace cloth {

// Seed eq. (2): F = c d with c = K (|d| − L)/|d|, d = p_q − p_k; c = 0 for a spring squeezed
// below 1e-12 L (no direction, no NaN). c is the same for d and −d: a spring's two ends share it.
template <typename T>
CLOTH_LANE T springCoefficient(T dx, T dy, T dz, T stiffness, T restLength) {
    const T len = std::sqrt(dx * dx + dy * dy + dz * dz);
    return len >= T(1e-12) * restLength ? stiffness * (len - restLength) / len : T(0);
}

// Damping along a spring (docs/physics.md "Spring damping"): f += c d with
// c = βK (w·d)/|d|², i.e. βK ((v_q − v_k)·d̂) d̂, d = p_q − p_k, w = v_q − v_k and
// dampingK = βK [N·s/m]. A spring squeezed below 1e-12 L adds nothing, as in springCoefficient.
// c is the same bits for (d, w) and (−d, −w): a spring's two ends share it, like the spring's.
// Linear in w: with w the difference of any vector field it is −(∂F/∂v) w, implicit Euler's
// damping product.
template <typename T>
CLOTH_LANE T springDampingCoefficient(T dx, T dy, T dz, T wx, T wy, T wz, T dampingK,
                                      T restLength) {
    const T d2 = dx * dx + dy * dy + dz * dz, floor = T(1e-12) * restLength;
    return d2 >= floor * floor ? dampingK * (wx * dx + wy * dy + wz * dz) / d2 : T(0);
}
template <typename T>
CLOTH_LANE void addSpringDamping(T dx, T dy, T dz, T wx, T wy, T wz, T dampingK, T restLength,
                                 T& fx, T& fy, T& fz) {
    const T c = springDampingCoefficient(dx, dy, dz, wx, wy, wz, dampingK, restLength);
    fx += c * dx;
    fy += c * dy;
    fz += c * dz;
}

// Unit normal n = (a × b)/|a × b| from the two central differences a, b (DESIGN.md §2), 0 where
// |a × b| < 1e-12.
template <typename T>
CLOTH_LANE void unitNormal(T ax, T ay, T az, T bx, T by, T bz, T& nx, T& ny, T& nz) {
    const T cx = ay * bz - by * az, cy = az * bx - bz * ax, cz = ax * by - bx * ay;
    const T len = std::sqrt(cx * cx + cy * cy + cz * cz);
    const bool some = len >= T(1e-12);
    nx = some ? cx / len : T(0);
    ny = some ? cy / len : T(0);
    nz = some ? cz / len : T(0);
}

// Wind (seed §5.3): F_w = K_w ⟨n, û_w⟩ n, added to f.
template <typename T>
CLOTH_LANE void addWind(T nx, T ny, T nz, T wx, T wy, T wz, T strength, T& fx, T& fy, T& fz) {
    const T s = strength * (nx * wx + ny * wy + nz * wz);
    fx += s * nx;
    fy += s * ny;
    fz += s * nz;
}

// The acceleration of one component of a free vertex (docs/integrators.md): a = F w − c v + g,
// w = 1/m_k the vertex's inverse mass, c the damping rate (the drag −c m_k v over m_k; the
// per-vertex form's (F − μ v)/m + g with c = μ/m).
template <typename T>
CLOTH_LANE T accelerationComponent(T f, T v, T dampingRate, T inverseMass, T g) {
    return f * inverseMass - dampingRate * v + g;
}

// One explicit or symplectic Euler update of one component (DESIGN.md §2, seed eq. (6)) with
// that acceleration; explicit moves p with the old v, symplectic with the new one.
template <typename T, bool kSymplectic>
CLOTH_LANE void eulerComponent(T& p, T& v, T f, T h, T dampingRate, T inverseMass, T g) {
    const T a = accelerationComponent(f, v, dampingRate, inverseMass, g);
    if (!kSymplectic) p = p + h * v;
    v = v + h * a;
    if (kSymplectic) p = p + h * v;
}

// The instability test of DESIGN.md §2 (x − x is 0 exactly when x is finite): true when the
// position or the speed is not finite, or the speed² exceeds maxSpeed2.
template <typename T>
CLOTH_LANE bool badVertex(T px, T py, T pz, T vx, T vy, T vz, T maxSpeed2) {
    const T s = px + py + pz, speed2 = vx * vx + vy * vy + vz * vz;
    return !(s - s == T(0)) | !(speed2 - speed2 == T(0)) | (speed2 > maxSpeed2);  // no branch
}

}  // namespace cloth
