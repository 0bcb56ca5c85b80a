// The step control's hold on a backend's state (solver/step_control.h): it keeps a step's start,
// measures what the step did to the structural springs, and puts the start back where the step
// fails the check. Each backend does all three where its state lives (Solver::stepCheck): the
// CPU copies its arrays (cpu/cpu_step_check.cpp); the GPU copies two buffers within the device
// and reads back only its work groups' largest growth (gpu/gpu_step_check.cpp), never the state.
#pragma once

#include "solver/solver.h"

namespace cloth {

class StepCheck {
public:
    virtual ~StepCheck() = default;
    // Keeps the state now as the step's start.
    virtual void keep() = 0;
    // How much the step since keep() grew some structural spring's stretch max(0, (|d| − L)/L),
    // as largestStretchGrowth (solver/diagnostics.h) measures it; +inf where a length is not
    // finite.
    virtual double stretchGrowth() = 0;
    // Puts the kept state back, its time included, as Solver::write would.
    virtual void restore() = 0;
};

}  // namespace cloth
