// What the app says on stderr about a run's physics: instability (exit 3) and implicit solves
// that stopped at their iteration cap.
#pragma once

#include <optional>
#include <string>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth::app {

// Says on stderr that the run became unstable (DESIGN.md §5, exit 3): the step or step range,
// the simulated time, what went wrong, a stable Δt or damping, and `consequence`.
void reportUnstable(const Scene& scene, const Solver& solver, const StepResult& r,
                    const std::string& consequence);

// Steps between the strain checks of `run` and `render`: a read of the state every 1000 steps
// costs well under 1% of them (docs/performance.md), and a run that left physics stops soon after.
inline constexpr long kStrainCheckSteps = 1000;

// Whether a run at step `done` of `total`, last checked at step `checked`, checks its strain now:
// every kStrainCheckSteps steps and at the end.
inline bool strainCheckDue(long checked, long done, long total) {
    return done - checked >= kStrainCheckSteps || done == total;
}

// DESIGN.md §2's strain check on the solver's state (solver/diagnostics.h strainBreach), last
// checked at step `before`: the unstable StepResult, with the steps since as the range the first
// bad step lies in, or nothing.
std::optional<StepResult> strainInstability(const Scene& scene, const Solver& solver, long before);

// A warning on stderr, before any step, when the scene's Δt is beyond its integrator's predicted
// stability bound (model/stability.h dtWarning).
void warnUnstableDt(const Scene& scene);

// A warning on stderr when implicit Euler's CG stopped at its cap in any step (never silent).
void reportSolveMisses(const Scene& scene, const Solver& solver);

}  // namespace cloth::app
