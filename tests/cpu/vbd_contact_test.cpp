// vbd's contact and friction (docs/integrators.md "vbd", contact and friction) at the real-time
// step Δt = 1/60 s, each test named by the law it checks:
// - Coulomb: a cloth on a slope holds below the friction angle, and above it slides as a block
//   does, s = ½ g (sin θ − μ cos θ) t² (to backward Euler's discrete sum);
// - static friction holds what the sheet's own tension presses on: a sheet wrapped off-centre
//   over a sphere stays on it (as symplectic Euler's small steps keep it), and slides off
//   without friction;
// - friction acts against the surface's motion: a cloth on a moving box is carried at its speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/contact_runs.h"
#include "support/contact_scenes.h"

namespace cloth {
namespace {

constexpr double kDt = 1.0 / 60;

const test::Json kVbd = {{"method", "vbd"}, {"dt", kDt}, {"iterations", 10}};

// The centre's displacement along the slope after 1 s of test::clothOnTiltedBox with vbd at
// Δt = 1/60, CPU double.
double slide(double degrees, double friction) {
    test::Json j = test::clothOnTiltedBox(degrees, friction);
    j["integrator"] = kVbd;
    const Scene s = parseScene(j.dump(), "tilted box, vbd (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const glm::dvec3 start = test::meanOf(solver->read().positions);
    const StepResult r = solver->step(std::lround(1.0 / kDt));
    EXPECT_FALSE(r.unstable) << degrees << "°: " << r.reason << " at step " << r.firstBadStep;
    return glm::length(test::meanOf(solver->read().positions) - start);
}

// Law (Coulomb): below atan(c_f) the cloth holds (up to the creep below ε_v = 1 mm/s); above, its
// centre slides as a block with a = g (sin θ − μ cos θ) against the scene's drag c: backward
// Euler's v_{n+1} = (v_n + h a)/(1 + h c), s_{n+1} = s_n + h v_{n+1}. Measured: 0.7 mm at
// 23.6°; 0.2751 m against 0.2743 m at 31.6°, 0.8108 against 0.8107 at 41.6°. Before friction
// entered the local problem (the projection's friction on each iterate) the cloth held at every
// angle.
TEST(VbdContact, FrictionHoldsBelowTheFrictionAngleAndTheSlideFollowsCoulomb) {
    const double cf = 0.5, g = 9.81;
    const double drag = parseScene(test::clothOnTiltedBox(30, cf).dump(), "test").dampingRate();
    const double angle = std::atan(cf) * 180 / std::numbers::pi;
    const double below = slide(angle - 3, cf);
    EXPECT_LT(below, 0.002) << "slid below the friction angle";
    for (double degrees : {angle + 5, angle + 15}) {
        const double t = degrees * std::numbers::pi / 180;
        const double a = g * (std::sin(t) - cf * std::cos(t));
        double v = 0, expected = 0;
        for (long n = 0; n < std::lround(1.0 / kDt); ++n) {
            v = (v + kDt * a) / (1 + kDt * drag);
            expected += kDt * v;
        }
        const double moved = slide(degrees, cf);
        std::printf(
            "vbd, c_f %.1f: %.2f° held to %.3g m; %.2f° slid %.4f m, Coulomb block %.4f m\n", cf,
            angle - 3, below, degrees, moved, expected);
        EXPECT_NEAR(moved, expected, 0.01 * expected) << degrees << "°";
    }
}

// Law (Coulomb, static friction): a sheet wrapped off-centre over a sphere is held by friction
// against its own tension, which presses it onto the sphere; without friction it slides off.
// Symplectic Euler at Δt = 0.4 ms is the comparison (0.475 m).
TEST(VbdContact, StaticFrictionHoldsASheetWrappedOverASphere) {
    const double small =
        test::meanHeightOnSphere(0.8, {{"method", "symplectic_euler"}, {"dt", 4e-4}});
    const double held = test::meanHeightOnSphere(0.8, kVbd);
    const double slid = test::meanHeightOnSphere(0.0, kVbd);
    std::printf(
        "sheet on a sphere, c_f 0.8, 1.5 s: vbd at 1/60 s %.3f m (frictionless %.3f m), "
        "symplectic Euler at 0.4 ms %.3f m\n",
        held, slid, small);
    EXPECT_NEAR(held, small, 0.06);
    EXPECT_LT(slid, 0.0) << "held without friction";
}

// Law (static friction against a moving surface): friction's slide is taken against the
// surface's own displacement h v_c, so a cloth resting on a box that moves at 0.3 m/s is carried
// at 0.3 m/s.
TEST(VbdContact, AMovingBoxCarriesTheClothAtItsSpeed) {
    test::Json j = test::clothOnMovingBox();
    j["integrator"] = kVbd;
    const Scene s = parseScene(j.dump(), "moving box, vbd (test)");
    for (Precision precision : {Precision::Double, Precision::Float}) {
        auto solver = makeCpuSolver(s, {precision, 1});
        ASSERT_FALSE(solver->step(s.defaultSteps()).unstable);
        const glm::dvec3 v = test::meanOf(solver->read().velocities);
        std::printf("vbd %s: box at 0.3 m/s: cloth's mean velocity after 1 s (%.4f, %.4f, %.4f)\n",
                    precisionName(precision), v.x, v.y, v.z);
        EXPECT_NEAR(v.x, 0.3, 1e-3);
        EXPECT_NEAR(v.z, 0.0, 1e-3);
    }
}

}  // namespace
}  // namespace cloth
