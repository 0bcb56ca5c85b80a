// Runs of the shared contact scenes (support/contact_scenes.h) on the CPU that more than one
// integrator's tests measure (tests/cpu/implicit_contact_test.cpp, tests/cpu/vbd_contact_test.cpp).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/contact_scenes.h"

namespace cloth::test {

// sheetOverSphere(friction, integrator) run for 1.5 s on the CPU in double: its vertices' mean
// height [m].
inline double meanHeightOnSphere(double friction, const Json& integrator) {
    const Scene s = parseScene(sheetOverSphere(friction, integrator).dump(), "test");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const StepResult r = solver->step(std::lround(1.5 / s.integrator.dt));
    EXPECT_FALSE(r.unstable) << r.reason;
    return meanOf(solver->read().positions).y;
}

}  // namespace cloth::test
