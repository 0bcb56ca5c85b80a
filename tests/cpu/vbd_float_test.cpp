// vbd in float far from the origin (docs/integrators.md "vbd", the iterate): the step's
// displacement x − x_n is iterated beside the position, so a float cloth at 10 m, where h² g is
// below half an ulp of the coordinates, still falls as backward Euler's closed form: its velocity
// to float's rounding of the displacement, its position to the rounding of x_n + Δx, at most half
// an ulp a step (tests/support/far_fall.h). Iterating the position alone, it never fell.
#include <gtest/gtest.h>

#include <memory>

#include "cpu/cpu_backend.h"
#include "support/far_fall.h"

namespace cloth {
namespace {

TEST(VbdFloat, ASheetFarAboveTheOriginFallsAsBackwardEulersClosedForm) {
    for (int threads : {1, 2}) {
        std::unique_ptr<Solver> solver = makeCpuSolver(farFallScene(), {Precision::Float, threads});
        const FarFall f =
            measureFarFall(*solver, threads == 1 ? "cpu float" : "cpu float, 2 threads");
        EXPECT_LT(f.speedError, 1e-4) << threads;
        EXPECT_LT(f.fallError, f.roundingBound) << threads;
    }
}

}  // namespace
}  // namespace cloth
