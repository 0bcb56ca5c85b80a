#include "app/reports.h"

#include <cstdio>

#include "model/stability.h"

namespace cloth::app {

void reportUnstable(const Scene& scene, const Solver& solver, const StepResult& r,
                    const std::string& consequence) {
    std::fprintf(stderr, "clothsim: %s: %s\n", scene.source.c_str(),
                 describeInstability(scene, r).c_str());
    std::fprintf(stderr, "clothsim: %s [%s]; %s\n", instabilityAdvice(scene, r).text.c_str(),
                 solver.name().c_str(), consequence.c_str());
}

void reportSolveMisses(const Scene& scene, const Solver& solver) {
    const SolveStats& s = solver.solveStats();
    const long capped = s.misses - s.breakdowns;
    if (capped > 0)
        std::fprintf(stderr,
                     "clothsim: %s: warning: %ld of %ld implicit solves stopped at "
                     "integrator.max_iterations = %d before |r| <= %g |b| (first miss at step %ld, "
                     "worst relative residual %.3g); raise integrator.max_iterations or lower dt\n",
                     scene.source.c_str(), capped, s.solves, scene.integrator.maxIterations,
                     scene.integrator.tolerance, s.firstMissStep, s.worstResidual);
    if (s.breakdowns > 0)
        std::fprintf(stderr,
                     "clothsim: %s: warning: %ld of %ld implicit solves broke down before "
                     "|r| <= %g |b| (first at step %ld): p·A p was not positive or a sum was not "
                     "finite, so the preconditioner's output or the state was not finite; those "
                     "steps went on with the last iterate. [%s] Try %s\n",
                     scene.source.c_str(), s.breakdowns, s.solves, scene.integrator.tolerance,
                     s.firstBreakdownStep, solver.name().c_str(),
                     breakdownRemedy(scene, solver).c_str());
}

void noteUnusedSettings(const Scene& scene) {
    for (const std::string& line : unusedIntegratorSettings(scene.integrator))
        std::fprintf(stderr, "clothsim: %s: note: %s\n", scene.source.c_str(), line.c_str());
}

void warnUnstableDt(const Scene& scene) {
    if (const auto warning = dtWarning(scene))
        std::fprintf(stderr, "clothsim: %s: warning: %s\n", scene.source.c_str(), warning->c_str());
}

}  // namespace cloth::app
