#include "solver/step_control.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace cloth {
namespace {

StepCheck& checkOf(Solver& backend) {
    StepCheck* check = backend.stepCheck();
    if (!check)
        throw std::logic_error(backend.name() + " keeps no step start: made without step control");
    return *check;
}

}  // namespace

StepControl::StepControl(std::unique_ptr<Solver> backend, const Scene& scene)
    : backend_(std::move(backend)),
      check_(checkOf(*backend_)),
      scene_(scene),
      backendDt_(scene.integrator.dt) {
    setStepDt(scene.integrator.dt);
    setTime(backend_->time());
    steps_ = backend_->stepsDone();
}

StepResult StepControl::step(long n) {
    StepResult result;
    for (long s = 0; s < n; ++s) {
        // A step starts at the pieces the last one ended with where one of those failed the
        // check, else at pieces twice as long: the step grows back by halves, a step at a time.
        const int start = startDepth_;
        deepest_ = start;
        failed_ = false;
        const long rejectedBefore = stats_.rejected;
        const SolveStats solvesBefore = backend_->solveStats();
        StepResult r;
        for (long piece = 0; piece < (1L << start) && !r.unstable; ++piece)
            r = advance(scene_.integrator.dt / double(1L << start), start);
        if (start > 0 || stats_.rejected > rejectedBefore) ++stats_.split;
        startDepth_ = failed_ ? deepest_ : std::max(0, start - 1);
        recordSolves(solvesBefore);
        if (r.unstable) {
            r.stepsTaken = s;
            r.firstBadStep = r.lastBadStep = steps_ + 1;
            return r;
        }
        ++steps_;
        ++result.stepsTaken;
    }
    return result;
}

// The backend counts its own steps, every piece and try among them: the first miss and breakdown
// are renumbered to the scene's step they fell in.
void StepControl::recordSolves(const SolveStats& before) {
    const long firstMiss = solveStats_.firstMissStep,
               firstBreakdown = solveStats_.firstBreakdownStep;
    solveStats_ = backend_->solveStats();
    solveStats_.firstMissStep =
        before.misses == 0 && solveStats_.misses > 0 ? steps_ + 1 : firstMiss;
    solveStats_.firstBreakdownStep =
        before.breakdowns == 0 && solveStats_.breakdowns > 0 ? steps_ + 1 : firstBreakdown;
}

StepResult StepControl::advance(double dt, int depth) {
    check_.keep();
    setBackendDt(dt);
    const StepResult tried = backend_->step(1);
    const bool failed =
        tried.unstable || !(check_.stretchGrowth() <= scene_.integrator.maxStepStrain);
    failed_ = failed_ || failed;
    if (!failed || depth == kMaxHalvings) {
        ++stats_.substeps;
        stats_.deepest = std::max(stats_.deepest, depth);
        deepest_ = std::max(deepest_, depth);
        return tried;
    }
    ++stats_.rejected;
    check_.restore();  // the step's start, its time included
    for (int half = 0; half < 2; ++half) {
        const StepResult r = advance(dt / 2, depth + 1);
        if (r.unstable) return r;
    }
    return {};
}

void StepControl::setBackendDt(double dt) {
    if (dt == backendDt_) return;
    Scene scene = scene_;
    scene.integrator.dt = dt;
    backend_->setParameters(scene);
    backendDt_ = dt;
}

void StepControl::write(const SimState& state) {
    backend_->write(state);
    setTime(state.time);
}

void StepControl::setParameters(const Scene& scene) {
    backend_->setParameters(scene);  // throws where the backend needs rebuilding
    scene_ = scene;
    backendDt_ = scene.integrator.dt;
    setStepDt(scene.integrator.dt);
}

}  // namespace cloth
