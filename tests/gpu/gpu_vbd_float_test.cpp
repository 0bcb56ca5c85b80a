// vbd on the GPU far from the origin, as on the CPU (tests/cpu/vbd_float_test.cpp): the step's
// displacement is iterated beside the position (vbdDisplacement), so a sheet at 10 m falls as
// backward Euler's closed form at Δt = 0.2 ms, where h² g is below half an ulp of its coordinates.
// Iterating the position alone, it never fell.
#include <memory>

#include "gpu/gpu_test_support.h"
#include "support/far_fall.h"

namespace cloth::test {
namespace {

class GpuVbdFloat : public GpuTest {};

TEST_F(GpuVbdFloat, ASheetFarAboveTheOriginFallsAsBackwardEulersClosedForm) {
    std::unique_ptr<Solver> solver = makeGpuSolver(farFallScene(), {});
    const FarFall f = measureFarFall(*solver, "gpu");
    EXPECT_LT(f.speedError, 1e-4);
    EXPECT_LT(f.fallError, f.roundingBound);
}

}  // namespace
}  // namespace cloth::test
