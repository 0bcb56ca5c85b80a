// The step control's hold on a backend's state (solver/step_control.h): it keeps a step's start,
// measures what the step did to the structural springs, and puts the start back where the step
// fails the check. A backend that keeps its state on a device does all three there
// (Solver::deviceStepCheck; the GPU: a copy of two buffers, one reduction pass and a read of its
// work groups' maxima); HostStepCheck does them for any backend through read() and write().
#pragma once

#include "solver/solver.h"

namespace cloth {

class StepCheck {
public:
    virtual ~StepCheck() = default;
    // Keeps the state now as the step's start.
    virtual void keep() = 0;
    // How much the step since keep() grew some structural spring's stretch max(0, (|d| − L)/L),
    // as largestStretchGrowth (solver/diagnostics.h) measures it; NaN or +inf where a length is
    // not finite (a check `growth ≤ limit` fails on either).
    virtual double stretchGrowth(const Scene& scene) = 0;
    // Puts the kept state back, its time included, as Solver::write would; the next keep()
    // keeps it again.
    virtual void restore() = 0;
    // The state was changed from outside since the last call (write, setPinned): a copy of it
    // kept to save a read is stale.
    virtual void forget() {}
};

// Through the solver's read() and write(): a read after each step, which is the next step's
// start, and a write where a step is thrown away.
class HostStepCheck final : public StepCheck {
public:
    explicit HostStepCheck(Solver& solver) : solver_(solver) {}
    void keep() override;
    double stretchGrowth(const Scene& scene) override;
    void restore() override;
    void forget() override { known_ = false; }

private:
    Solver& solver_;
    SimState start_;  // the kept state
    SimState now_;    // the solver's state now, where known_
    bool known_ = false;
};

}  // namespace cloth
