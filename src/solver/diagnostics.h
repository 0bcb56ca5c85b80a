// Quantities measured on a state: energy (DESIGN.md §6 invariants), strain, extent.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

struct Energy {
    // m_k and K of each slot as the solvers model them (Scene::vertexMass, slotStiffness).
    double kinetic = 0;  // Σ ½ m_k |v_k|²  [J]
    double spring = 0;   // Σ over springs (each once) ½ K (|d| − L)²  [J]
    double gravity = 0;  // −Σ m_k ⟨g, p_k⟩  [J]
    double bending = 0;  // a material's bending energy (model/bending.h) [J]
    double total() const { return kinetic + spring + gravity + bending; }
};

Energy energy(const Scene& scene, const SimState& state);

// Largest relative stretch (|d| − L)/L over the structural springs (0 if there are none).
double maxStrain(const Scene& scene, const SimState& state);

// The modelled spring of largest |strain| = ||d| − L|/L over every family the scene declares, with
// its two ends (k = j·nu + i); strain 0 when the scene models no springs.
struct SpringStrain {
    double strain = 0;
    std::int64_t a = 0, b = 0;
};
SpringStrain largestStrain(const Scene& scene, const SimState& state);

// The structural spring whose stretch max(0, (|d| − L)/L) grew most from `before` to `after` (two
// states of the same grid), by how much: the step control's measure of a step
// (solver/step_control.h). A membrane torn by a step stretches; one that folds or shears
// shortens its bend and shear springs, and buckling compresses, as the cloth may. +inf where a
// length is not finite, before or after.
SpringStrain largestStretchGrowth(const Scene& scene, const SimState& before,
                                  const SimState& after);

// DESIGN.md §2's instability by strain: why the state has a spring beyond the scene's max_strain
// ("strain 1.8 > max_strain 1 on the spring (3, 4)-(4, 4)"), or nothing.
std::optional<std::string> strainBreach(const Scene& scene, const SimState& state);

// True when every position and velocity is finite.
bool allFinite(const SimState& state);

}  // namespace cloth
