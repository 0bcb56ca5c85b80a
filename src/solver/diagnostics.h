// Quantities measured on a state: energy (DESIGN.md §6 invariants), strain, extent.
#pragma once

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

struct Energy {
    double kinetic = 0;  // Σ ½ m |v|²  [J]
    double spring = 0;   // Σ over springs (each once) ½ K (|d| − L)²  [J]
    double gravity = 0;  // −Σ m ⟨g, p⟩  [J]
    double total() const { return kinetic + spring + gravity; }
};

Energy energy(const Scene& scene, const SimState& state);

// Largest relative stretch (|d| − L)/L over the structural springs (0 if there are none).
double maxStrain(const Scene& scene, const SimState& state);

// True when every position and velocity is finite.
bool allFinite(const SimState& state);

}  // namespace cloth
