// Step control (docs/integrators.md "Step control"), for every integrator on both backends: a
// step of the scene's Δt is taken whole first; where it stretches some structural spring by more
// than integrator.max_step_strain of its rest length (solver/diagnostics.h
// largestStretchGrowth), or leaves the state unstable, the backend is put back to the
// step's start and the step is taken as two of Δt/2, each checked the same way, down to
// Δt/2^kMaxHalvings, where a step is kept as it comes (Baraff and Witkin, 1998, control their
// implicit step by the stretch it causes in the same spirit). A large step fails where its
// one linearisation (implicit Euler) or its few sweeps (vbd) cannot follow the motion, as in an
// impact: the halves are paid there only.
//
// It wraps the backend's solver (solver_factory makes it where the scene declares the key). The
// backend's StepCheck (solver/step_check.h) keeps each step's start, measures the step and puts
// the start back where the state lives: the GPU reads back no state for it. A scene without the
// key pays none of it.
#pragma once

#include <memory>

#include "solver/solver.h"
#include "solver/step_check.h"

namespace cloth {

class StepControl final : public Solver {
public:
    static constexpr int kMaxHalvings = 4;  // the shortest step: Δt / 16

    StepControl(std::unique_ptr<Solver> backend, const Scene& scene);

    StepResult step(long n) override;
    SimState read() const override { return backend_->read(); }
    Features features() const override { return backend_->features(); }
    std::string name() const override { return backend_->name(); }
    void write(const SimState& state) override;
    void setPinned(int i, int j, bool pinned) override { backend_->setPinned(i, j, pinned); }
    void setGrab(const std::optional<Grab>& grab) override { backend_->setGrab(grab); }
    void setParameters(const Scene& scene) override;
    void setColliderDrag(int index, const glm::dvec3& offset, const glm::dvec3& velocity) override {
        backend_->setColliderDrag(index, offset, velocity);
    }
    std::optional<DrawBuffers> drawBuffers() const override { return backend_->drawBuffers(); }
    DeviceReport deviceReport() const override { return backend_->deviceReport(); }
    PassTimes timePasses(int repeats) override { return backend_->timePasses(repeats); }
    SelfCollisionStats selfCollisionStats() const override {
        return backend_->selfCollisionStats();
    }
    std::vector<std::int64_t> selfContactVertices() const override {
        return backend_->selfContactVertices();
    }
    StepControlStats stepControlStats() const override { return stats_; }

private:
    // Advances the backend by `dt` from its state now, as one step or, where that one fails the
    // check, as two of dt/2; depth halvings below the scene's Δt. Returns the result of the last
    // step kept (unstable only where a step of the shortest length is).
    StepResult advance(double dt, int depth);
    void setBackendDt(double dt);
    // solveStats_ from the backend's after a step, its first miss and breakdown numbered by the
    // scene's steps; `before`: the backend's before that step.
    void recordSolves(const SolveStats& before);

    std::unique_ptr<Solver> backend_;
    StepCheck& check_;      // the backend's
    Scene scene_;           // the parameters, with the scene's Δt
    double backendDt_ = 0;  // the Δt the backend steps by now
    int startDepth_ = 0;    // the halvings the next step starts at
    int deepest_ = 0;       // the most halvings of a piece kept in this step
    bool failed_ = false;   // whether a piece of this step failed the check
    StepControlStats stats_;
};

}  // namespace cloth
