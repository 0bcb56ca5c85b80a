// What a run does about instability beyond the solvers' own checks (DESIGN.md §2): the strain
// check on the state every so many steps, and the advice that goes with an unstable step. The
// command line and the Python module both step by these rules.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// Steps between the strain checks of a run: a read of the state every 1000 steps costs well under
// 1% of them (docs/performance.md), and a run that left physics stops soon after. A large step
// is checked at least every kStrainCheckInterval of simulated time: vbd at 1/60 s can stretch a
// sheet to 5× and let it contract again within 40 steps (docs/stability.md "vbd").
inline constexpr long kStrainCheckSteps = 1000;
inline constexpr double kStrainCheckInterval = 0.1;  // [s]

// The steps between checks at Δt = dt: 1000, or fewer where they span more than 0.1 s.
inline long strainCheckSteps(double dt) {
    if (!(dt > 0)) return kStrainCheckSteps;
    const double steps = std::floor(kStrainCheckInterval / dt * (1 + 1e-9));
    return steps < 1 ? 1 : steps < double(kStrainCheckSteps) ? long(steps) : kStrainCheckSteps;
}

// Whether a run at step `done` of `total`, last checked at step `checked`, checks its strain now:
// every `every` steps (strainCheckSteps) and at the end.
inline bool strainCheckDue(long checked, long done, long total, long every) {
    return done - checked >= every || done == total;
}

// DESIGN.md §2's strain check on the solver's state (solver/diagnostics.h strainBreach), last
// checked at step `before`: the unstable StepResult, with the steps since as the range the first
// bad step lies in, or nothing.
std::optional<StepResult> strainInstability(const Scene& scene, const Solver& solver, long before);

// Where `r` went unstable: "unstable at step 12 (t = 0.012 s): <reason>", or "unstable between
// steps 65 and 128 (t = 0.065..0.128 s): <reason>" where a backend checks every few steps.
std::string describeInstability(const Scene& scene, const StepResult& r);

// vbd's measured rule (docs/performance.md "vbd: the step that holds the sheet at each N"): the
// sweeps a simulated second, iterations / Δt, at which a sheet of the scene's N vertices a side
// dropped onto a collider held, 13 N; 3 N with 4 or more translation levels.
double vbdHoldingSweepsPerSecond(const Scene& scene);
// The sweeps a simulated second the scene's vbd runs: iterations / Δt.
double vbdSweepsPerSecond(const Scene& scene);

// What to change after the unstable step `r`: one line a user can act on, and the Δt it
// suggests, if a smaller step is the cure (model/stability.h suggestedDt). A spring past
// max_strain has a cause per method: after an explicit method inside its bound the cloth is too
// soft for its load (no Δt suggested); after vbd its sweeps did not carry the tension across the
// sheet, and the Δt is the one at which sweeps as many a second held a dropped sheet of that size
// (docs/performance.md); after implicit Euler the step control is named first, then half the step.
struct InstabilityAdvice {
    std::string text;
    std::optional<double> dt;  // [s]
};
InstabilityAdvice instabilityAdvice(const Scene& scene, const StepResult& r);

// What to try where implicit solves broke down (SolveStats::breakdowns: a state or preconditioner
// output not finite): the block-Jacobi preconditioner, or with it a smaller step or softer
// springs (a 3×3 block of stiffness 1e20 N/m inverts to inf in float); the CPU where `solver`
// is the GPU's. `integrator.preconditioner = "jacobi" or --backend cpu`.
std::string breakdownRemedy(const Scene& scene, const Solver& solver);

}  // namespace cloth
