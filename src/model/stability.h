// Predicted stability limits of each integrator (DESIGN.md §2; derivations in docs/physics.md
// and docs/stability.md).
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.h"

namespace cloth {

// Largest stable Δt of `method` for one spring mode of stiffness eigenvalue λ [N/m] with mass m
// and damping μ, including the rigid (λ = 0) drag mode. +infinity: stable at every Δt (implicit
// Euler; Verlet or RK4 with no spring); 0: no stable Δt (explicit Euler without damping).
//   explicit_euler    Δt < μ/λ and μΔt/m < 2
//   symplectic_euler  (λ/m)Δt² + 2(μ/m)Δt < 4
//   verlet            Δt < 2/ω, ω² = λ/m (independent of μ with the trapezoidal damping)
//   rk4               |1 + z + z²/2 + z³/6 + z⁴/24| ≤ 1 for z = Δt·(eigenvalues of the mode)
//   implicit_euler    unconditional (linearised)
double methodDt(Method method, double lambda, double mass, double damping);

struct StabilityBound {
    double lambdaMax = 0;    // Gershgorin bound on the stiffness matrix's eigenvalues [N/m]
    double lambdaPower = 0;  // power-iteration estimate at the initial state (≤ the true λ_max);
                             // 0 when not computed
    double explicitEulerDt = 0;    // methodDt(explicit_euler, lambdaMax, ...) [s] (0: none)
    double symplecticEulerDt = 0;  // methodDt(symplectic_euler, lambdaMax, ...) [s]

    // The bound of `method` from Gershgorin's λ (safe: λ_max ≤ it) or from the power estimate
    // (tight: the step at which the stiffest mode actually turns unstable).
    double safeDt(Method method) const;
    double tightDt(Method method) const;  // = safeDt when lambdaPower was not computed

    double mass = 1, damping = 0;
};

// λ_max ≤ max over free vertices of Σ_springs K + Σ_springs to free neighbours K (Gershgorin
// on the free degrees of freedom: a spring to a pinned vertex adds only its diagonal K).
// powerIterations > 0 also estimates λ_max of H = −∂F/∂x at the initial (rest) state by that
// many power iterations (a Rayleigh quotient; the cost is one stencil pass each).
StabilityBound estimateStability(const Scene& scene, int powerIterations = 0);

// The stiffest mode of H = −∂F/∂x at the rest state by `iterations` power iterations: its
// Rayleigh-quotient estimate λ [N/m] (≤ the true λ_max) and the unit-norm shape the iteration
// ended on (zero on pinned vertices), k = j·nu + i. What estimateStability's lambdaPower uses.
struct StiffMode {
    double lambda = 0;
    std::vector<glm::dvec3> shape;
};
StiffMode stiffestMode(const Scene& scene, int iterations);

// The safe bound for the scene's own integrator.
double stableDt(const Scene& scene);

// One line a user can act on: a Δt inside the bound, or the damping that makes the Δt stable.
std::string stabilityAdvice(const Scene& scene);

// When the scene's Δt is beyond its integrator's predicted (safe) bound, or explicit Euler has no
// stable Δt at its damping: one line naming Δt, the bound and the key to change, which `run`,
// `render` and the viewer show before stepping. Nothing inside the bound.
std::optional<std::string> dtWarning(const Scene& scene);

}  // namespace cloth
