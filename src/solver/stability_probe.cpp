#include "solver/stability_probe.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "model/stability.h"
#include "model/stiffness.h"
#include "model/vertex_masses.h"
#include "solver/diagnostics.h"

namespace cloth {
namespace {

// The start of every trial, and what the explicit-Euler energy test needs.
struct Trial {
    Scene scene;     // the linearised scene; Δt and max_speed change per trial
    SimState start;  // the solver's rest positions and the kick's velocities
    std::vector<std::uint8_t> pinned;
    std::vector<StencilSpring<double>> springs;
    std::vector<double> mass;  // m_k [kg]
    double qStart = 0;
};

// Shortest rest length of a modelled spring [m] (1 when none is modelled).
double shortestSpring(const Scene& scene) {
    const Grid g = scene.grid();
    double shortest = 0;
    for (const SpringOffset& o : kSpringOffsets) {
        const double l = g.restLength(o.di, o.dj);
        if (familyModelled(scene, o.family) && l > 0 && (shortest == 0 || l < shortest))
            shortest = l;
    }
    return shortest > 0 ? shortest : 1;
}

// Velocities along the stiffest mode, scaled to a displacement amplitude a = kick·L_min (speed
// a·ω, ω² the mode's eigenvalue of M⁻¹H), plus 1e-4 of that speed in random directions on every
// free vertex: those reach the modes the stiff shape leaves out, such as the out-of-plane ones
// whose limit is cΔt < 2.
std::vector<glm::dvec3> kickVelocities(const Scene& scene, const std::vector<std::uint8_t>& pinned,
                                       const ProbeOptions& o) {
    const StiffMode mode = stiffestMode(scene, o.powerIterations);
    const double c = scene.dampingRate();
    const double omega = std::max({std::sqrt(mode.omega2), c, 1.0});
    const double speed = o.kick * shortestSpring(scene) * omega;
    double largest = 0;
    for (const glm::dvec3& s : mode.shape) largest = std::max(largest, glm::length(s));
    std::mt19937_64 random(12345);
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<glm::dvec3> v(pinned.size(), glm::dvec3(0));
    for (std::size_t k = 0; k < v.size(); ++k) {
        // Drawn in a fixed order (z first, as GCC evaluated the arguments before), so that every
        // compiler gives the same kick.
        const double z = uniform(random), y = uniform(random), x = uniform(random);
        const glm::dvec3 noise(x, y, z);
        if (pinned[k]) continue;
        if (largest > 0) v[k] = mode.shape[k] * (speed / largest);
        v[k] += 1e-4 * speed * noise;
    }
    return v;
}

// Q = Σ m_k (|v_k|² + c⟨x_k, v_k⟩) + ⟨x, H x⟩ over the free vertices, x = position − rest, H at
// rest: the quadratic form explicit Euler scales by det(A) each step, mode by mode (see the
// header).
double explicitEulerEnergy(const Trial& t, const SimState& s) {
    const std::size_t n = s.positions.size();
    std::vector<glm::dvec3> x(n), hx(n);
    for (std::size_t k = 0; k < n; ++k) x[k] = s.positions[k] - t.start.positions[k];
    stiffnessProduct(s.nu, s.nv, t.springs, t.start.positions.data(), x.data(), t.pinned.data(),
                     hx.data(), 0, std::int64_t(n),
                     bendingWeights(t.scene.grid(), t.scene.bendingStiffness()));
    const double c = t.scene.dampingRate();
    double q = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (t.pinned[k]) continue;
        const glm::dvec3& v = s.velocities[k];
        q += t.mass[k] * (glm::dot(v, v) + c * glm::dot(x[k], v)) + glm::dot(x[k], hx[k]);
    }
    return q;
}

Trial prepareTrial(const Scene& linear, Solver& solver, const ProbeOptions& o) {
    Trial t;
    t.scene = linear;
    const Grid g = linear.grid();
    t.pinned.assign(std::size_t(g.count()), 0);
    for (const Pin& p : linear.pins) t.pinned[std::size_t(g.index(p.i, p.j))] = 1;
    t.springs = activeSprings<double>(linear);
    t.mass = vertexMasses(linear);
    t.start = solver.read();  // rest, as the solver's precision rounds it
    t.start.velocities = kickVelocities(linear, t.pinned, o);
    double fastest = 0;
    for (const glm::dvec3& v : t.start.velocities) fastest = std::max(fastest, glm::length(v));
    t.scene.maxSpeed = fastest * std::min(kRunaway, kLinearReach / o.kick);
    t.qStart = explicitEulerEnergy(t, t.start);
    return t;
}

bool trialStable(Solver& solver, Trial& t, double dt, const ProbeOptions& o, ProbeResult& r) {
    t.scene.integrator.dt = dt;
    solver.setParameters(t.scene);  // Δt and max_speed
    solver.write(t.start);
    solver.resetStepCount();
    const double wanted = std::min(o.trialTime / dt, double(o.maxSteps));
    const long n = std::max(o.minSteps, std::lround(wanted));
    const StepResult step = solver.step(n);
    ++r.trials;
    r.steps += step.stepsTaken;
    if (step.unstable) return false;
    const SimState end = solver.read();
    if (!allFinite(end)) return false;
    if (t.scene.integrator.method != Method::ExplicitEuler) return true;
    return std::abs(explicitEulerEnergy(t, end)) <= t.qStart;
}

}  // namespace

const char* probeStatusName(ProbeStatus s) {
    switch (s) {
        case ProbeStatus::Bounded:
            return "bounded";
        case ProbeStatus::StableToCap:
            return "stable_to_cap";
        case ProbeStatus::UnstableEverywhere:
            return "unstable_everywhere";
    }
    return "?";
}

Scene linearisedAboutRest(const Scene& scene, Method method) {
    Scene s = scene;
    s.gravity = glm::dvec3(0);
    s.wind.reset();
    s.colliders.clear();
    s.integrator.method = method;
    return s;
}

ProbeResult probeStableDt(const Scene& scene, Method method, double startDt,
                          const SolverMaker& make, const ProbeOptions& o) {
    const Scene linear = linearisedAboutRest(scene, method);
    std::unique_ptr<Solver> solver = make(linear);
    Trial t = prepareTrial(linear, *solver, o);
    ProbeResult r;
    // A solver that has reported an unstable step is not trusted again (the CPU solver keeps
    // reporting it after a write()): the next trial gets a new one.
    auto stable = [&](double dt) {
        if (!solver) solver = make(t.scene);
        const bool ok = trialStable(*solver, t, dt, o, r);
        if (!ok) solver.reset();
        return ok;
    };

    double lo = 0, hi = 0;  // largest stable, smallest unstable found
    const double start = std::isfinite(startDt) && startDt > 0 ? std::min(startDt, o.cap) : o.cap;
    if (stable(start)) {
        lo = start;
        while (lo < o.cap && hi == 0) {
            const double dt = std::min(2 * lo, o.cap);
            (stable(dt) ? lo : hi) = dt;
        }
        if (hi == 0) r.status = ProbeStatus::StableToCap;
    } else {
        hi = start;
        while (lo == 0 && hi / 2 >= o.floor) {
            const double dt = hi / 2;
            (stable(dt) ? lo : hi) = dt;
        }
        if (lo == 0) r.status = ProbeStatus::UnstableEverywhere;
    }
    while (lo > 0 && hi > 0 && hi > lo * (1 + o.tolerance)) {
        const double mid = std::sqrt(lo * hi);
        (stable(mid) ? lo : hi) = mid;
    }
    r.stableDt = lo;
    r.unstableDt = hi;
    return r;
}

}  // namespace cloth
