#include "core/stability.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace cloth {

StabilityBound estimateStability(const Scene& scene) {
    const Grid g = scene.grid();
    std::vector<std::uint8_t> pinned(g.count(), 0);
    for (const Pin& p : scene.pins) pinned[g.index(p.i, p.j)] = 1;
    double lambda = 0;
    for (int j = 0; j < g.nv; ++j) {
        for (int i = 0; i < g.nu; ++i) {
            if (pinned[g.index(i, j)]) continue;
            double row = 0;  // |diagonal| + Σ |off-diagonal| of this vertex's 3×3 block row
            for (const SpringOffset& o : kSpringOffsets) {
                const int qi = i + o.di, qj = j + o.dj;
                if (!g.contains(qi, qj)) continue;
                const double k = scene.springs.of(o.family);
                row += pinned[g.index(qi, qj)] ? k : 2 * k;
            }
            lambda = std::max(lambda, row);
        }
    }
    StabilityBound b;
    b.lambdaMax = lambda;
    const double m = scene.cloth.mass, mu = scene.damping, c = mu / m;
    const double inf = std::numeric_limits<double>::infinity();
    // det = 1 − cΔt + (λ/m)Δt² < 1  ⇔  Δt < μ/λ; the rigid mode needs |1 − cΔt| ≤ 1.
    const double eulerSprings = lambda > 0 ? mu / lambda : inf;
    const double eulerDrag = mu > 0 ? 2 / c : inf;
    b.explicitEulerDt = std::min(eulerSprings, eulerDrag);
    const double w2 = lambda / m;
    b.symplecticEulerDt = w2 > 0 ? (-c + std::sqrt(c * c + 4 * w2)) / w2 : eulerDrag;
    return b;
}

double stableDt(const Scene& scene) {
    const StabilityBound b = estimateStability(scene);
    switch (scene.integrator.method) {
        case Method::ExplicitEuler:
            return b.explicitEulerDt;
    }
    return b.explicitEulerDt;
}

std::string stabilityAdvice(const Scene& scene) {
    const StabilityBound b = estimateStability(scene);
    const double bound = stableDt(scene);
    char buf[300];
    if (bound > 0) {
        std::snprintf(buf, sizeof buf,
                      "predicted stable dt < %.3g s for %s (lambda_max <= %.4g N/m, damping %g); "
                      "try --set integrator.dt=%.2g",
                      bound, methodName(scene.integrator.method), b.lambdaMax, scene.damping,
                      0.5 * bound);
    } else {
        std::snprintf(buf, sizeof buf,
                      "explicit Euler has no stable dt without damping (every spring mode grows); "
                      "at dt = %g s it needs damping > lambda_max*dt = %.3g N*s/m: try --set "
                      "damping=%.2g",
                      scene.integrator.dt, b.lambdaMax * scene.integrator.dt,
                      2 * b.lambdaMax * scene.integrator.dt);
    }
    return buf;
}

}  // namespace cloth
