// Measures the largest stable Δt of an integrator on a scene, by bisection over short trials
// (`clothsim bench stability`). It tests what src/model/stability.h predicts: the linearised
// system about the rest state, so each trial runs the scene without gravity, wind and colliders
// (the rest state is then an equilibrium) from a small velocity kick along the stiffest mode.
//
// A trial at Δt is unstable when, within its steps, the state runs away (a position or velocity
// is not finite, or a speed exceeds kRunaway times the kick's, or the speed of a displacement of
// kLinearReach of the shortest spring if that is lower: past it the spring is no longer linear
// and an unstable mode grows more slowly), or, for explicit Euler only, when
// its discrete energy Q grows. Explicit Euler leaves its bound slowly (a mode grows by
// c·Δt·ε/2 per step at Δt = (1 + ε)·c/ω², c the damping rate), far too slowly to run away in a
// short trial; but for one mode of M⁻¹H (M the vertex masses, ω² its eigenvalue),
// Q = Σ_k m_k (|v_k|² + c⟨x_k, v_k⟩) + ⟨x, H x⟩ (x the displacement from rest) obeys
// Q_{n+1} = det(A)·Q_n exactly, det(A) = 1 − cΔt + ω²Δt² (docs/physics.md), so Q grows
// from the first step exactly when Δt > c/ω². The other integrators leave their bounds through
// an eigenvalue crossing −1 or the unit circle, which runs away within tens of steps.
#pragma once

#include <functional>
#include <memory>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// Speed, in multiples of the kick's largest speed, at which a trial counts as a runaway, and the
// displacement (a fraction of the shortest rest length) whose speed caps it.
inline constexpr double kRunaway = 1e4;
inline constexpr double kLinearReach = 0.1;

struct ProbeOptions {
    double trialTime = 0.5;   // simulated time of one trial [s] ...
    long minSteps = 200;      // ... but at least this many steps
    long maxSteps = 20000;    // ... and at most this many
    double tolerance = 0.02;  // bisection ends when unstable/stable ≤ 1 + tolerance
    double cap = 1.0;         // largest Δt tried [s]: a method stable there is "stable to the cap"
    double floor = 1e-12;     // smallest Δt tried [s]: unstable there is "unstable everywhere"
    double kick = 1e-6;       // stiff-mode displacement amplitude / the shortest rest length
    int powerIterations = 200;  // for the kick's shape (stiffestMode)
};

enum class ProbeStatus { Bounded, StableToCap, UnstableEverywhere };
const char* probeStatusName(ProbeStatus s);  // "bounded", "stable_to_cap", "unstable_everywhere"

struct ProbeResult {
    ProbeStatus status = ProbeStatus::Bounded;
    double stableDt = 0;    // the largest Δt found stable [s] (0: none)
    double unstableDt = 0;  // the smallest Δt found unstable above it [s] (0: none)
    int trials = 0;
    long steps = 0;  // summed over the trials
};

// Builds a solver for a scene (a backend's factory); the probe keeps it for all its trials and
// changes only Δt (Solver::setParameters) and the state (Solver::write).
using SolverMaker = std::function<std::unique_ptr<Solver>(const Scene&)>;

// The scene the trials run: gravity 0, no wind, no colliders, `method`.
Scene linearisedAboutRest(const Scene& scene, Method method);

// Bisects for the largest stable Δt of `method`, starting from `startDt` (a prediction; a
// non-finite or non-positive one starts at the cap) and doubling or halving to bracket it.
ProbeResult probeStableDt(const Scene& scene, Method method, double startDt,
                          const SolverMaker& make, const ProbeOptions& options);

}  // namespace cloth
