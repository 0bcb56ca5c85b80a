// The colliders of docs/colliders.md in the CPU solver, at cloth level: every shape alone and
// combined, with thickness, friction and motion, against the double reference (tests/reference);
// nothing ends a step inside a collider; friction holds a cloth on a tilted box below the
// friction angle and lets it slide above; a moving box carries the cloth resting on it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "cpu/cpu_backend.h"
#include "model/collider_mesh.h"
#include "reference/reference.h"
#include "reference/reference_colliders.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/collider_cases.h"
#include "support/contact_scenes.h"
#include "support/process.h"
#include "support/reference_bridge.h"

namespace cloth {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

// A 13×11 cloth, 0.6 m × 0.5 m, level at y = 1, falling from rest onto colliders 0.1–0.3 m
// below. Symplectic Euler, inside its bound (λ/m)Δt² + 2cΔt < 4 with λ_max ≤ 2·4·(300 + 100 +
// 20) = 3360 N/m, m = 0.01 kg, c = μ/m = 1/s: Δt < 2/√(λ/m) = 3.4 ms; Δt = 0.5 ms.
Json fallingCloth() {
    return Json::parse(R"({
      "cloth": { "resolution": [13, 11], "size": [0.6, 0.5], "origin": [-0.3, 1.0, -0.25],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.01 },
      "springs": { "structural": 300.0, "shear": 100.0, "bend": 20.0 },
      "damping": 0.01,
      "integrator": { "method": "symplectic_euler", "dt": 0.0005 }
    })");
}

class ColliderSolver : public ::testing::TestWithParam<test::ColliderCase> {
protected:
    static void SetUpTestSuite() {
        dir_ = test::freshTempDir("ColliderSolver", "mesh");
        test::writeSlabObj(dir_);
    }
    static Scene scene(const Json& colliders, double duration) {
        Json j = fallingCloth();
        j["colliders"] = colliders;
        j["duration"] = duration;
        return parseScene(j.dump(), (dir_ / "scene.json").string());
    }
    static fs::path dir_;
};
fs::path ColliderSolver::dir_;

// Law: the CPU backend applies docs/colliders.md's response exactly as the reference does —
// double to rounding until contacts chatter, float to float rounding, over 0.4 s of falling
// and resting. Invariant: no vertex ends any step inside a collider (φ ≥ h − ε).
TEST_P(ColliderSolver, MatchesTheReferenceAndEndsNoStepInside) {
    const test::ColliderCase& c = GetParam();
    const Scene s = scene(c.colliders, 0.4);
    const long steps = s.defaultSteps();
    const double extent = s.grid().extent();
    const ref::Params prm = toReference(s);
    ref::Simulation reference(prm);
    auto dbl = makeCpuSolver(s, {Precision::Double, 1});
    auto flt = makeCpuSolver(s, {Precision::Float, 1});
    double devDouble = 0, devFloat = 0, worstInside = 0, moved = 0;
    for (long n = 1; n <= steps; ++n) {
        reference.step();
        ASSERT_FALSE(dbl->step(1).unstable) << c.name << ": double, step " << n;
        ASSERT_FALSE(flt->step(1).unstable) << c.name << ": float, step " << n;
        const SimState sd = dbl->read(), sf = flt->read();
        devDouble = std::max(devDouble, maxDeviationOverExtent(sd, reference, extent));
        devFloat = std::max(devFloat, maxDeviationOverExtent(sf, reference, extent));
        if (n % 10 == 0 || n == steps)
            worstInside =
                std::min(worstInside,
                         test::worstPenetration(prm, double(n) * s.integrator.dt, sd.positions));
    }
    // The colliders were reached: the cloth's lowest point ends well above its free fall.
    double lowest = 1e300;
    for (const glm::dvec3& p : dbl->read().positions) lowest = std::min(lowest, p.y);
    moved = lowest - (1.0 - 0.5 * 9.81 * 0.4 * 0.4);
    std::printf(
        "%-26s max |p - p_ref| / extent: double %.3g, float %.3g; deepest %.3g m; held "
        "%.3g m above free fall\n",
        c.name.c_str(), devDouble, devFloat, -worstInside, moved);
    EXPECT_GT(moved, 0.05) << "the cloth never met the collider";
    EXPECT_LT(devDouble, 1e-10) << c.name;
    EXPECT_LT(devFloat, 2e-3) << c.name;
    // An analytic shape puts the vertex on φ = h to rounding. A mesh's φ is trilinear, so one
    // step of h − φ along its gradient lands within a small fraction of a cell of φ = h
    // (measured 0.7 % of the cell here).
    const double slack = c.name.find("mesh") != std::string::npos ? 0.02 * 0.02 : 1e-9;
    EXPECT_GT(worstInside, -slack) << c.name << ": a vertex ended a step inside";
}

INSTANTIATE_TEST_SUITE_P(EveryShape, ColliderSolver, ::testing::ValuesIn(test::colliderCases()),
                         [](const ::testing::TestParamInfo<test::ColliderCase>& p) {
                             return p.param.name;
                         });

// ---- friction at cloth level -----------------------------------------------------------------

// How far the centre of test::clothOnTiltedBox(degrees, friction) moves in 1 s [m], on the CPU
// in double (the GPU test's scene). The run must stay stable.
double slideOnTiltedBox(double degrees, double friction) {
    const Scene s =
        parseScene(test::clothOnTiltedBox(degrees, friction).dump(), "tilted box (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const glm::dvec3 start = test::meanOf(solver->read().positions);
    const StepResult r = solver->step(s.defaultSteps());
    EXPECT_FALSE(r.unstable) << degrees << "°, c_f " << friction << ": " << r.reason << " at step "
                             << r.firstBadStep;
    return glm::length(test::meanOf(solver->read().positions) - start);
}

// Law (Coulomb, docs/colliders.md §2): a cloth on a slope holds below the friction angle
// atan(c_f) and slides above it, whatever the cloth's springs do in between.
TEST(ColliderFriction, ClothHoldsBelowTheFrictionAngleAndSlidesAbove) {
    for (double cf : {0.3, 0.6, 1.0}) {
        const double angle = std::atan(cf) * 180 / std::numbers::pi;
        const double below = slideOnTiltedBox(angle - 3, cf);
        const double above = slideOnTiltedBox(angle + 3, cf);
        std::printf(
            "friction %.1f (atan %.2f°): centre moves %.3g m in 1 s at %.2f°, %.3g m at "
            "%.2f°\n",
            cf, angle, below, angle - 3, above, angle + 3);
        EXPECT_LT(below, 0.01) << "c_f " << cf << ": slid below the friction angle";
        EXPECT_GT(above, 0.05) << "c_f " << cf << ": held above the friction angle";
    }
}

// Law: static friction carries the cloth with a moving collider (v = v_c at a sticking
// contact): on a box moving sideways at 0.3 m/s, the cloth's mean velocity approaches it. The
// springs (the GPU test's twin) are outside explicit Euler's bound, but every vertex sticks
// every step, which sets its velocity to v_c and leaves no mode to grow: the run is stable.
TEST(ColliderMotion, MovingBoxCarriesTheClothRestingOnIt) {
    const Scene s = parseScene(test::clothOnMovingBox().dump(), "moving box (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const StepResult r = solver->step(s.defaultSteps());
    EXPECT_FALSE(r.unstable) << r.reason << " at step " << r.firstBadStep;
    const SimState st = solver->read();
    const glm::dvec3 v = test::meanOf(st.velocities);
    const double minY = test::lowestY(st.positions);
    std::printf("box at 0.3 m/s: cloth's mean velocity after 1 s (%.4f, %.4f, %.4f) m/s\n", v.x,
                v.y, v.z);
    EXPECT_NEAR(v.x, 0.3, 0.01);
    EXPECT_NEAR(v.z, 0.0, 0.01);
    EXPECT_GT(minY, 0.1 + 0.002 - 1e-6) << "the cloth sank into the box";
}

}  // namespace
}  // namespace cloth
