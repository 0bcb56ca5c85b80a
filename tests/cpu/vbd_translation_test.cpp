// vbd's translation step (integrator.translation_sweeps; docs/integrators.md "vbd", few sweeps):
// the Newton step of G on the rigid translation of the free vertices, the mode a sweep barely
// moves. Each test names the law it checks, and shows that 10 sweeps alone do not meet it:
// - Coulomb on a slope holds for a stiff sheet too: it slides as the block does, frictionless
//   and with friction, at Δt = 1/60 and 10 sweeps;
// - a hanging sheet carries its weight to its pins at few sweeps: the shipped denim sheet stays
//   whole at 5 sweeps a step, where without the step it tears;
// - the step changes where the sweeps go, not where they converge: 300 sweeps give the same
//   state with and without it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <utility>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "support/contact_runs.h"

namespace cloth {
namespace {

constexpr double kDt = 1.0 / 60;

double slide(const Scene& s) {
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    return test::slideInOneSecond(*solver, kDt);
}

// Measured: frictionless at 10°, 0.4854 m against the block's 0.4854 (0.236 without the step);
// c_f 0.5 at 31.6°, 0.2731 against 0.2743 (0.194 without).
TEST(VbdTranslation, AStiffSheetSlidesAsCoulombsBlockAtTenSweeps) {
    const double angle = std::atan(0.5) * 180 / std::numbers::pi + 5;
    for (auto [degrees, friction] : {std::pair{10.0, 0.0}, std::pair{angle, 0.5}}) {
        const Scene with = test::stiffSheetOnSlope(degrees, friction, 10);
        const double expected = test::coulombBlockSlide(degrees, friction, with.dampingRate(), kDt);
        const double slid = slide(with),
                     alone = slide(test::stiffSheetOnSlope(degrees, friction, 0));
        std::printf(
            "%.1f°, c_f %.1f: slid %.4f m with the translation's step, %.4f without; "
            "block %.4f m\n",
            degrees, friction, slid, alone, expected);
        EXPECT_NEAR(slid, expected, 0.01 * expected) << degrees;
        EXPECT_LT(alone, 0.8 * expected) << degrees << ": the sweeps alone already slide";
    }
}

// The shipped hanging denim sheet (24², two pins) at Δt = 1/60 and 5 sweeps: the tension that
// holds it reaches one vertex further from the pins each sweep, so the sweeps alone let it tear
// (strain past its max_strain, 1); the translation's step, whose Hessian holds the pins' springs,
// lifts the whole sheet onto them. Checked every 0.1 s for 3 s, as the command line does. The
// swing stretches the sheet itself: 100 sweeps without the step peak at a strain of 0.24; 5 with
// it at 0.30, without it at 4.4.
TEST(VbdTranslation, AHangingSheetHoldsOnItsPinsAtFiveSweeps) {
    Scene s = loadScene(CLOTH_SOURCE_DIR "/scenes/hanging.json");
    s.integrator.method = Method::Vbd;
    s.integrator.dt = kDt;
    s.integrator.iterations = 5;
    double strain[2];
    for (int sweeps : {0, 1}) {
        s.integrator.translationSweeps = sweeps;
        auto solver = makeCpuSolver(s, {Precision::Float, 2});
        strain[sweeps] = test::largestStrainOver(*solver, s, 3.0);
    }
    std::printf(
        "hanging denim, 5 sweeps: largest strain %.3g with the translation's step, %.3g "
        "without (max_strain %g)\n",
        strain[1], strain[0], s.maxStrain);
    EXPECT_LT(strain[1], 0.5);
    EXPECT_GT(strain[0], s.maxStrain) << "the sweeps alone held it";
}

// Converged, vbd is backward Euler whatever path its sweeps took: 300 sweeps with the step after
// each of the first ten and without it end 1 s of the stiff slide within 1e-5 m of each other
// (2.5e-6 m measured, where 10 sweeps part them by 0.25 m).
TEST(VbdTranslation, ItChangesThePathNotTheConvergedStep) {
    Scene with = test::stiffSheetOnSlope(10, 0, 10), without = test::stiffSheetOnSlope(10, 0, 0);
    with.integrator.iterations = without.integrator.iterations = 300;
    const double most = test::farthestApartAfter(with, without, 60);
    std::printf("300 sweeps with and without the translation's step: %.3g m apart\n", most);
    EXPECT_LT(most, 1e-5);
}

}  // namespace
}  // namespace cloth
