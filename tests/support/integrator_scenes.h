// Scenes and helpers the integrator tests share: the seed's damped spring as a cloth::Scene, a
// small cloth with every feature of DESIGN.md §2, and a few state checks.
#pragma once

#include <string>

#include "model/scene.h"
#include "solver/solver.h"
#include "support/damped_spring.h"

namespace cloth {

// The 1×2 spring along −y, top vertex pinned, gravity s.g along −y; tolerance for implicit Euler.
Scene springScene(const DampedSpring& s, Method method, double dt, double tolerance = 1e-14);

// The state of that spring at stretch x and stretch rate xDot.
SimState springState(double x, double xDot);

// A 9×13 cloth with every feature of §2: three spring families, wind, a floor and a sphere it
// falls onto, pins with negative indices, mass ≠ 1, damping, axes neither unit nor orthogonal.
// λ_max ≤ 2·4·(200 + 80 + 20) = 2400 N/m: Δt = 1e-3 is inside every method's bound.
Scene everythingScene(Method method, double dt = 1e-3);

// The first step (1-based) after which some vertex of the reference run of `scene` lies on one
// of its colliders; 0 when none is touched within `steps`.
long firstContactStep(const Scene& scene, long steps);

}  // namespace cloth
