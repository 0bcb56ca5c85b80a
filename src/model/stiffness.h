// The stiffness operator H = −∂F/∂x of the spring forces, applied without storing it: one gather
// over the 12-neighbour stencil, like the force pass. Implicit Euler's conjugate gradient and the
// power iteration of the stability prediction both use it (docs/integrators.md).
#pragma once

#include <cstdint>
#include <vector>

#include "model/bending.h"
#include "model/forces.h"
#include "model/scene.h"

namespace cloth {

// A family is modelled when one of its slots of kSpringOffsets has a stiffness > 0
// (Scene::slotStiffness: the per-vertex form's K of the family, or a material's K along u, along
// v, of the shear springs; a material models no bend springs). Every slot of a modelled family is
// walked, with its own K.
inline bool familyModelled(const Scene& scene, Family f) {
    for (std::size_t s = 0; s < kSpringOffsets.size(); ++s)
        if (kSpringOffsets[s].family == f && scene.slotStiffness(int(s)) > 0) return true;
    return false;
}

// One active entry of kSpringOffsets: a slot of a family the scene models.
template <typename T>
struct StencilSpring {
    int di, dj;
    std::int64_t indexOffset;  // dj·nu + di
    T stiffness, restLength;
    bool halvedOnBorder = false;  // a material's structural spring (model/grid.h onBorderLine)
    T damping = 0;                // βK [N·s/m] (Scene::springDamping); 0: no spring damping
};

// K of spring s at vertex (i, j): halved on a border line where the spring asks for it.
template <typename T>
T stiffnessAt(const StencilSpring<T>& s, int i, int j, int nu, int nv) {
    return s.halvedOnBorder && onBorderLine(s.di, s.dj, i, j, nu, nv) ? T(0.5) * s.stiffness
                                                                      : s.stiffness;
}

template <typename T>
std::vector<StencilSpring<T>> activeSprings(const Scene& scene) {
    const Grid g = scene.grid();
    std::vector<StencilSpring<T>> springs;
    for (std::size_t s = 0; s < kSpringOffsets.size(); ++s) {
        const SpringOffset& o = kSpringOffsets[s];
        if (!familyModelled(scene, o.family)) continue;
        springs.push_back({o.di, o.dj, std::int64_t(o.dj) * g.nu + o.di,
                           T(scene.slotStiffness(int(s))), T(g.restLength(o.di, o.dj)),
                           scene.material.has_value() && o.family == Family::Structural,
                           T(scene.springDamping() * scene.slotStiffness(int(s)))});
    }
    return springs;
}

template <typename T>
Vec3<T> positionAt(const Vec3<T>* x, std::int64_t k) {
    return x[k];
}
template <typename T>
Vec3<T> positionAt(const std::vector<Vec3<T>>& x, std::int64_t k) {
    return x[std::size_t(k)];
}

// f += Σ_s the damping of spring s at vertex k = (i, j), in the springs' order, w the velocities
// (or, for implicit Euler's product, any vector field): −(∂F/∂v) w. x and w: anything
// positionAt(x, k) reads. The CPU's force pass and implicit product and the stability probe
// share it.
template <typename T, typename Positions, typename Vectors>
void addSpringDampingAt(int nu, int nv, const std::vector<StencilSpring<T>>& springs,
                        const Positions& x, const Vectors& w, std::int64_t k, int i, int j,
                        Vec3<T>& f) {
    const bool interior = i >= 2 && i < nu - 2 && j >= 2 && j < nv - 2;
    const Vec3<T> pk = positionAt(x, k), wk = positionAt(w, k);
    for (const StencilSpring<T>& s : springs) {
        if (!interior) {
            const int qi = i + s.di, qj = j + s.dj;
            if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
        }
        const std::int64_t q = k + s.indexOffset;
        addSpringDamping(pk, positionAt(x, q), positionAt(w, q) - wk,
                         s.halvedOnBorder && onBorderLine(s.di, s.dj, i, j, nu, nv)
                             ? T(0.5) * s.damping
                             : s.damping,
                         s.restLength, f);
    }
}

// out_k = (H p)_k = Σ_s J_s(x) (p_k − p_q) for k in [begin, end), with J_s clamped
// (springJacobianTimes). Rows of pinned vertices are 0: a pin is a constraint, not a DOF; the
// caller keeps p = 0 there, which removes the pinned columns too.
// x and p: a Vec3<T> array or anything positionAt(x, k) reads (the CPU's Soa3). With `bending`
// active, its Hessian (constant: model/bending.h) is added: H p += −bendingForce(p).
template <typename T, typename Positions, typename Vectors>
void stiffnessProduct(int nu, int nv, const std::vector<StencilSpring<T>>& springs,
                      const Positions& x, const Vectors& p, const std::uint8_t* pinned,
                      Vec3<T>* out, std::int64_t begin, std::int64_t end,
                      const BendingWeights& bending = {}) {
    auto pAt = [&](int qi, int qj) { return positionAt(p, std::int64_t(qj) * nu + qi); };
    int i = int(begin % nu), j = int(begin / nu);
    for (std::int64_t k = begin; k < end; ++k) {
        Vec3<T> y(0);
        if (!pinned[k]) {
            const bool interior = i >= 2 && i < nu - 2 && j >= 2 && j < nv - 2;
            for (const StencilSpring<T>& s : springs) {
                if (!interior) {
                    const int qi = i + s.di, qj = j + s.dj;
                    if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
                }
                const std::int64_t q = k + s.indexOffset;
                y += springJacobianTimes(positionAt(x, k), positionAt(x, q),
                                         stiffnessAt(s, i, j, nu, nv), s.restLength,
                                         positionAt(p, k) - positionAt(p, q));
            }
            if (bending.active()) y -= bendingForce<T>(bending, i, j, pAt);
        }
        out[k] = y;
        if (++i == nu) {
            i = 0;
            ++j;
        }
    }
}

}  // namespace cloth
