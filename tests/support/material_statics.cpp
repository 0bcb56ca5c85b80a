#include "support/material_statics.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "model/material_presets.h"

namespace cloth {
namespace {

constexpr double kG = 9.81;  // [m/s²], the scenes' gravity, along −y

// Implicit Euler with Δt = 1 s: the system is the stiffness, M/Δt² adds ~10⁻⁶ of it; its
// conjugate gradient solved to 10⁻⁹, which moves where Newton's steps go, not where they end.
Scene staticScene(const Material& material) {
    Scene s;
    s.name = "statics";
    s.material = material;
    s.gravity = {0, -kG, 0};
    s.integrator.method = Method::ImplicitEuler;
    s.integrator.dt = 1;
    s.integrator.tolerance = 1e-9;
    s.integrator.maxIterations = 100000;
    return s;
}

Material cotton() {
    return *materialPreset("cotton");
}

}  // namespace

Scene cantileverScene(int cells, double length, double bend) {
    Material m = cotton();
    m.bend = bend;
    Scene s = staticScene(m);
    s.name = "cantilever";
    s.cloth.nu = cells + 1;
    s.cloth.nv = 3;  // on square cells: the lattice needs C ≥ G (dv/du)² (docs/physics.md)
    s.cloth.size = {length, 2 * length / cells};
    s.cloth.uAxis = {1, 0, 0};
    s.cloth.vAxis = {0, 0, 1};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < s.cloth.nv; ++j) s.pins.push_back({i, j});
    return s;
}

double cantileverFreeLength(const Scene& scene) {
    return scene.cloth.size.x - scene.grid().du;
}

double cantileverBeamSag(const Scene& scene) {
    const double q = scene.material->density * kG;
    return q * std::pow(cantileverFreeLength(scene), 4) / (8 * scene.material->bend);
}

double cantileverTipSag(const Scene& scene, const SimState& state) {
    const int nu = scene.cloth.nu, nv = scene.cloth.nv;
    double sag = 0;
    for (int j = 0; j < nv; ++j)
        sag += scene.cloth.origin.y - state.positions[std::size_t(j * nu + nu - 1)].y;
    return sag / nv;
}

double cantileverElasticaSag(const Scene& scene) {
    const double length = cantileverFreeLength(scene);
    const double a = scene.material->density * kG / scene.material->bend;  // q/B [1/m³]
    // Integrates θ' = κ, κ' = −a(L − s)cos θ, y' = sin θ from s = 0 by RK4; κ(L) and y(L).
    struct End {
        double curvature, sag;
    };
    auto shoot = [&](double curvature0) {
        const int n = 4000;
        const double h = length / n;
        double theta = 0, kappa = curvature0, y = 0;
        auto rate = [&](double s, double t, double k) {
            return glm::dvec3(k, -a * (length - s) * std::cos(t), std::sin(t));
        };
        for (int k = 0; k < n; ++k) {
            const double s = k * h;
            const glm::dvec3 k1 = rate(s, theta, kappa);
            const glm::dvec3 k2 = rate(s + h / 2, theta + h / 2 * k1.x, kappa + h / 2 * k1.y);
            const glm::dvec3 k3 = rate(s + h / 2, theta + h / 2 * k2.x, kappa + h / 2 * k2.y);
            const glm::dvec3 k4 = rate(s + h, theta + h * k3.x, kappa + h * k3.y);
            const glm::dvec3 d = (k1 + 2.0 * k2 + 2.0 * k3 + k4) * (h / 6);
            theta += d.x;
            kappa += d.y;
            y += d.z;
        }
        return End{kappa, y};
    };
    // κ(0) lies between 0 (κ(L) < 0) and the linear a L²/2 (cos θ ≤ 1, so κ(L) ≥ 0).
    double lo = 0, hi = a * length * length / 2;
    for (int k = 0; k < 60; ++k) {
        const double mid = (lo + hi) / 2;
        (shoot(mid).curvature < 0 ? lo : hi) = mid;
    }
    return shoot((lo + hi) / 2).sag;
}

Scene hangingStripScene(int cells, bool alongV) {
    Scene s = staticScene(cotton());
    s.name = alongV ? "hanging strip along v" : "hanging strip along u";
    const int across = std::max(1, cells / 8);
    s.cloth.origin = {0, 1, 0};
    if (!alongV) {
        s.cloth.nu = cells + 1;
        s.cloth.nv = across + 1;
        s.cloth.size = {1, 0.125 * across / (cells / 8.0)};
        s.cloth.uAxis = {0, -1, 0};
        s.cloth.vAxis = {1, 0, 0};
        for (int j = 0; j < s.cloth.nv; ++j) s.pins.push_back({0, j});
    } else {
        s.cloth.nu = across + 1;
        s.cloth.nv = cells + 1;
        s.cloth.size = {1.5 * across / cells, 1};  // du = 1.5 dv
        s.cloth.uAxis = {1, 0, 0};
        s.cloth.vAxis = {0, -1, 0};
        for (int i = 0; i < s.cloth.nu; ++i) s.pins.push_back({i, 0});
    }
    return s;
}

double hangingStripElongation(const Scene& scene) {
    return scene.material->density * kG / (2 * scene.material->stretch);  // L = 1 m
}

double hangingStripStretch(const Scene& scene, const SimState& state) {
    const int nu = scene.cloth.nu, nv = scene.cloth.nv;
    const bool alongV = scene.cloth.vAxis.y < 0;
    const int n = alongV ? nu : nv;
    double drop = 0;
    for (int k = 0; k < n; ++k) {
        const std::size_t at =
            alongV ? std::size_t((nv - 1) * nu + k) : std::size_t(k * nu + nu - 1);
        drop += scene.cloth.origin.y - 1 - state.positions[at].y;
    }
    return drop / n;
}

Scene hangingSheetScene(int cells) {
    Scene s = staticScene(cotton());
    s.name = "hanging sheet";
    s.cloth.nu = s.cloth.nv = cells + 1;
    s.cloth.size = {1, 1};
    s.cloth.origin = {-0.5, 1, 0};
    s.cloth.uAxis = {1, 0, 0};
    s.cloth.vAxis = {0, -1, 0};
    for (int i = 0; i <= cells; ++i)
        if (4 * i <= cells || 4 * i >= 3 * cells) s.pins.push_back({i, 0});
    return s;
}

double hangingSheetSag(const Scene& scene, const SimState& state) {
    const int nu = scene.cloth.nu, nv = scene.cloth.nv;
    return scene.cloth.origin.y - 1 - state.positions[std::size_t((nv - 1) * nu + nu / 2)].y;
}

Settled settle(Solver& solver, double tolerance, int maxSteps) {
    Settled out;
    out.state = solver.read();
    while (out.steps < maxSteps) {
        solver.step(1);
        ++out.steps;
        SimState next = solver.read();
        out.lastMove = 0;
        for (std::size_t k = 0; k < next.positions.size(); ++k)
            out.lastMove =
                std::max(out.lastMove, glm::length(next.positions[k] - out.state.positions[k]));
        out.state = std::move(next);
        if (out.lastMove <= tolerance) break;
    }
    out.iterations = solver.solveStats().iterations;
    return out;
}

}  // namespace cloth
