// What the app says on stderr about a run's physics: instability (exit 3) and implicit solves
// that stopped at their iteration cap.
#pragma once

#include <string>

#include "model/scene.h"
#include "solver/instability.h"
#include "solver/solver.h"

namespace cloth::app {

// Says on stderr that the run became unstable (DESIGN.md §5, exit 3): the step or step range,
// the simulated time, what went wrong, what to change (solver/instability.h), and `consequence`.
void reportUnstable(const Scene& scene, const Solver& solver, const StepResult& r,
                    const std::string& consequence);

// A warning on stderr, before any step, when the scene's Δt is beyond its integrator's predicted
// stability bound (model/stability.h dtWarning).
void warnUnstableDt(const Scene& scene);
// One note a line on stderr for each integrator key the scene sets that its method does not use
// (model/scene.h unusedIntegratorSettings): run, render, view and validate.
void noteUnusedSettings(const Scene& scene);

// A warning on stderr when implicit Euler's CG stopped at its cap in any step, and another when
// it broke down (never silent).
void reportSolveMisses(const Scene& scene, const Solver& solver);

}  // namespace cloth::app
