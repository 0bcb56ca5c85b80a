#include "solver/step_check.h"

#include <utility>

#include "solver/diagnostics.h"

namespace cloth {

void HostStepCheck::keep() {
    if (!known_) now_ = solver_.read();
    start_ = std::move(now_);
    known_ = false;
}

double HostStepCheck::stretchGrowth(const Scene& scene) {
    now_ = solver_.read();
    known_ = true;
    return largestStretchGrowth(scene, start_, now_).strain;
}

void HostStepCheck::restore() {
    solver_.write(start_);  // the step's start, its time included
    now_ = std::move(start_);
    known_ = true;
}

}  // namespace cloth
