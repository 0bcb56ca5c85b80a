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

}  // namespace cloth::app
