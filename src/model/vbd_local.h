// The local problem of Vertex Block Descent (Chen, Macklin et al., SIGGRAPH 2024;
// docs/integrators.md "vbd"): the gradient and Hessian of one vertex's part of backward Euler's
// incremental potential
//
//   G(x) = Σ_k m_k/(2h²) |x_k − y_k|² + Σ_k m_k c/(2h) |x_k − x_n,k|² + E(x) + E_β(x),
//
// x_k moving, every other vertex held; and the 3×3 Newton step on it. The iterate is the pair
// (x, d): the positions, which the springs and bending read, and the step's displacement
// d = x − x_n, which inertia, drag, damping and friction read (a float x far from the origin
// rounds a small step away; d keeps it). Every step moves both alike. E holds the springs
// (½K(|d| − L)², each slot of the stencil with its stiffnessAt), the quadratic bending energy
// (model/bending.h) and the grab; E_β is the spring damping of implicit Euler's D taken on the
// step's displacement. Stateless: positions and parameters in, gradient and Hessian out, so the
// CPU backend and a GPU mirror compute the same operations.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "model/bending.h"
#include "model/forces.h"
#include "model/stiffness.h"
#include "model/sym3.h"
#include "model/vbd_lane.h"

namespace cloth {

// g = ∂G/∂x_k and H = ∂²G/∂x_k² (made positive semi-definite term by term) at the current x.
template <typename T>
struct VbdLocal {
    Vec3<T> gradient{0};
    Sym3<T> hessian;
};

// f(lane) on the local problem's entries as a VbdLane (model/vbd_lane.h): the arithmetic each
// term shares with the vbd row kernels.
template <typename T, typename F>
void onLane(VbdLocal<T>& local, const F& f) {
    const Vec3<T>& g = local.gradient;
    const Sym3<T>& m = local.hessian;
    VbdLane<T> a{g.x, g.y, g.z, m.xx, m.yy, m.zz, m.xy, m.xz, m.yz};
    f(a);
    local.gradient = {a.gx, a.gy, a.gz};
    local.hessian = {a.xx, a.yy, a.zz, a.xy, a.xz, a.yz};
}

// Inertia and air drag: m/(2h²)|d − ŷ|² + m c/(2h)|d|², d = x − x_n and ŷ = y − x_n =
// h v_n + h² a_ext, y the inertial target. The drag term is backward Euler's −c m v_{n+1} with
// v_{n+1} = d/h: its gradient m c d/h is that force's negative.
template <typename T>
void addVbdInertia(const Vec3<T>& d, const Vec3<T>& target, T mass, T h, T dampingRate,
                   VbdLocal<T>& local) {
    const T inertia = vbdInertiaWeight(mass, h), drag = vbdDragWeight(mass, h, dampingRate);
    for (int c = 0; c < 3; ++c)
        local.gradient[c] += vbdInertiaGradient(d[c], target[c], inertia, drag);
    local.hessian.addDiagonal(inertia + drag);
}

// The spring from k to q, E = ½K(|d| − L)², d = x_q − x_k: ∂E/∂x_k = −K (|d| − L) d/|d| (minus
// springForce, seed eq. (2)), and ∂²E/∂x_k² = K (d̂d̂ᵀ + (1 − L/|d|)(I − d̂d̂ᵀ)) with the transverse
// part clamped at 0 (Choi & Ko), the matrix springJacobianTimes applies: positive semi-definite,
// so a compressed spring never turns the Newton step uphill. Nothing for a spring squeezed to a
// point, as in springCoefficient.
template <typename T>
void addVbdSpring(const Vec3<T>& pk, const Vec3<T>& pq, T stiffness, T restLength,
                  VbdLocal<T>& local) {
    const Vec3<T> d = pq - pk;
    onLane(local, [&](VbdLane<T>& a) { vbdSpringLane(d.x, d.y, d.z, stiffness, restLength, a); });
}

// Spring damping as implicit Euler's D (docs/integrators.md): the force −D v_{n+1}, D = Σ βK d̂d̂ᵀ
// at the step's start x_n, with v_{n+1} = (x − x_n)/h, is minus the gradient of
// E_β = Σ_springs βK/(2h) (d̂_n·(Δ_q − Δ_k))², Δ = x − x_n. w = Δ_q − Δ_k; pk, pq the ends now, so
// d_n = pq − pk − w. The gradient is −F_β(x_n, w)/h (addSpringDamping with the displacement for
// the velocity), the Hessian βK/h d̂_n d̂_nᵀ.
template <typename T>
void addVbdSpringDamping(const Vec3<T>& pk, const Vec3<T>& pq, const Vec3<T>& w, T dampingK,
                         T restLength, T h, VbdLocal<T>& local) {
    const Vec3<T> d = (pq - pk) - w;
    onLane(local, [&](VbdLane<T>& a) {
        vbdSpringDampingLane(d.x, d.y, d.z, w.x, w.y, w.z, dampingK, restLength, T(1) / h, a);
    });
}

// W_kk, the bending Hessian's diagonal coefficient at (i, j) [N/m]: the energy is quadratic,
// E = ½ xᵀ(W ⊗ I)x, so its Hessian block at k is W_kk I. It is −bendingForce of the field that is
// (1, 0, 0) at (i, j) and 0 elsewhere, read off along x.
template <typename T>
T bendingDiagonal(const BendingWeights& w, int i, int j) {
    const auto unit = [i, j](int a, int b) {
        return Vec3<T>(a == i && b == j ? T(1) : T(0), 0, 0);
    };
    return -bendingForce<T>(w, i, j, unit).x;
}

// The grab (forces.h grabForce): E = ½K|x − t|², gradient K(x − t), Hessian K I.
template <typename T>
void addVbdGrab(const Vec3<T>& x, const Vec3<T>& target, T stiffness, VbdLocal<T>& local) {
    local.gradient -= grabForce(x, target, stiffness);
    local.hessian.addDiagonal(stiffness);
}

// Everything of G at vertex k = (i, j) that couples it to its neighbours: the springs of the
// stencil (with their damping when modelled) and the bending energy, whose Hessian block
// bendDiagonal·I (bendingDiagonal, constant: the caller keeps it) is added. x: the current
// positions, d: the step's displacements, both anything positionAt(x, k) reads.
template <typename T, typename Positions, typename Displacements>
void addVbdStencil(int nu, int nv, const std::vector<StencilSpring<T>>& springs,
                   const BendingWeights& bending, T bendDiagonal, const Positions& x,
                   const Displacements& d, T h, std::int64_t k, int i, int j, VbdLocal<T>& local) {
    const bool interior = i >= 2 && i < nu - 2 && j >= 2 && j < nv - 2;
    const Vec3<T> pk = positionAt(x, k), dk = positionAt(d, k);
    const T inverseH = T(1) / h;
    onLane(local, [&](VbdLane<T>& a) {  // addVbdSpring and addVbdSpringDamping, summed in place
        for (const StencilSpring<T>& s : springs) {
            if (!interior) {
                const int qi = i + s.di, qj = j + s.dj;
                if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
            }
            const std::int64_t q = k + s.indexOffset;
            const Vec3<T> pq = positionAt(x, q), e = pq - pk;
            vbdSpringLane(e.x, e.y, e.z, stiffnessAt(s, i, j, nu, nv), s.restLength, a);
            if (s.damping > 0) {
                const bool half = s.halvedOnBorder && onBorderLine(s.di, s.dj, i, j, nu, nv);
                const Vec3<T> w = positionAt(d, q) - dk, dn = e - w;
                vbdSpringDampingLane(dn.x, dn.y, dn.z, w.x, w.y, w.z,
                                     half ? T(0.5) * s.damping : s.damping, s.restLength, inverseH,
                                     a);
            }
        }
    });
    if (bending.active()) {
        const auto at = [&](int a, int b) { return positionAt(x, std::int64_t(b) * nu + a); };
        local.gradient -= bendingForce<T>(bending, i, j, at);
        local.hessian.addDiagonal(bendDiagonal);
    }
}

// Friction as an energy with the lagged normal force (vbdFrictionLane): u = d − h v_c,
// n the unit normal and w = c_f λ of the vertex's last projection, ε = ε_v h.
template <typename T>
void addVbdFriction(const Vec3<T>& u, const Vec3<T>& n, T weight, T epsilon, VbdLocal<T>& local) {
    onLane(local, [&](VbdLane<T>& a) {
        vbdFrictionLane(u.x, u.y, u.z, n.x, n.y, n.z, weight, epsilon, a);
    });
}

// The local problem's entries as a VbdLane.
template <typename T>
VbdLane<T> vbdLane(const VbdLocal<T>& local) {
    const Vec3<T>& g = local.gradient;
    const Sym3<T>& m = local.hessian;
    return {g.x, g.y, g.z, m.xx, m.yy, m.zz, m.xy, m.xz, m.yz};
}

// The Newton step s = −H⁻¹g, solved in double (a stiff spring beside a light vertex makes H
// too ill-conditioned for a float inverse), for the caller to add to x and d. H ⪰ floor·I with
// floor = m/h² (every other term is positive semi-definite), so det H ≥ floor³: a determinant
// below 1e-12 of that is rounding or a non-finite state, and then s = 0. Returns whether it moved.
template <typename T>
bool vbdNewtonStep(const VbdLocal<T>& local, double floor, Vec3<T>& s) {
    return vbdNewtonLane(vbdLane(local), floor, s.x, s.y, s.z);
}

// The paper's adaptive initial guess (§3.7) as a displacement: x − x_n = h v_n + h² ã, ã the
// component of the previous step's acceleration a = (v_n − v_{n−1})/h along gravity ĝ, clipped to
// [0, |g|]: a vertex that fell freely starts where free fall takes it, one held up by the cloth
// starts where its velocity does. Without a previous step (`history` false) ã = g, the inertial
// guess.
template <typename T>
Vec3<T> vbdInitialGuess(const Vec3<T>& vn, const Vec3<T>& vPrevious, const Vec3<T>& gravity, T h,
                        bool history) {
    const T g = glm::length(gravity);
    Vec3<T> a = gravity;
    if (history && g > T(0)) {
        const T along = glm::dot(vn - vPrevious, gravity) / (h * g);
        a = (std::clamp(along, T(0), g) / g) * gravity;
    }
    return h * vn + (h * h) * a;
}

// The Chebyshev semi-iterative weight ω_n of iteration n ≥ 1 (Wang 2015, as VBD §3.8 uses it):
// ω_1 = 1, ω_2 = 2/(2 − ρ²), ω_n = 4/(4 − ρ²ω_{n−1}); ρ the estimated spectral radius of the
// unaccelerated iteration. The iterate becomes ω_n (x̄_n − x_{n−2}) + x_{n−2}.
inline double chebyshevOmega(int n, double rho, double previous) {
    if (n <= 1) return 1;
    if (n == 2) return 2 / (2 - rho * rho);
    return 4 / (4 - rho * rho * previous);
}

// The passes of the translation's levels a vbd step of `iterations` sweeps runs for `passes`
// asked: at most one before each sweep; none where passes ≤ 0 (no levels).
inline int vbdLevelPassCount(int iterations, int passes) {
    return std::clamp(passes, 0, std::max(iterations, 1));
}

// The sweep before which the levels run for the p-th time (p = 0 … count − 1): sweep 1, then
// 1 + ⌈p N / P⌉, spread evenly over the N sweeps (docs/integrators.md "The translation's levels").
inline int vbdLevelPassSweep(int p, int iterations, int passes) {
    const int each = std::max(vbdLevelPassCount(iterations, passes), 1);
    return 1 + (p * std::max(iterations, 1) + each - 1) / each;
}

// Whether the levels run before sweep n of such a step.
inline bool vbdLevelsBefore(int n, int iterations, int passes) {
    for (int p = 0; p < vbdLevelPassCount(iterations, passes); ++p)
        if (n == vbdLevelPassSweep(p, iterations, passes)) return true;
    return false;
}

// The sweeps of a vbd step that come before Chebyshev's first iteration: the semi-iteration
// assumes one fixed map from sweep to sweep, which a sweep followed by the translation's step is
// not, nor a sweep that follows a pass of the levels after the first, so its sequence starts from
// the iterate after the last such sweep (docs/integrators.md "vbd"). `passes` 0: no levels.
inline int vbdChebyshevStart(int translationSweeps, int iterations, int passes) {
    const int count = vbdLevelPassCount(iterations, passes);
    const int lastPass = count > 1 ? vbdLevelPassSweep(count - 1, iterations, passes) : 0;
    return std::max({translationSweeps, lastPass, 0});
}

// ω after sweep n of a vbd step whose first `start` sweeps come before Chebyshev's sequence
// (vbdChebyshevStart): sweep n is its iteration n − start.
inline double vbdChebyshevOmega(int n, int start, double rho, double previous) {
    return chebyshevOmega(n - start, rho, previous);
}

// The translation's levels that run on an nu × nv grid: `levels`, and more while the finest
// blocks are wider than `blockWidth` vertices (0: no more), up to 16; 0 where `levels` is 0. With
// 8 sweeps and 2 passes at Δt = 1/60, 1/120 and 1/240 s, blocks 16 wide held the dropped cotton
// sheet of 256², 512² and 1024² vertices (N Δt ≈ 4.3 s), where blocks 32 and 64 wide tore it at
// 512² and 1024² (docs/integrators.md "The translation's levels").
inline int vbdTranslationLevels(int levels, int blockWidth, int nu, int nv) {
    if (levels <= 0) return 0;
    const std::int64_t widest = std::max(nu, nv);
    while (blockWidth > 0 && levels < 16 && widest > (std::int64_t(blockWidth) << levels)) ++levels;
    return levels;
}

// The parts a side of the finest of the translation's `levels` (level l cuts an nu × nv grid
// into 2^l × 2^l blocks) that runs: 2^levels, or fewer where a block would be narrower than 2
// vertices; 1 where no level runs.
inline int vbdLevelParts(int levels, int nu, int nv) {
    int parts = 1;
    for (int l = 1; l <= levels && 4 * parts <= std::min(nu, nv); ++l) parts *= 2;
    return parts;
}

// What a vbd step's translation levels come to on an nu × nv grid (what validate and the viewer
// say): the levels that run (vbdTranslationLevels, as far as blocks stay at least 2 vertices
// wide) and the widest finest block's vertices along u and v.
struct VbdLevelsRun {
    int levels = 0, width = 0, height = 0;
};
inline VbdLevelsRun vbdLevelsRun(int levels, int blockWidth, int nu, int nv) {
    const int parts = vbdLevelParts(vbdTranslationLevels(levels, blockWidth, nu, nv), nu, nv);
    VbdLevelsRun run{0, (nu + parts - 1) / parts, (nv + parts - 1) / parts};
    while ((1 << run.levels) < parts) ++run.levels;
    return run;
}

}  // namespace cloth
