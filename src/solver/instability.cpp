#include "solver/instability.h"

#include <algorithm>
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

namespace {

// vbdHoldingSweepsPerSecond's factor: iterations / Δt came to about 11 N (10 sweeps, N = 64 …
// 384) or 10 N (20 sweeps with chebyshev_rho = 0.9) where the sheets held; 13 N is what the
// largest that held (384² at 1/480 s) took.
constexpr double kVbdSweepsPerSecondPerVertex = 13;
// With 4 or more translation levels: 10 sweeps at 1/60 s (600 a second) held every landing tried
// up to 192² and tore one at 208² (docs/integrators.md "The translation's levels"): 3 N. Fewer
// levels tore at 192²: the rule without them.
constexpr double kVbdLevelsSweepsPerSecondPerVertex = 3;
constexpr int kVbdRuleLevels = 4;

double vbdHoldingFactor(const Scene& scene) {
    return scene.integrator.translationLevels >= kVbdRuleLevels ? kVbdLevelsSweepsPerSecondPerVertex
                                                                : kVbdSweepsPerSecondPerVertex;
}

// What to do about a cloth too soft for its load: its material's membrane or its springs.
std::string stiffenOrRaise(const Scene& scene) {
    return std::string("stiffen it (") +
           (scene.material ? "material.stretch, material.shear" : "springs.*") +
           ") or raise max_strain";
}

// The other cause of a strain past max_strain, for the large-step methods' advice.
std::string tooSoft(const Scene& scene) {
    return "a cloth that stretches this far at rest is too soft for its load: " +
           stiffenOrRaise(scene);
}

InstabilityAdvice vbdStrainAdvice(const Scene& scene) {
    const Grid g = scene.grid();
    const int n = std::max(g.nu, g.nv);
    const IntegratorSpec& in = scene.integrator;
    const double rate = vbdSweepsPerSecond(scene), needed = vbdHoldingSweepsPerSecond(scene);
    const double dt = in.iterations / needed;
    // The translation's step carries the sheet's weight to its pins and contacts at once; after
    // Chebyshev's extrapolation more than one a step tears the drape sooner (docs/integrators.md).
    const std::string translation =
        in.translationSweeps < in.iterations && in.chebyshevRho == 0
            ? ", or set integrator.translation_sweeps = " + std::to_string(in.iterations) +
                  " (the translation's step after every sweep, docs/integrators.md)"
            : "";
    // The translation's levels carry a landing's tension across the sheet within the step: the
    // sweeps a second the rule asks for no longer grow with N (docs/integrators.md).
    const std::string levels =
        in.translationLevels == 0
            ? ", or set integrator.translation_levels = 4 (the translation's step on blocks of "
              "the sheet before the sweeps: with it 10 sweeps at 1/60 s hold a dropped sheet of "
              "192 vertices a side, docs/integrators.md)"
            : "";
    // One pass of the levels before the first sweep holds a landing on its blocks' edges; a
    // second between the sweeps holds it wherever the sheet meets the collider (docs/stability.md
    // "vbd"), better than Chebyshev's ρ = 0.95 for the same cost.
    const std::string passes =
        in.translationLevels >= kVbdRuleLevels && in.translationLevelPasses < 2
            ? ", or set integrator.translation_level_passes = 2 (a second pass of the "
              "translation's levels between the sweeps: with it 10 sweeps held the dropped cotton "
              "sheet of 256 vertices a side wherever the sphere lay under it, docs/stability.md)"
            : "";
    char buf[1600];
    if (dt < in.dt) {
        std::snprintf(buf, sizeof buf,
                      "vbd's %d sweeps a step did not carry the tension across the sheet: it ran "
                      "%.0f sweeps a simulated second (iterations / dt), and dropped sheets of %d "
                      "vertices a side held with %.0f x %d = %.0f (docs/performance.md); lower "
                      "integrator.dt to %.2g s or raise integrator.iterations (with "
                      "integrator.chebyshev_rho = 0.9)%s%s%s; %s",
                      in.iterations, rate, n, vbdHoldingFactor(scene), n, needed, dt,
                      levels.c_str(), passes.c_str(), translation.c_str(), tooSoft(scene).c_str());
        return {buf, dt};
    }
    std::snprintf(buf, sizeof buf,
                  "vbd's %d sweeps a step did not carry the tension across the sheet, although "
                  "%.0f sweeps a simulated second for %d vertices a side held a dropped cotton "
                  "sheet (docs/performance.md): a stiffer or more loaded cloth needs more; raise "
                  "integrator.iterations or lower integrator.dt%s%s%s; %s",
                  in.iterations, rate, n, levels.c_str(), passes.c_str(), translation.c_str(),
                  tooSoft(scene).c_str());
    return {buf, std::nullopt};
}

InstabilityAdvice implicitStrainAdvice(const Scene& scene) {
    const IntegratorSpec& in = scene.integrator;
    char buf[800];
    if (!(in.maxStepStrain > 0)) {
        std::snprintf(buf, sizeof buf,
                      "implicit_euler linearises the springs once a step, and a fast rotation "
                      "(%s) stretches them: set integrator.max_step_strain = 0.1 to take such "
                      "steps again in halves (docs/integrators.md) or lower integrator.dt; %s",
                      scene.colliders.empty() ? "a swing as far as this dt lets the cloth fall"
                                              : "a landing on a collider",
                      tooSoft(scene).c_str());
        return {buf, std::nullopt};
    }
    std::snprintf(buf, sizeof buf,
                  "implicit_euler's steps stretched the springs although those that strained "
                  "more than integrator.max_step_strain = %g were taken again in halves (down "
                  "to dt/16): lower integrator.dt to %.2g s; %s",
                  in.maxStepStrain, in.dt / 2, tooSoft(scene).c_str());
    return {buf, in.dt / 2};
}

}  // namespace

double vbdHoldingSweepsPerSecond(const Scene& scene) {
    const Grid g = scene.grid();
    return vbdHoldingFactor(scene) * std::max(g.nu, g.nv);
}

double vbdSweepsPerSecond(const Scene& scene) {
    return scene.integrator.iterations / scene.integrator.dt;
}

std::string breakdownRemedy(const Scene& scene, const Solver& solver) {
    std::string remedy = scene.integrator.preconditioner == Preconditioner::Jacobi
                             ? "a smaller integrator.dt or softer springs"
                             : "integrator.preconditioner = \"jacobi\"";
    const bool onGpu = solver.name().find("gpu") != std::string::npos;
    return onGpu ? remedy + " or --backend cpu" : remedy;
}

InstabilityAdvice instabilityAdvice(const Scene& scene, const StepResult& r) {
    if (r.reason.rfind("self-collision", 0) == 0)  // (model/self_contact.h selfCollapseReason)
        return {
            "no step of a cloth kept self_collision.thickness apart leads there: start from a "
            "state whose elements that share no vertex are at least that far apart (a "
            "written or dragged state, or a scene whose sheet starts folded onto itself)",
            std::nullopt};
    const bool strain = r.reason.rfind("strain", 0) == 0;
    if (strain && scene.integrator.method == Method::Vbd) return vbdStrainAdvice(scene);
    if (strain && scene.integrator.method == Method::ImplicitEuler)
        return implicitStrainAdvice(scene);
    if (strain && !dtWarning(scene))
        return {"dt is inside the predicted stability bound: the cloth is too soft for the load; " +
                    stiffenOrRaise(scene),
                std::nullopt};
    // Half the bound at or above the step that failed: a smaller step is not the cure (a wind of
    // 1e300, a max_speed of 5e-324), and the advice must not offer a larger one.
    const std::optional<double> dt = suggestedDt(scene);
    if (dt && *dt >= scene.integrator.dt) {
        char buf[300];
        std::snprintf(buf, sizeof buf,
                      "dt = %.3g s is already within half the predicted stability bound (%.3g s): "
                      "a smaller step is not the cure; look for a force or size far outside a "
                      "cloth's (wind.strength, max_speed, cloth.size, the springs)",
                      scene.integrator.dt, 2 * *dt);
        return {buf, std::nullopt};
    }
    return {stabilityAdvice(scene), dt};
}

}  // namespace cloth
