#include "app/reports.h"

#include <cstdio>

#include "model/stability.h"
#include "solver/diagnostics.h"

namespace cloth::app {

void reportUnstable(const Scene& scene, const Solver& solver, const StepResult& r,
                    const std::string& consequence) {
    const double dt = scene.integrator.dt;
    if (r.firstBadStep == r.lastBadStep)
        std::fprintf(stderr, "clothsim: %s: unstable at step %ld (t = %.6g s): %s\n",
                     scene.source.c_str(), r.firstBadStep, r.firstBadStep * dt, r.reason.c_str());
    else
        std::fprintf(stderr,
                     "clothsim: %s: unstable between steps %ld and %ld (t = %.6g..%.6g s): %s\n",
                     scene.source.c_str(), r.firstBadStep, r.lastBadStep, r.firstBadStep * dt,
                     r.lastBadStep * dt, r.reason.c_str());
    // A spring past max_strain at a Δt inside the bound is a cloth too soft for its load, not a
    // step too long.
    const bool softSprings = r.reason.rfind("strain", 0) == 0 && !dtWarning(scene);
    const std::string advice =
        softSprings ? "dt is inside the predicted stability bound: the springs are too soft for "
                      "the load; stiffen them (springs.*) or raise max_strain"
                    : stabilityAdvice(scene);
    std::fprintf(stderr, "clothsim: %s [%s]; %s\n", advice.c_str(), solver.name().c_str(),
                 consequence.c_str());
}

void reportSolveMisses(const Scene& scene, const Solver& solver) {
    const SolveStats& s = solver.solveStats();
    if (s.misses == 0) return;
    std::fprintf(stderr,
                 "clothsim: %s: warning: %ld of %ld implicit solves stopped at "
                 "integrator.max_iterations = %d before |r| <= %g |b| (first at step %ld, worst "
                 "relative residual %.3g); raise integrator.max_iterations or lower dt\n",
                 scene.source.c_str(), s.misses, s.solves, scene.integrator.maxIterations,
                 scene.integrator.tolerance, s.firstMissStep, s.worstResidual);
}

void warnUnstableDt(const Scene& scene) {
    if (const auto warning = dtWarning(scene))
        std::fprintf(stderr, "clothsim: %s: warning: %s\n", scene.source.c_str(), warning->c_str());
}

std::optional<StepResult> strainInstability(const Scene& scene, const Solver& solver, long before) {
    const auto why = strainBreach(scene, solver.read());
    if (!why) return std::nullopt;
    StepResult r;
    r.unstable = true;
    r.firstBadStep = before + 1;
    r.lastBadStep = solver.stepsDone();
    r.reason = *why;
    return r;
}

}  // namespace cloth::app
