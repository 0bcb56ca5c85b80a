// The five integrators of docs/integrators.md, each written out as the page writes it, on whole
// arrays: every stage finishes for all vertices before the next one starts.
#include <cmath>

#include "reference/reference.h"
#include "reference/vector_ops.h"

namespace ref {

// explicit_euler (DESIGN.md §2, seed eq. (6)): v += h a(x, v); x += h v_old.
void Simulation::stepExplicitEuler() {
    const double h = prm_.dt;
    const std::vector<V3> a = accelerations(p_, v_);
    for (std::size_t k = 0; k < p_.size(); ++k) {
        const V3 vOld = v_[k];
        v_[k] = add(vOld, scale(h, a[k]));
        p_[k] = add(p_[k], scale(h, vOld));
    }
    pinAndCollide(p_, v_);
}

// symplectic_euler: v += h a(x, v); x += h v_new.
void Simulation::stepSymplecticEuler() {
    const double h = prm_.dt;
    const std::vector<V3> a = accelerations(p_, v_);
    for (std::size_t k = 0; k < p_.size(); ++k) {
        v_[k] = add(v_[k], scale(h, a[k]));
        p_[k] = add(p_[k], scale(h, v_[k]));
    }
    pinAndCollide(p_, v_);
}

// verlet: kick (damping at v_n), drift, pins and colliders on (x_{n+1}, v_half), forces at the
// projected x_{n+1}, kick with the damping taken at v_{n+1} (solved per vertex), pins. F(x_n) is
// recomputed here rather than kept from the previous step: the same numbers, since nothing moves
// x between the two. With spring damping the force depends on v too: the second kick's
// F(x_{n+1}, v_half) is kept and is the next step's first kick's (docs/integrators.md), as the
// solvers evaluate the forces once a step.
void Simulation::stepVerlet() {
    const double h = prm_.dt;
    std::vector<V3> a = accelerations(p_, v_);
    if (!verletForces_.empty()) {
        for (std::size_t k = 0; k < p_.size(); ++k) {
            if (pinned_[k]) continue;
            const V3 f = sub(verletForces_[k], scale(drag(int(k)), v_[k]));
            a[k] = add(scale(1.0 / mass_[k], f), prm_.gravity);
        }
    }
    std::vector<V3> vHalf(v_.size());
    for (std::size_t k = 0; k < p_.size(); ++k) {
        vHalf[k] = add(v_[k], scale(h / 2, a[k]));
        p_[k] = add(p_[k], scale(h, vHalf[k]));
    }
    pinAndCollide(p_, vHalf);
    std::vector<V3> f = forces(p_);
    addSpringDamping(p_, vHalf, f);
    if (prm_.springDamping != 0) verletForces_ = f;
    for (std::size_t k = 0; k < p_.size(); ++k) {
        const double m = mass_[k], mu = drag(int(k));
        const V3 kick = scale(h / 2, add(scale(1.0 / m, f[k]), prm_.gravity));
        v_[k] = scale(1.0 / (1 + h * mu / (2 * m)), add(vHalf[k], kick));
    }
    pin(p_, v_);
}

// rk4 on y = (x, v), y' = (v, a(x, v)); pinned vertices keep x_pin and v = 0 in every stage;
// pins and colliders act on y_{n+1} only.
void Simulation::stepRk4() {
    const double h = prm_.dt;
    const std::size_t n = p_.size();
    const std::vector<V3> x0 = p_, v0 = v_;
    const double offset[4] = {0, h / 2, h / 2, h};  // stage s is evaluated at y_n + offset·k_{s−1}
    std::vector<V3> kx[4], kv[4];
    std::vector<V3> xs = x0, vs = v0;
    for (int s = 0; s < 4; ++s) {
        if (s > 0) {
            for (std::size_t k = 0; k < n; ++k) {
                xs[k] = add(x0[k], scale(offset[s], kx[s - 1][k]));
                vs[k] = add(v0[k], scale(offset[s], kv[s - 1][k]));
            }
            pin(xs, vs);
        }
        kx[s] = vs;
        kv[s] = accelerations(xs, vs);
    }
    for (std::size_t k = 0; k < n; ++k) {
        const V3 dx = add(add(kx[0][k], scale(2, kx[1][k])), add(scale(2, kx[2][k]), kx[3][k]));
        const V3 dv = add(add(kv[0][k], scale(2, kv[1][k])), add(scale(2, kv[2][k]), kv[3][k]));
        p_[k] = add(x0[k], scale(h / 6, dx));
        v_[k] = add(v0[k], scale(h / 6, dv));
    }
    pinAndCollide(p_, v_);
}

// implicit_euler (Baraff & Witkin 1998), linearised once at x_n:
// ((m_k + hμ_k) I + h D + h² H) Δv = h (F(x_n) + F_β(x_n, v_n) − μ_k v_n + m_k g − h H v_n);
// v += Δv; x += h v_new. D = −∂F_β/∂v, the spring damping's (its ∂F_β/∂x is left out, as
// Baraff & Witkin do).
void Simulation::stepImplicitEuler() {
    const double h = prm_.dt;
    std::vector<V3> f = forces(p_);
    addSpringDamping(p_, v_, f);
    const std::vector<V3> hv = hessianProduct(p_, v_, true);  // a follow pin's v_n counts
    std::vector<V3> b(p_.size(), V3{0, 0, 0});
    // Contacts in the solve (docs/integrators.md, "Contact in the solve"): the prediction
    // p* = x + h (v + h g), v* = v + h g through the colliders; a vertex they push out by d gets
    // n = d/|d| and ⟨n, Δv⟩ = ⟨n, p' − x⟩/h − ⟨n, v⟩. Friction by the grip of the last step
    // (grip_): held (< 0), the tangential velocity is fixed to the collider's v_c; sliding (> 0),
    // the response with the approach J_n/m of the last solve takes its friction from v*'s
    // tangential part, an impulse in b; new (0), the response on v* itself does.
    std::vector<V3> normal(p_.size(), V3{0, 0, 0}), fixed(p_.size(), V3{0, 0, 0});
    std::vector<bool> held(p_.size(), false), stuck(p_.size(), false);
    for (std::size_t k = 0; k < p_.size(); ++k) {
        if (pinned_[k]) continue;  // the pinned rows are removed: Δv = 0 there
        const V3 rhs = add(sub(f[k], scale(drag(int(k)), v_[k])), scale(mass_[k], prm_.gravity));
        b[k] = scale(h, sub(rhs, scale(h, hv[k])));
        const V3 vStar = add(v_[k], scale(h, prm_.gravity));
        const V3 pStar = add(p_[k], scale(h, vStar));
        V3 p = pStar, w = vStar;
        applyColliders(p, w);
        const V3 d = sub(p, pStar);
        if (norm(d) == 0) continue;
        const V3 n = scale(1 / norm(d), d);
        normal[k] = n;
        const double z = dot(n, sub(p, p_[k])) / h - dot(n, v_[k]);
        fixed[k] = scale(z, n);
        const V3 slide = tangential(n, vStar), still = tangential(n, surfaceVelocity(pStar));
        if (grip_[k] < 0) {
            held[k] = true;
            fixed[k] = add(fixed[k], sub(still, tangential(n, v_[k])));
            continue;
        }
        const V3 kept =
            grip_[k] > 0 ? coulomb(pStar, n, slide, grip_[k] / mass_[k]) : tangential(n, w);
        // Held next step where the response stuck (returned v_c) and the vertex did not already
        // move with the surface.
        auto same = [](const V3& a, const V3& c) {
            return a[0] == c[0] && a[1] == c[1] && a[2] == c[2];
        };
        stuck[k] = same(kept, still) && !same(slide, still);
        b[k] = add(b[k], scale(mass_[k], sub(kept, slide)));
    }
    const std::vector<V3> dv = solveImplicitSystem(p_, b, normal, held, fixed);
    // The grips of the next step from each contact's impulse J = (A Δv)_k − b_k.
    const std::vector<V3> adv = systemProduct(p_, dv);
    for (std::size_t k = 0; k < p_.size(); ++k) {
        const V3& n = normal[k];
        const V3 impulse = sub(adv[k], b[k]);
        const double jn = dot(n, impulse);
        if (pinned_[k] || norm(n) == 0 || !(jn > 0)) {
            grip_[k] = 0;
            continue;
        }
        if (!held[k]) {
            grip_[k] = stuck[k] ? -jn : jn;
            continue;
        }
        // Held while Coulomb's law with J_n supplies J_t: the response on the velocity without
        // J_t, at the approach J_n/m, removes all of J_t/m.
        const V3 jt = scale(1 / mass_[k], tangential(n, impulse));
        const V3 free = sub(add(tangential(n, v_[k]), tangential(n, dv[k])), jt);
        const V3 pStar = add(p_[k], scale(h, add(v_[k], scale(h, prm_.gravity))));
        const V3 kept = coulomb(pStar, n, free, jn / mass_[k]);
        grip_[k] = norm(sub(kept, free)) >= 0.999 * norm(jt) ? -jn : jn;
    }
    // The end of step lands on the surface; a contact keeps no normal velocity away from it
    // faster than the surface moves (a vertex that started inside leaves at rest).
    for (std::size_t k = 0; k < p_.size(); ++k) {
        const V3 vNew = add(v_[k], dv[k]),
                 pStar = add(p_[k], scale(h, add(v_[k], scale(h, prm_.gravity))));
        p_[k] = add(p_[k], scale(h, vNew));
        v_[k] = vNew;
        if (norm(normal[k]) == 0) continue;
        const double away = dot(normal[k], sub(vNew, surfaceVelocity(pStar)));
        if (away > 0) v_[k] = sub(vNew, scale(away, normal[k]));
    }
    pinAndCollide(p_, v_);
}

// The colliders' Coulomb law at p* on a tangential velocity `slide` approaching the surface at
// `approach`: the tangential velocity their response leaves (a first run finds the collider's
// normal velocity).
V3 Simulation::coulomb(const V3& pStar, const V3& n, const V3& slide, double approach) const {
    V3 q = pStar, w = slide;
    applyColliders(q, w);
    q = pStar;
    w = add(slide, scale(dot(n, w) - approach, n));
    applyColliders(q, w);
    return tangential(n, w);
}

// A w = (m_k + hμ_k) w + h D w + h² H w, pinned rows 0.
std::vector<V3> Simulation::systemProduct(const std::vector<V3>& x,
                                          const std::vector<V3>& w) const {
    const double h = prm_.dt;
    std::vector<V3> y = hessianProduct(x, w);
    std::vector<V3> damping(x.size(), V3{0, 0, 0});  // −D w: w is 0 on pinned vertices
    addSpringDamping(x, w, damping);
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double diagonal = mass_[k] + h * drag(int(k));
        y[k] = pinned_[k]
                   ? V3{0, 0, 0}
                   : sub(add(scale(diagonal, w[k]), scale(h * h, y[k])), scale(h, damping[k]));
    }
    return y;
}

// Conjugate gradient from Δv = c (r = S (b − A c), p = r): α = r·r / p·Ap, Δv += α p,
// r −= α S Ap, stop when |r| ≤ tolerance·max(|b|, |r₀|) or after max_iterations, β = r_new·r_new /
// r·r, p = r + β p. S w = w − n ⟨n, w⟩ at a contact of normal n, 0 at a held one, c its fixed
// velocity change (0 elsewhere). Dot products run over the free vertices only; pinned entries of
// p and r stay 0.
std::vector<V3> Simulation::solveImplicitSystem(const std::vector<V3>& x, const std::vector<V3>& b,
                                                const std::vector<V3>& normal,
                                                const std::vector<bool>& held,
                                                const std::vector<V3>& fixed) {
    const std::size_t n = x.size();
    auto dotFree = [&](const std::vector<V3>& a, const std::vector<V3>& c) {
        double s = 0;
        for (std::size_t k = 0; k < n; ++k) {
            if (!pinned_[k]) s += dot(a[k], c[k]);
        }
        return s;
    };
    auto filter = [&](std::vector<V3> w) {
        for (std::size_t k = 0; k < n; ++k)
            w[k] = held[k] ? V3{0, 0, 0} : tangential(normal[k], w[k]);
        return w;
    };
    auto apply = [&](const std::vector<V3>& w) { return filter(systemProduct(x, w)); };
    std::vector<V3> dv = fixed, r = filter(b);
    const std::vector<V3> ac = apply(dv);
    for (std::size_t k = 0; k < n; ++k) r[k] = sub(r[k], ac[k]);
    const double bNorm = std::sqrt(std::fmax(dotFree(b, b), dotFree(r, r)));
    std::vector<V3> p = r;
    const double stop = prm_.cgTolerance * bNorm;
    double rr = dotFree(r, r);
    int iterations = 0;
    while (std::sqrt(rr) > stop && iterations < prm_.cgMaxIterations) {
        const std::vector<V3> ap = apply(p);
        const double alpha = rr / dotFree(p, ap);
        for (std::size_t k = 0; k < n; ++k) {
            dv[k] = add(dv[k], scale(alpha, p[k]));
            r[k] = sub(r[k], scale(alpha, ap[k]));
        }
        ++iterations;
        const double rrNew = dotFree(r, r);
        const double beta = rrNew / rr;
        for (std::size_t k = 0; k < n; ++k) p[k] = add(r[k], scale(beta, p[k]));
        rr = rrNew;
    }
    const double residual = bNorm > 0 ? std::sqrt(rr) / bNorm : 0;
    ++cg_.solves;
    cg_.iterations += iterations;
    cg_.lastIterations = iterations;
    cg_.lastResidual = residual;
    if (!(std::sqrt(rr) <= stop)) {  // stopped by the cap (or by a non-finite residual)
        ++cg_.misses;
        cg_.worstResidual = std::fmax(cg_.worstResidual, residual);
    }
    return dv;
}

}  // namespace ref
