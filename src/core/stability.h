// Predicted stability limits (DESIGN.md §2; derivation in docs/physics.md).
#pragma once

#include <string>

#include "core/scene.h"

namespace cloth {

struct StabilityBound {
    double lambdaMax = 0;          // Gershgorin bound on the stiffness matrix's eigenvalues [N/m]
    double explicitEulerDt = 0;    // largest stable Δt of the seed's explicit Euler [s] (0: none)
    double symplecticEulerDt = 0;  // same for symplectic Euler, for comparison [s]
};

// λ_max ≤ max over free vertices of Σ_springs K + Σ_springs to free neighbours K (Gershgorin
// on the free degrees of freedom: a spring to a pinned vertex adds only its diagonal K).
// Explicit Euler: Δt < μ/λ_max and μΔt/m < 2. Symplectic Euler: (λ/m)Δt² + 2(μ/m)Δt < 4.
StabilityBound estimateStability(const Scene& scene);

// The bound for the scene's own integrator.
double stableDt(const Scene& scene);

// One line a user can act on: a Δt inside the bound, or the damping that makes the Δt stable.
std::string stabilityAdvice(const Scene& scene);

}  // namespace cloth
