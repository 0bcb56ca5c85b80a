// Pins that follow a moving collider (docs/colliders.md §5): the scene keys round-trip and bad
// ones are refused naming `pins[k].follow`; on the CPU a follow pin is exactly where the
// collider's pose puts its grid position, with the collider's velocity, under every integrator
// and every motion; the CPU in double matches the reference; the viewer's setPinned still works.
#include "model/pin_follow.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cpu/cpu_backend.h"
#include "model/errors.h"
#include "scene/scene_json.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/follow_scene.h"
#include "support/reference_bridge.h"

namespace cloth {
namespace {

using Json = nlohmann::json;

using test::followScene;
using test::kSwinging;
using test::kTurning;
using test::kWalking;
using test::parseFollowScene;

// The pose written out independently of collider_motion.h: the rotation about y by θ through
// the pivot, the linear shift, the sine swing.
glm::dvec3 expectedPosition(const Json& motion, double t, const glm::dvec3& x0) {
    const std::string type = motion["type"];
    if (type == "linear")
        return x0 +
               t * glm::dvec3(motion["velocity"][0], motion["velocity"][1], motion["velocity"][2]);
    if (type == "oscillation") {
        const double w = 2 * M_PI * double(motion["frequency"]);
        const double s = double(motion["amplitude"]) *
                         std::sin(w * t + double(motion["phase_degrees"]) * M_PI / 180);
        return x0 + glm::dvec3(0, 0, s);
    }
    const glm::dvec3 o(motion["pivot"][0], motion["pivot"][1], motion["pivot"][2]);
    const double th = double(motion["degrees_per_second"]) * t * M_PI / 180;
    const glm::dvec3 d = x0 - o;
    return o + glm::dvec3(std::cos(th) * d.x + std::sin(th) * d.z, d.y,
                          -std::sin(th) * d.x + std::cos(th) * d.z);
}

TEST(PinFollow, KeysRoundTripExactly) {
    const Scene a = parseFollowScene(followScene(kTurning));
    ASSERT_EQ(a.pins.size(), 3u);
    EXPECT_EQ(a.pins[0].follow, 1);
    EXPECT_EQ(a.pins[1].follow, -1);
    EXPECT_EQ(a.pins[2].i, 6);
    EXPECT_EQ(a.pins[2].follow, 1);
    const std::string saved = sceneToJson(a);
    const Json pins = Json::parse(saved)["pins"];
    EXPECT_EQ(pins[0], Json::parse(R"({"at": [0, 0], "follow": 1})"));
    EXPECT_EQ(pins[1], Json::parse("[3, 0]"));
    const Scene b = parseScene(saved, "saved.json");
    EXPECT_EQ(saved, sceneToJson(b));
    for (size_t k = 0; k < a.pins.size(); ++k) {
        EXPECT_EQ(a.pins[k].i, b.pins[k].i);
        EXPECT_EQ(a.pins[k].j, b.pins[k].j);
        EXPECT_EQ(a.pins[k].follow, b.pins[k].follow);
    }
}

void expectRefused(const Json& scene, const std::string& key, const std::string& part) {
    try {
        parseFollowScene(scene);
        ADD_FAILURE() << "accepted; expected an error at " << key;
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), key) << e.what();
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        EXPECT_EQ(e.file(), "follow.json");
    }
}

TEST(PinFollow, BadFollowsAreRefusedNamingTheKey) {
    Json j = followScene(kTurning);
    j["pins"][2]["follow"] = 0;  // the plane has no motion
    expectRefused(j, "pins[2].follow", "has no motion");
    j["pins"][2]["follow"] = 2;
    expectRefused(j, "pins[2].follow", "does not exist");
    j["pins"][2]["follow"] = -1;
    expectRefused(j, "pins[2].follow", ">= 0");
    j["pins"][2]["follow"] = "capsule";
    expectRefused(j, "pins[2].follow", "expected an integer");
    j["pins"][2] = Json::parse(R"({"follow": 1})");
    expectRefused(j, "pins[2].at", "required key is missing");
    j["pins"][2] = Json::parse(R"({"at": [0, 0, 0], "follow": 1})");
    expectRefused(j, "pins[2].at", "expected a pair");
    j["pins"][2] = Json::parse(R"({"at": [9, 0], "follow": 1})");
    expectRefused(j, "pins[2].at", "outside the 7 x 5 grid");
    j["pins"][2] = Json::parse(R"({"at": [0, 0], "follow": 1})");
    expectRefused(j, "pins[2].at", "a second time");
    j["pins"][2] = Json::parse(R"({"at": [1, 0], "folow": 1})");
    expectRefused(j, "pins[2].folow", "unknown key");
    Json none = followScene(kTurning);
    none["colliders"] = Json::array();
    expectRefused(none, "pins[0].follow", "the scene has 0 colliders");
}

struct MotionCase {
    const char* name;
    Json motion;
};

class PinFollowMotion : public testing::TestWithParam<std::tuple<MotionCase, const char*>> {};

// Law: after every step a follow pin is at the collider's pose at the step's end applied to its
// grid position (and moves with the capsule's own points), with the collider's velocity there;
// the still pin stays put. Every integrator, double to rounding, float to float rounding.
TEST_P(PinFollowMotion, FollowPinMovesExactlyWithTheColliderPose) {
    const auto& [mc, method] = GetParam();
    const Scene s = parseFollowScene(followScene(mc.motion, method));
    const Grid g = s.grid();
    const Motion m = s.colliders[1].motion->motion();
    const Capsule cap = *s.colliders[1].as<Capsule>();
    for (Precision p : {Precision::Double, Precision::Float}) {
        const double tol = p == Precision::Double ? 1e-13 : 3e-6;
        auto solver = makeCpuSolver(s, {p, 1});
        double worst = 0, worstV = 0, worstCapsule = 0;
        for (int n = 0; n <= 200; ++n) {
            if (n > 0) {
                ASSERT_FALSE(solver->step(1).unstable);
            }
            const double t = solver->time();
            const SimState st = solver->read();
            for (int i : {0, 6}) {
                const glm::dvec3 x0 = g.restPosition(i, 0), x = st.positions[size_t(i)];
                const glm::dvec3 want = expectedPosition(mc.motion, t, x0);
                worst = std::max(worst, glm::length(x - want));
                worstV = std::max(
                    worstV, glm::length(st.velocities[size_t(i)] - velocityAt(m, t).at(want)));
                // A capsule point at the pin's rest offset from a moves with it rigidly.
                const Pose q = poseAt(m, t);
                const glm::dvec3 a = q.apply(cap.a);
                worstCapsule =
                    std::max(worstCapsule, std::abs(glm::length(x - a) - glm::length(x0 - cap.a)));
            }
            EXPECT_LT(glm::length(st.positions[3] - g.restPosition(3, 0)), tol);
            EXPECT_EQ(st.velocities[3], glm::dvec3(0));
        }
        std::printf("%-12s %-16s %-6s |x - pose| %.3g m, |v - v_c| %.3g m/s, rigid %.3g m\n",
                    mc.name, method, precisionName(p), worst, worstV, worstCapsule);
        EXPECT_LT(worst, tol);
        EXPECT_LT(worstV, tol * 10);
        EXPECT_LT(worstCapsule, tol);
    }
}

INSTANTIATE_TEST_SUITE_P(Motions, PinFollowMotion,
                         testing::Combine(testing::Values(MotionCase{"turning", kTurning},
                                                          MotionCase{"walking", kWalking},
                                                          MotionCase{"swinging", kSwinging}),
                                          testing::Values("explicit_euler", "symplectic_euler",
                                                          "verlet", "rk4", "implicit_euler")),
                         [](const auto& param) {
                             return std::string(std::get<0>(param.param).name) + "_" +
                                    std::get<1>(param.param);
                         });

// Law: the CPU in double gives the reference's numbers (tests/reference, written from
// docs/colliders.md alone) for a cloth carried by follow pins into a capsule with friction.
TEST(PinFollow, CpuDoubleMatchesTheReference) {
    for (const char* method :
         {"explicit_euler", "symplectic_euler", "verlet", "rk4", "implicit_euler"}) {
        for (const Json& motion : {kTurning, kWalking, kSwinging}) {
            Json j = followScene(motion, method);
            j["integrator"]["tolerance"] = 1e-12;  // both CGs to rounding (implicit_euler)
            j["integrator"]["max_iterations"] = 1000;
            const Scene s = parseFollowScene(j);
            ref::Simulation reference(toReference(s));
            auto cpu = makeCpuSolver(s, {Precision::Double, 1});
            double dev = maxDeviationOverExtent(cpu->read(), reference, s.grid().extent());
            for (long n = 0; n < s.defaultSteps(); ++n) {
                reference.step();
                ASSERT_FALSE(cpu->step(1).unstable) << method << " " << motion.dump() << " " << n;
                dev = std::max(dev,
                               maxDeviationOverExtent(cpu->read(), reference, s.grid().extent()));
            }
            std::printf("%-16s %-12s max |p - p_ref| / extent %.3g\n", method,
                        std::string(motion["type"]).c_str(), dev);
            EXPECT_LT(dev, 1e-10) << method << " " << motion.dump();
        }
    }
}

// The viewer's setPinned: a released follow pin falls free; pinned again it stays where it is;
// re-pinning a following vertex (as a backend switch does) keeps it following.
TEST(PinFollow, SetPinnedReleasesAndRepins) {
    const Scene s = parseFollowScene(followScene(kWalking));
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    ASSERT_FALSE(solver->step(50).unstable);
    solver->setPinned(0, 0, true);  // already following: keeps following
    solver->setPinned(6, 0, false);
    ASSERT_FALSE(solver->step(50).unstable);
    SimState st = solver->read();
    const glm::dvec3 x0 = s.grid().restPosition(0, 0);
    EXPECT_LT(glm::length(st.positions[0] - expectedPosition(kWalking, solver->time(), x0)), 1e-13);
    EXPECT_LT(st.positions[6].y, s.grid().restPosition(6, 0).y - 1e-3);  // released: falls
    solver->setPinned(6, 0, true);
    const glm::dvec3 held = solver->read().positions[6];
    ASSERT_FALSE(solver->step(20).unstable);
    EXPECT_EQ(solver->read().positions[6], held);
    EXPECT_EQ(solver->read().velocities[6], glm::dvec3(0));
    // The scene's pins with one follow released no longer match: setParameters refuses.
    EXPECT_THROW(solver->setParameters(s), std::invalid_argument);
}

// setParameters takes a changed motion for the same follow pins (the viewer's edits).
TEST(PinFollow, SetParametersTakesANewMotion) {
    const Scene s = parseFollowScene(followScene(kWalking));
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    Json faster = followScene(Json::parse(R"({"type": "linear", "velocity": [0.6, 0, -0.4]})"));
    solver->setParameters(parseFollowScene(faster));
    ASSERT_FALSE(solver->step(100).unstable);
    const glm::dvec3 x0 = s.grid().restPosition(0, 0);
    EXPECT_LT(glm::length(solver->read().positions[0] - (x0 + 0.1 * glm::dvec3(0.6, 0, -0.4))),
              1e-13);
    Json moved = followScene(kWalking);
    moved["pins"][2] = Json::parse("[-1, 0]");  // no longer following
    EXPECT_THROW(solver->setParameters(parseFollowScene(moved)), std::invalid_argument);
}

}  // namespace
}  // namespace cloth

namespace cloth {
namespace {

// Switching colliders off renumbers the follows; a pin whose collider is gone holds still. A
// scene edited in code with a follow out of range holds that pin still instead of reading past
// the colliders.
TEST(PinFollow, KeepCollidersRenumbersTheFollows) {
    const Scene s = parseFollowScene(followScene(kWalking));
    const Scene planeOff = keepColliders(s, {false, true});
    ASSERT_EQ(planeOff.colliders.size(), 1u);
    EXPECT_EQ(planeOff.pins[0].follow, 0);
    EXPECT_EQ(planeOff.pins[1].follow, -1);
    EXPECT_EQ(planeOff.pins[2].follow, 0);
    EXPECT_EQ(followPins(planeOff).size(), 2u);
    const Scene capsuleOff = keepColliders(s, {true, false});
    EXPECT_EQ(capsuleOff.pins[0].follow, -1);
    EXPECT_TRUE(followPins(capsuleOff).empty());
    EXPECT_EQ(keepColliders(s, {}).pins[2].follow, 1);
    Scene broken = s;
    broken.colliders.pop_back();
    EXPECT_TRUE(followPins(broken).empty());
    auto solver = makeCpuSolver(broken, {Precision::Double, 1});
    ASSERT_FALSE(solver->step(10).unstable);
    EXPECT_EQ(solver->read().positions[0], s.grid().restPosition(0, 0));
}

}  // namespace
}  // namespace cloth
