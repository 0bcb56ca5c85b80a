#include "model/stability.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <vector>

#include "model/stiffness.h"
#include "model/vertex_masses.h"

namespace cloth {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// |R(z)| ≤ 1 for RK4's amplification R(z) = 1 + z + z²/2 + z³/6 + z⁴/24.
bool rk4Stable(std::complex<double> z) {
    const std::complex<double> r = 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6 + z / 24.0)));
    return std::abs(r) <= 1.0 + 1e-12;
}

// The mode x'' = −ω² x − c x' has eigenvalues −c/2 ± sqrt(c²/4 − ω²).
bool rk4ModeStable(double h, double w2, double c) {
    const std::complex<double> disc = std::sqrt(std::complex<double>(c * c / 4 - w2, 0));
    return rk4Stable(h * (-c / 2 + disc)) && rk4Stable(h * (-c / 2 - disc));
}

// Largest h with every mode ω² in [0, w2max] stable, by bisection (RK4's region is an interval
// along each ray; 64 sampled ω² cover the modes between the rigid and the stiffest one).
// With spring damping β each sampled mode ω² is damped at c + βω².
double rk4Dt(double w2max, double c, double beta) {
    if (w2max <= 0 && c <= 0) return kInf;
    auto stable = [&](double h) {
        for (int s = 0; s <= 64; ++s) {
            const double w2 = w2max * s / 64.0;
            if (!rk4ModeStable(h, w2, beta > 0 ? c + beta * w2 : c)) return false;
        }
        return true;
    };
    double lo = 0, hi = 1;
    while (stable(hi)) {
        lo = hi;
        hi *= 2;
        if (hi > 1e30) return kInf;
    }
    for (int it = 0; it < 100; ++it) {
        const double mid = 0.5 * (lo + hi);
        (stable(mid) ? lo : hi) = mid;
    }
    return lo;
}

}  // namespace

// Power iteration on M⁻¹H at the rest state, with Rayleigh quotients pᵀHp/pᵀMp: M⁻¹H is
// self-adjoint in the M inner product, so they bound ω²_max from below.
StiffMode stiffestMode(const Scene& scene, int iterations) {
    const Grid g = scene.grid();
    const std::int64_t n = g.count();
    std::vector<std::uint8_t> pinned(std::size_t(n), 0);
    for (const Pin& p : scene.pins) pinned[std::size_t(g.index(p.i, p.j))] = 1;
    const std::vector<double> mass = vertexMasses(scene);
    const std::size_t size = std::size_t(n);
    std::vector<glm::dvec3> x(size), p(size), y(size);
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) {
            const std::size_t k = std::size_t(g.index(i, j));
            x[k] = g.restPosition(i, j);
            // Sign patterns alternating along u, along v and along both: the stiffest modes of
            // a stencil like this one; plus a ripple so that no mode starts at zero.
            const double su = (i % 2 == 0) ? 1.0 : -1.0, sv = (j % 2 == 0) ? 1.0 : -1.0;
            const double r = 0.1 * std::sin(0.7 * i + 1.3 * j);
            const glm::dvec3 start = su * g.u + sv * g.v + su * sv * glm::cross(g.u, g.v);
            p[k] = pinned[k] ? glm::dvec3(0) : start + glm::dvec3(r, -r, 0.5 * r);
        }
    StiffMode mode;
    const auto springs = activeSprings<double>(scene);
    const BendingWeights bending = bendingWeights(g, scene.bendingStiffness());
    if (springs.empty() && !bending.active()) return mode;
    for (int it = 0; it < iterations; ++it) {
        stiffnessProduct(g.nu, g.nv, springs, x.data(), p.data(), pinned.data(), y.data(), 0, n,
                         bending);
        double pp = 0, pmp = 0, py = 0, yy = 0;
        for (std::size_t k = 0; k < p.size(); ++k) {
            pp += glm::dot(p[k], p[k]);
            pmp += mass[k] * glm::dot(p[k], p[k]);
            py += glm::dot(p[k], y[k]);
            y[k] /= mass[k];  // M⁻¹H p
            yy += glm::dot(y[k], y[k]);
        }
        if (!(pp > 0) || !(yy > 0)) break;
        mode.lambda = std::max(mode.lambda, py / pp);
        mode.omega2 = std::max(mode.omega2, py / pmp);
        const double scale = 1 / std::sqrt(yy);
        for (std::size_t k = 0; k < p.size(); ++k) p[k] = y[k] * scale;
    }
    mode.shape = std::move(p);
    return mode;
}

double methodDt(Method method, double omega2, double c) {
    return dampedMethodDt(method, omega2, c, 0);
}

double dampedMethodDt(Method method, double omega2, double c, double beta) {
    if (beta > 0 && omega2 > 0) {
        if (method == Method::Verlet) {  // leapfrog with the drag βω² at v_half
            // (−b + √(b² + 4ω²))/ω², written without the cancellation at b² ≫ ω² and without
            // squaring b (hypot): spring damping of 1e200 gave 0/0 or ∞ before.
            const double b = beta * omega2;
            return 4 / (b + std::hypot(b, 2 * std::sqrt(omega2)));
        }
        // The stiffest mode's rate: explicit Euler's Δt < c_ω/ω² = c/ω² + β and c_ω Δt < 2,
        // symplectic Euler's ω²Δt² + 2c_ω Δt < 4 all bind there.
        if (method != Method::Rk4) c += beta * omega2;
    }
    const double drag = c > 0 ? 2 / c : kInf;  // the rigid mode: |1 − cΔt| ≤ 1
    switch (method) {
        case Method::ExplicitEuler:
            // det = 1 − cΔt + ω²Δt² < 1  ⇔  Δt < c/ω².
            if (omega2 <= 0) return drag;
            return std::min(c / omega2, drag);
        case Method::SymplecticEuler:
            // (−c + √(c² + 4ω²))/ω², in the same cancellation-free form as Verlet's.
            return omega2 > 0 ? 4 / (c + std::hypot(c, 2 * std::sqrt(omega2))) : drag;
        case Method::Verlet:
            return omega2 > 0 ? 2 / std::sqrt(omega2) : kInf;
        case Method::Rk4:
            return rk4Dt(omega2, c, beta);
        case Method::ImplicitEuler:
            return kInf;
        case Method::Vbd:  // a descent on backward Euler's potential: no Δt bound of its own
            return kInf;
    }
    return 0;
}

double methodDt(Method method, double lambda, double mass, double damping) {
    return methodDt(method, lambda / mass, damping / mass);
}

double StabilityBound::safeDt(Method method) const {
    return dampedMethodDt(method, omega2Max, dampingRate, springDamping);
}

double StabilityBound::tightDt(Method method) const {
    return dampedMethodDt(method, omega2Power > 0 ? omega2Power : omega2Max, dampingRate,
                          springDamping);
}

StabilityBound estimateStability(const Scene& scene, int powerIterations) {
    const Grid g = scene.grid();
    std::vector<std::uint8_t> pinned(std::size_t(g.count()), 0);
    for (const Pin& p : scene.pins) pinned[std::size_t(g.index(p.i, p.j))] = 1;
    double stiffness[kSpringOffsets.size()];
    for (std::size_t s = 0; s < kSpringOffsets.size(); ++s)
        stiffness[s] = scene.slotStiffness(int(s));
    StabilityBound b;
    // The bending Hessian's rows add at most 16·(w_u + w_v + t) (model/bending.h).
    const double bendingRow = bendingLambdaBound(bendingWeights(g, scene.bendingStiffness()));
    for (int j = 0; j < g.nv; ++j) {
        for (int i = 0; i < g.nu; ++i) {
            if (pinned[std::size_t(g.index(i, j))]) continue;
            double row = bendingRow;  // |diagonal| + Σ |off-diagonal| of this vertex's block row
            for (std::size_t s = 0; s < kSpringOffsets.size(); ++s) {
                const int qi = i + kSpringOffsets[s].di, qj = j + kSpringOffsets[s].dj;
                if (!g.contains(qi, qj)) continue;
                const double k = std::abs(stiffness[s]);
                row += pinned[std::size_t(g.index(qi, qj))] ? k : 2 * k;
            }
            b.lambdaMax = std::max(b.lambdaMax, row);
            b.omega2Max = std::max(b.omega2Max, row / scene.vertexMass(i, j));
        }
    }
    b.dampingRate = scene.dampingRate();
    b.springDamping = scene.springDamping();
    if (powerIterations > 0) {
        const StiffMode mode = stiffestMode(scene, powerIterations);
        b.lambdaPower = mode.lambda;
        b.omega2Power = mode.omega2;
    }
    b.explicitEulerDt = b.safeDt(Method::ExplicitEuler);
    b.symplecticEulerDt = b.safeDt(Method::SymplecticEuler);
    return b;
}

double stableDt(const Scene& scene) {
    return estimateStability(scene).safeDt(scene.integrator.method);
}

namespace {

std::optional<double> halfBound(double bound) {
    if (std::isinf(bound) || !(bound > 0)) return std::nullopt;
    return 0.5 * bound;
}

}  // namespace

std::optional<double> suggestedDt(const Scene& scene) {
    return halfBound(stableDt(scene));
}

std::string stabilityAdvice(const Scene& scene) {
    const StabilityBound b = estimateStability(scene);
    const double bound = stableDt(scene), dt = scene.integrator.dt;
    const double suggested = halfBound(bound).value_or(0);  // where the advice names a Δt
    char buf[400];
    if (std::isinf(bound)) {
        std::snprintf(buf, sizeof buf,
                      "%s is stable at any dt for the linear spring model; an unstable run "
                      "points at the nonlinear terms or the wind: try a smaller dt",
                      methodName(scene.integrator.method));
    } else if (bound > 0 && scene.material) {
        std::snprintf(buf, sizeof buf,
                      "predicted stable dt < %.3g s for %s (omega_max^2 <= %.4g 1/s^2, "
                      "air_damping %g 1/s, spring_damping %g s); try --set integrator.dt=%.2g",
                      bound, methodName(scene.integrator.method), b.omega2Max, b.dampingRate,
                      b.springDamping, suggested);
    } else if (bound > 0) {
        std::snprintf(buf, sizeof buf,
                      "predicted stable dt < %.3g s for %s (lambda_max <= %.4g N/m, damping %g); "
                      "try --set integrator.dt=%.2g",
                      bound, methodName(scene.integrator.method), b.lambdaMax, scene.damping,
                      suggested);
    } else if (scene.material) {  // explicit Euler is stable iff c/ω²_max + β > Δt
        std::snprintf(buf, sizeof buf,
                      "explicit Euler has no stable dt without damping (every spring mode grows); "
                      "at dt = %g s it needs air_damping > omega_max^2*dt = %.3g 1/s or "
                      "spring_damping > dt: try --set material.spring_damping=%.2g, or another "
                      "integrator (--set integrator.method=\"verlet\")",
                      dt, b.omega2Max * dt, 2 * dt);
    } else {
        std::snprintf(buf, sizeof buf,
                      "explicit Euler has no stable dt without damping (every spring mode grows); "
                      "at dt = %g s it needs damping > lambda_max*dt = %.3g N*s/m: try --set "
                      "damping=%.2g, or another integrator (--set integrator.method=\"verlet\")",
                      dt, b.lambdaMax * dt, 2 * b.lambdaMax * dt);
    }
    return buf;
}

std::optional<std::string> dtWarning(const Scene& scene) {
    const double bound = stableDt(scene), dt = scene.integrator.dt;
    if (std::isinf(bound) || (bound > 0 && dt < bound)) return std::nullopt;
    char buf[400];
    if (bound > 0)
        std::snprintf(buf, sizeof buf,
                      "integrator.dt = %.3g s is beyond %s's predicted stability bound %.3g s: the "
                      "run may leave physics; lower integrator.dt",
                      dt, methodName(scene.integrator.method), bound);
    else if (scene.material)
        std::snprintf(buf, sizeof buf,
                      "explicit_euler has no stable integrator.dt at air_damping %g 1/s and "
                      "spring_damping %g s: the run may leave physics; raise "
                      "material.spring_damping or change integrator.method",
                      scene.dampingRate(), scene.springDamping());
    else
        std::snprintf(buf, sizeof buf,
                      "explicit_euler has no stable integrator.dt at damping %g: the run may leave "
                      "physics; raise damping or change integrator.method",
                      scene.damping);
    return std::string(buf);
}

}  // namespace cloth
