// Predicted stability limits of each integrator (DESIGN.md §2; derivations in docs/physics.md
// and docs/stability.md).
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.h"

namespace cloth {

// Largest stable Δt of `method` for one mode x'' = −ω² x − c x' of the linearised cloth: ω² the
// mode's eigenvalue of M⁻¹H [1/s²] (H = −∂F/∂x, M the vertex masses), c the damping rate [1/s]
// (the drag −c·m_k·v_k is proportional to the mass, so every mode of M⁻¹H keeps its own c),
// including the rigid (ω = 0) drag mode. +infinity: stable at every Δt (implicit Euler; Verlet or
// RK4 with no spring); 0: no stable Δt (explicit Euler without damping).
//   explicit_euler    Δt < c/ω² (= μ/λ) and cΔt < 2
//   symplectic_euler  ω²Δt² + 2cΔt < 4
//   verlet            Δt < 2/ω (independent of c with the trapezoidal damping)
//   rk4               |1 + z + z²/2 + z³/6 + z⁴/24| ≤ 1 for z = Δt·(eigenvalues of the mode)
//   implicit_euler    unconditional (linearised)
//   vbd               unconditional: each local step lowers backward Euler's potential
double methodDt(Method method, double omega2, double c);
// The same with spring damping β [s] (docs/stability.md "Spring damping"): at rest its damping
// matrix is β times the springs' H, so the mode of ω² is damped at c + βω² (taken at ω² = the
// bound's, the stiffest mode, where every condition binds); verlet, whose forces take the spring
// damping at the half-step velocity (docs/integrators.md), needs ω²Δt² + 2βω²Δt < 4. β = 0 gives
// methodDt's bits.
double dampedMethodDt(Method method, double omega2, double c, double beta);
// The same for the per-vertex form's mode of stiffness eigenvalue λ [N/m] on masses m [kg] with
// damping μ [N·s/m]: ω² = λ/m, c = μ/m.
double methodDt(Method method, double lambda, double mass, double damping);

struct StabilityBound {
    double lambdaMax = 0;    // Gershgorin bound on the eigenvalues of H [N/m] (the springs alone)
    double lambdaPower = 0;  // the Rayleigh quotient of H on the power iteration's mode [N/m]
                             // (≤ the true λ_max); 0 when not computed
    // Gershgorin bound on the eigenvalues ω² of M⁻¹H [1/s²]: what the step's stability depends
    // on. λ_max/m in the per-vertex form; with a material, the worst row of H over the vertex's
    // own mass, where masses differ from vertex to vertex.
    double omega2Max = 0;
    double omega2Power = 0;      // power-iteration estimate of ω²_max (≤ the true one); 0: none
    double dampingRate = 0;      // c [1/s] (Scene::dampingRate)
    double springDamping = 0;    // β [s] (Scene::springDamping): adds βω² to a mode's rate
    double explicitEulerDt = 0;  // methodDt(explicit_euler, omega2Max, c) [s] (0: none)
    double symplecticEulerDt = 0;  // methodDt(symplectic_euler, omega2Max, c) [s]

    // The bound of `method` from Gershgorin's ω² (safe: ω²_max ≤ it) or from the power estimate
    // (tight: the step at which the stiffest mode actually turns unstable).
    double safeDt(Method method) const;
    double tightDt(Method method) const;  // = safeDt when the power estimate was not computed
};

// λ_max ≤ max over free vertices of Σ_springs K + Σ_springs to free neighbours K (Gershgorin
// on the free degrees of freedom: a spring to a pinned vertex adds only its diagonal K), and
// ω²_max ≤ the largest such row sum divided by its vertex's mass m_k (Gershgorin on M⁻¹H, whose
// row k is H's over m_k). powerIterations > 0 also estimates ω²_max of M⁻¹H at the initial
// (rest) state by that many power iterations (a Rayleigh quotient; one stencil pass each).
StabilityBound estimateStability(const Scene& scene, int powerIterations = 0);

// The stiffest mode of M⁻¹H at the rest state by `iterations` power iterations: its
// Rayleigh-quotient estimate ω² = pᵀHp/pᵀMp [1/s²] (≤ the true ω²_max), pᵀHp/pᵀp [N/m], and the
// unit-norm shape the iteration ended on (zero on pinned vertices), k = j·nu + i. What
// estimateStability's omega2Power and lambdaPower use.
struct StiffMode {
    double omega2 = 0;
    double lambda = 0;
    std::vector<glm::dvec3> shape;
};
StiffMode stiffestMode(const Scene& scene, int iterations);

// The safe bound for the scene's own integrator.
double stableDt(const Scene& scene);

// One line a user can act on: a Δt inside the bound, or the damping that makes the Δt stable.
std::string stabilityAdvice(const Scene& scene);

// The Δt that advice suggests [s]: half the safe bound, a margin for the nonlinear terms the
// bound leaves out. Nothing where every Δt is predicted stable (the instability is not the
// step's) or none is (explicit Euler without damping: the damping must change).
std::optional<double> suggestedDt(const Scene& scene);

// When the scene's Δt is beyond its integrator's predicted (safe) bound, or explicit Euler has no
// stable Δt at its damping: one line naming Δt, the bound and the key to change, which `run`,
// `render` and the viewer show before stepping. Nothing inside the bound.
std::optional<std::string> dtWarning(const Scene& scene);

}  // namespace cloth
