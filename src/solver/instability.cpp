#include "solver/instability.h"

#include <cstdio>

#include "model/stability.h"
#include "solver/diagnostics.h"

namespace cloth {

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

std::string describeInstability(const Scene& scene, const StepResult& r) {
    const double dt = scene.integrator.dt;
    char where[200];
    if (r.firstBadStep == r.lastBadStep)
        std::snprintf(where, sizeof where, "unstable at step %ld (t = %.6g s): ", r.firstBadStep,
                      double(r.firstBadStep) * dt);
    else
        std::snprintf(where, sizeof where,
                      "unstable between steps %ld and %ld (t = %.6g..%.6g s): ", r.firstBadStep,
                      r.lastBadStep, double(r.firstBadStep) * dt, double(r.lastBadStep) * dt);
    return where + r.reason;
}

InstabilityAdvice instabilityAdvice(const Scene& scene, const StepResult& r) {
    const bool softSprings = r.reason.rfind("strain", 0) == 0 && !dtWarning(scene);
    if (softSprings)
        return {
            "dt is inside the predicted stability bound: the springs are too soft for the "
            "load; stiffen them (springs.*) or raise max_strain",
            std::nullopt};
    return {stabilityAdvice(scene), suggestedDt(scene)};
}

}  // namespace cloth
