// A rigid sheet falling with drag 10 m above the origin at Δt = 0.2 ms, where h² g (0.39 µm) is
// below half an ulp of a float coordinate (0.48 µm): the case that shows whether a solver's
// velocity comes from a rounded difference of positions. Backward Euler's closed form is
// v_{n+1} = (v_n + h g)/(1 + h c), and the fall Σ h v_n.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/solver.h"

namespace cloth {

struct FarFall {
    static constexpr double kDrag = 4, kGravity = 9.81, kStep = 2e-4, kHeight = 10;
    static constexpr int kSteps = 5000;  // 1 s
    double speedError = 0;  // the largest |v − v_closed| / v_closed over the vertices
    double fallError = 0;   // the largest |fall − fall_closed| [m]
    // Half an ulp of a float at 10 m, once a step [m]: the rounding of x_n + Δx.
    double roundingBound = 0.5 * std::ldexp(1.0, std::ilogb(kHeight) - 23) * kSteps;
};

// 12 × 10 vertices (rows inside the sheet too), 10 g each, vbd with `iterations` sweeps.
inline Scene farFallScene(int iterations = 3) {
    Scene scene;
    scene.cloth.nu = 12;
    scene.cloth.nv = 10;
    scene.cloth.mass = 0.01;
    scene.cloth.origin.y = FarFall::kHeight;
    scene.damping = FarFall::kDrag * scene.cloth.mass;  // μ = c m
    scene.integrator.method = Method::Vbd;
    scene.integrator.dt = FarFall::kStep;
    scene.integrator.iterations = iterations;
    return scene;
}

// Runs `solver` (built on farFallScene) for 1 s and compares it with the closed form.
inline FarFall measureFarFall(Solver& solver, const char* what) {
    const double h = FarFall::kStep;
    double v = 0, fall = 0;
    for (int n = 1; n <= FarFall::kSteps; ++n) {
        v = (v + h * FarFall::kGravity) / (1 + h * FarFall::kDrag);
        fall += h * v;
    }
    const SimState start = solver.read();
    FarFall f;
    if (solver.step(FarFall::kSteps).unstable) {
        f.speedError = f.fallError = INFINITY;
        return f;
    }
    const SimState s = solver.read();
    for (std::size_t k = 0; k < s.positions.size(); ++k) {
        f.speedError = std::max(f.speedError, std::abs(-s.velocities[k].y - v) / v);
        f.fallError =
            std::max(f.fallError, std::abs(start.positions[k].y - s.positions[k].y - fall));
    }
    std::printf(
        "%s after 1 s at %g m: v %.7g m/s (closed form %.7g), worst relative speed error "
        "%.3g, worst fall error %.3g m (half an ulp a step: %.3g m)\n",
        what, FarFall::kHeight, -s.velocities[0].y, v, f.speedError, f.fallError, f.roundingBound);
    return f;
}

}  // namespace cloth
