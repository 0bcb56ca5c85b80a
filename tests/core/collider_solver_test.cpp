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

#include "core/collider_mesh.h"
#include "core/scene_loader.h"
#include "core/solver.h"
#include "reference/reference.h"
#include "reference/reference_colliders.h"
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

// An OBJ of a closed box (0.5 × 0.1 × 0.4), written by the project itself, for the mesh collider.
std::string writeBoxObj(const fs::path& dir) {
    const fs::path obj = dir / "slab.obj";
    writeMeshesObj(obj.string(),
                   {{"slab", boxMesh({{0, 0, 0}, {0.25, 0.05, 0.2}, glm::dmat3(1)})}});
    return obj.string();
}

struct Case {
    std::string name;
    Json colliders;
};

// Each shape alone, with thickness, friction and motion, and all of them together. The cloth
// starts 0.1–0.3 m above them and lands within the run.
std::vector<Case> cases() {
    const Json box = {{"type", "box"},
                      {"center", {0.02, 0.7, 0.01}},
                      {"half_extents", {0.2, 0.05, 0.15}},
                      {"rotation", {{"axis", {1, 0, 0.3}}, {"degrees", 12}}}};
    const Json capsule = {{"type", "capsule"},
                          {"a", {-0.25, 0.8, 0.05}},
                          {"b", {0.2, 0.75, -0.05}},
                          {"radius", 0.08}};
    const Json mesh = {{"type", "mesh"},
                       {"file", "slab.obj"},
                       {"cell", 0.02},
                       {"band", 0.06},
                       {"translation", {0, 0.75, 0}},
                       {"rotation", {{"axis", {0, 0, 1}}, {"degrees", 8}}}};
    const Json plane = {{"type", "plane"}, {"point", {0, 0.85, 0}}, {"normal", {0.1, 1, 0}}};
    const Json sphere = {{"type", "sphere"}, {"center", {0.05, 0.7, 0}}, {"radius", 0.2}};
    auto with = [](Json c, const Json& extra) {
        c.update(extra);
        return c;
    };
    const Json contact = {{"thickness", 0.01}, {"friction", 0.4}};
    const Json rising = {{"motion", {{"type", "linear"}, {"velocity", {0.1, 0.5, 0}}}}};
    const Json turning = {{"motion",
                           {{"type", "rotation"},
                            {"axis", {0, 1, 0}},
                            {"pivot", {0, 0, 0}},
                            {"degrees_per_second", 90}}}};
    const Json swinging = {{"motion",
                            {{"type", "oscillation"},
                             {"axis", {1, 0, 0}},
                             {"amplitude", 0.05},
                             {"frequency", 2},
                             {"phase_degrees", 30}}}};
    return {
        {"box", Json{box}},
        {"capsule", Json{capsule}},
        {"mesh", Json{mesh}},
        {"plane_thickness_friction", Json{with(plane, contact)}},
        {"sphere_thickness_friction", Json{with(sphere, contact)}},
        {"box_friction_rising", Json{with(with(box, contact), rising)}},
        {"capsule_turning", Json{with(with(capsule, contact), turning)}},
        {"sphere_swinging", Json{with(sphere, swinging)}},
        {"mesh_friction_turning", Json{with(with(mesh, contact), turning)}},
        {"all_combined",
         Json{with(box, contact), with(capsule, turning), with(mesh, Json{{"thickness", 0.005}}),
              with(sphere, swinging), with(plane, rising)}},
    };
}

class ColliderSolver : public ::testing::TestWithParam<Case> {
protected:
    static void SetUpTestSuite() {
        dir_ = test::freshTempDir("ColliderSolver", "mesh");
        writeBoxObj(dir_);
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

// The distance of p outside every collider of the reference at time t, minus its thickness:
// the reference's own shapes (no code shared with src/), ≥ 0 after each step.
double worstPenetration(const ref::Params& prm, double t, const std::vector<glm::dvec3>& ps) {
    double worst = 1e300;
    for (const ref::Collider& c : prm.colliders) {
        for (const glm::dvec3& q : ps) {
            // A probe vertex at rest that collideMoving() would push out by exactly the
            // penetration: measure it by how far it moves.
            ref::V3 p{q.x, q.y, q.z}, v{0, 0, 0};
            ref::Collider probe = c;
            probe.extended = true;
            probe.friction = 0;
            ref::collideMoving(probe, t, p, v);
            const double moved = std::hypot(p[0] - q.x, p[1] - q.y, p[2] - q.z);
            worst = std::min(worst, -moved);
        }
    }
    return worst;
}

// Law: the CPU backend applies docs/colliders.md's response exactly as the reference does —
// double to rounding until contacts chatter, float to float rounding, over 0.4 s of falling
// and resting. Invariant: no vertex ends any step inside a collider (φ ≥ h − ε).
TEST_P(ColliderSolver, MatchesTheReferenceAndEndsNoStepInside) {
    const Case& c = GetParam();
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
            worstInside = std::min(
                worstInside, worstPenetration(prm, double(n) * s.integrator.dt, sd.positions));
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

INSTANTIATE_TEST_SUITE_P(EveryShape, ColliderSolver, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

// ---- friction at cloth level -----------------------------------------------------------------

// A 5×5 cloth, 0.1 m square, lying flat on a box tilted by θ about x (friction c_f, h = 2 mm),
// released at rest: how far its centre moves in 1 s [m]. docs/colliders.md §2: it holds iff
// tan θ ≤ c_f, up to the creep of the seed's explicit Euler (≈ ½ g sin θ Δt m/s). The springs
// keep explicit Euler inside its bound Δt < μ/λ_max (DESIGN.md §2): λ_max ≤ 2·4·(0.1 + 0.025)
// = 1 N/m and μ = 0.002 give 2 ms against Δt = 1 ms (the GPU test's scene; with K = 20 N/m the
// bound is 10 µs and a sliding cloth blows up near step 400). The run must stay stable.
double slideOnTiltedBox(double degrees, double friction) {
    const double t = degrees * std::numbers::pi / 180;
    const double top = 0.05 + 0.002;  // the box's half height + h
    // The cloth's plane: the box's top face, tilted about x (y, z turn together).
    const glm::dvec3 up(0, std::cos(t), std::sin(t)), along(0, -std::sin(t), std::cos(t));
    const glm::dvec3 centre = top * up;
    Json j = Json::parse(R"({
      "cloth": { "resolution": [5, 5], "size": [0.1, 0.1], "mass": 0.001 },
      "springs": { "structural": 0.1, "shear": 0.025 },
      "damping": 0.002,
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "duration": 1.0
    })");
    const glm::dvec3 origin = centre - 0.05 * glm::dvec3(1, 0, 0) - 0.05 * along;
    j["cloth"]["origin"] = {origin.x, origin.y, origin.z};
    j["cloth"]["u_axis"] = {1, 0, 0};
    j["cloth"]["v_axis"] = {along.x, along.y, along.z};
    j["colliders"] = Json::array({{{"type", "box"},
                                   {"center", {0, 0, 0}},
                                   {"half_extents", {1, 0.05, 1}},
                                   {"rotation", {{"axis", {1, 0, 0}}, {"degrees", degrees}}},
                                   {"thickness", 0.002},
                                   {"friction", friction}}});
    const Scene s = parseScene(j.dump(), "tilted box (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    auto mean = [](const SimState& st) {
        glm::dvec3 m(0);
        for (const glm::dvec3& p : st.positions) m += p;
        return m / double(st.positions.size());
    };
    const glm::dvec3 start = mean(solver->read());
    const StepResult r = solver->step(s.defaultSteps());
    EXPECT_FALSE(r.unstable) << degrees << "°, c_f " << friction << ": " << r.reason << " at step "
                             << r.firstBadStep;
    return glm::length(mean(solver->read()) - start);
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
    Json j = Json::parse(R"({
      "cloth": { "resolution": [6, 6], "size": [0.2, 0.2], "origin": [-0.1, 0.1021, -0.1],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.001 },
      "springs": { "structural": 20.0, "shear": 5.0 },
      "damping": 0.002,
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "duration": 1.0,
      "colliders": [ { "type": "box", "center": [0, 0, 0], "half_extents": [0.5, 0.1, 0.5],
                       "thickness": 0.002, "friction": 0.8,
                       "motion": { "type": "linear", "velocity": [0.3, 0, 0] } } ]
    })");
    const Scene s = parseScene(j.dump(), "moving box (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const StepResult r = solver->step(s.defaultSteps());
    EXPECT_FALSE(r.unstable) << r.reason << " at step " << r.firstBadStep;
    glm::dvec3 v(0);
    const SimState st = solver->read();
    for (const glm::dvec3& w : st.velocities) v += w;
    v /= double(st.velocities.size());
    double minY = 1e300;
    for (const glm::dvec3& p : st.positions) minY = std::min(minY, p.y);
    std::printf("box at 0.3 m/s: cloth's mean velocity after 1 s (%.4f, %.4f, %.4f) m/s\n", v.x,
                v.y, v.z);
    EXPECT_NEAR(v.x, 0.3, 0.01);
    EXPECT_NEAR(v.z, 0.0, 0.01);
    EXPECT_GT(minY, 0.1 + 0.002 - 1e-6) << "the cloth sank into the box";
}

}  // namespace
}  // namespace cloth
