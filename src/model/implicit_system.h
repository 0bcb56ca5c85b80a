// Implicit Euler's linear system on one grid (docs/integrators.md, implicit_euler):
//
//   A = m_k (1 + hc) I + h D + h² H      (+ h² K_grab I at the grabbed vertex)
//
// linearised at the positions x, applied without storing it, and its 3×3 diagonal blocks: the
// block-Jacobi preconditioner and the multigrid smoother invert them. The CPU's fine grid and
// every coarse grid of its multigrid preconditioner (cpu/cpu_multigrid.h) are one of these.
#pragma once

#include <cstdint>
#include <vector>

#include "model/solve_contact.h"
#include "model/stiffness.h"
#include "model/sym3.h"

namespace cloth {

// One spring's two blocks at its vertex k = (i, j), unscaled: the stiffness Jacobian J_s
// (model/stiffness.h) and the damping block D_s, with β halved on a border line as the force
// halves it (zero unless damped). A's off-diagonal block for the pair is −(h² J_s + h D_s); both
// the diagonal below and the multigrid's assembled fine stencil sum them.
template <typename T>
struct SpringBlocks {
    Sym3<T> stiffness, damping;
};

template <typename T>
SpringBlocks<T> springBlocks(const StencilSpring<T>& s, const Vec3<T>& xk, const Vec3<T>& xq, int i,
                             int j, int nu, int nv, bool damped) {
    SpringBlocks<T> b;
    b.stiffness = springJacobian(xk, xq, stiffnessAt(s, i, j, nu, nv), s.restLength);
    if (damped) {
        const bool halved = s.halvedOnBorder && onBorderLine(s.di, s.dj, i, j, nu, nv);
        b.damping =
            springDampingBlock(xk, xq, halved ? T(0.5) * s.damping : s.damping, s.restLength);
    }
    return b;
}

template <typename T, typename Positions>
struct ImplicitSystem {
    int nu = 0, nv = 0;
    const std::vector<StencilSpring<T>>* springs = nullptr;
    BendingWeights bending;
    const Positions* x = nullptr;    // the state it is linearised at
    const T* inverseMass = nullptr;  // 1/m_k per vertex
    const std::uint8_t* pinned = nullptr;
    T h = 0, drag = 1;  // Δt and 1 + hc
    bool springDamping = false;
    std::int64_t grabVertex = -1;  // the grab spring's vertex, −1 for none
    T grabStiffness = 0;
    // The contacts in the solve (model/solve_contact.h), one per vertex, or none.
    const SolveContact<T>* contacts = nullptr;

    // out = A p on vertices [begin, end), filtered by the contacts (S A p); pinned rows 0 (the
    // caller keeps p = 0 there).
    void apply(const Vec3<T>* p, Vec3<T>* out, std::int64_t begin, std::int64_t end) const {
        stiffnessProduct(nu, nv, *springs, *x, p, pinned, out, begin, end, bending);
        const T h2 = h * h;
        for (std::int64_t k = begin; k < end; ++k) {
            if (pinned[k]) continue;
            out[k] = (drag / inverseMass[k]) * p[k] + h2 * out[k];
            if (springDamping) {  // + h D p, D = −∂F/∂v = Σ βK d̂d̂ᵀ
                Vec3<T> damped(0);
                addSpringDampingAt(nu, nv, *springs, *x, p, k, int(k % nu), int(k / nu), damped);
                out[k] -= h * damped;
            }
        }
        if (grabVertex >= begin && grabVertex < end && !pinned[grabVertex])
            out[grabVertex] += h2 * grabStiffness * p[grabVertex];
        if (contacts)
            for (std::int64_t k = begin; k < end; ++k) out[k] = filterContact(contacts[k], out[k]);
    }

    // The 3×3 block A_kk of vertex k = (i, j), not pinned.
    Sym3<T> diagonal(std::int64_t k) const {
        const int i = int(k % nu), j = int(k / nu);
        const bool interior = i >= 2 && i < nu - 2 && j >= 2 && j < nv - 2;
        const Vec3<T> xk = positionAt(*x, k);
        Sym3<T> stiffness, damping;
        for (const StencilSpring<T>& s : *springs) {
            if (!interior && !(i + s.di >= 0 && i + s.di < nu && j + s.dj >= 0 && j + s.dj < nv))
                continue;
            const SpringBlocks<T> b =
                springBlocks(s, xk, positionAt(*x, k + s.indexOffset), i, j, nu, nv, springDamping);
            stiffness += b.stiffness;
            if (springDamping) damping += b.damping;
        }
        if (bending.active()) {  // H's diagonal coefficient: minus the force of a unit vertex
            auto unit = [&](int a, int b) { return Vec3<T>(a == i && b == j ? 1 : 0); };
            stiffness += Sym3<T>::identity(-bendingForce<T>(bending, i, j, unit).x);
        }
        if (k == grabVertex) stiffness += Sym3<T>::identity(grabStiffness);
        Sym3<T> a = Sym3<T>::identity(drag / inverseMass[k]);
        a += stiffness * (h * h);
        if (springDamping) a += damping * h;
        return a;
    }
};

}  // namespace cloth
