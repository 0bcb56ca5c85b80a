// Follow pins on the GPU (docs/colliders.md §5, §9): a follow pin is where the collider's motion
// puts its grid position, with the collider's velocity, under every integrator and both
// dispatches; the GPU matches the double reference and the CPU float backend; setPinned releases
// and re-pins as on the CPU; the shipped cape and windsock run on the GPU with their outcomes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "cpu/cpu_backend.h"
#include "gpu_test_support.h"
#include "model/collider_motion.h"
#include "model/pin_follow.h"
#include "scene/scene_json.h"
#include "support/follow_scene.h"

namespace cloth {
namespace {

using Json = nlohmann::json;

// pin_follow_test.cpp's scene (support/follow_scene.h), its implicit Euler solved to 1e-6 and
// its explicit Euler at Δt = 0.5 ms.
Json followScene(const Json& motion, const char* method) {
    Json j = test::followScene(motion, method);
    j["integrator"]["tolerance"] = 1e-6;
    j["integrator"]["max_iterations"] = 200;
    if (std::string(method) == "explicit_euler")  // inside its bound Δt < μ/λ_max (DESIGN.md §2)
        j["integrator"]["dt"] = 0.0005;
    return j;
}

using test::kSwinging;
using test::kTurning;
using test::kWalking;
using test::parseFollowScene;

// The largest |x − pose(x₀)| and |v − v_c| over the scene's follow pins at the solver's time.
std::pair<double, double> followPinError(const Scene& s, const Solver& solver) {
    const SimState st = solver.read();
    double dx = 0, dv = 0;
    for (const FollowPin& f : followPins(s)) {
        const PinState want = followPinAt(f, solver.time());
        dx = std::max(dx, glm::length(st.positions[size_t(f.vertex)] - want.position));
        dv = std::max(dv, glm::length(st.velocities[size_t(f.vertex)] - want.velocity));
    }
    return {dx, dv};
}

using Case = std::tuple<const char*, const char*, StepDispatch>;
class GpuPinFollow : public test::GpuTest, public testing::WithParamInterface<Case> {};

Json motionNamed(const std::string& name) {
    return name == "turning" ? kTurning : name == "walking" ? kWalking : kSwinging;
}

// Law: after every step a follow pin is at the collider's pose (float rounding of R x₀ + T), the
// still pin stays put, and the run keeps to the double reference as closely as the CPU float
// backend does (the pins add no error of their own).
TEST_P(GpuPinFollow, PinsFollowAndTheRunMatchesTheReferenceAndTheCpu) {
    const auto& [motion, method, dispatch] = GetParam();
    const Scene s = parseFollowScene(followScene(motionNamed(motion), method));
    GpuOptions o;
    o.dispatch = dispatch;
    auto gpu = makeGpuSolver(s, o);
    auto cpu = makeCpuSolver(s, {Precision::Float, 1});
    ref::Simulation reference(toReference(s));
    const double extent = s.grid().extent();
    double pinX = 0, pinV = 0, devRef = 0, devCpuRef = 0, devCpu = 0;
    const glm::dvec3 still = s.grid().restPosition(3, 0);
    for (long n = 0; n < s.defaultSteps(); n += 10) {
        ASSERT_FALSE(gpu->step(10).unstable);
        ASSERT_FALSE(cpu->step(10).unstable);
        for (int k = 0; k < 10; ++k) reference.step();
        const auto [dx, dv] = followPinError(s, *gpu);
        pinX = std::max(pinX, dx);
        pinV = std::max(pinV, dv);
        const SimState g = gpu->read();
        EXPECT_LT(glm::length(g.positions[3] - still), 1e-7);
        devRef = std::max(devRef, maxDeviationOverExtent(g, reference, extent));
        devCpuRef = std::max(devCpuRef, maxDeviationOverExtent(cpu->read(), reference, extent));
        devCpu = std::max(devCpu, test::maxDifferenceOverExtent(g, cpu->read(), extent));
    }
    std::printf(
        "%-8s %-16s %-10s pins |x - pose| %.2g m |v - v_c| %.2g m/s; /extent: gpu-ref %.2g, "
        "cpu float-ref %.2g, gpu-cpu float %.2g\n",
        motion, method, stepDispatchName(dispatch), pinX, pinV, devRef, devCpuRef, devCpu);
    EXPECT_LT(pinX, 3e-6);
    EXPECT_LT(pinV, 3e-5);
    EXPECT_LT(devRef, 1.5 * devCpuRef + 1e-5);
    EXPECT_LT(devCpu, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(
    Motions, GpuPinFollow,
    testing::Values(Case{"turning", "explicit_euler", StepDispatch::PerStep},
                    Case{"turning", "explicit_euler", StepDispatch::ManySteps},
                    Case{"walking", "symplectic_euler", StepDispatch::PerStep},
                    Case{"swinging", "symplectic_euler", StepDispatch::ManySteps},
                    Case{"turning", "verlet", StepDispatch::PerStep},
                    Case{"swinging", "verlet", StepDispatch::PerStep},
                    Case{"turning", "rk4", StepDispatch::PerStep},
                    Case{"walking", "rk4", StepDispatch::PerStep},
                    Case{"swinging", "implicit_euler", StepDispatch::PerStep},
                    Case{"turning", "implicit_euler", StepDispatch::PerStep}),
    [](const auto& param) {
        return std::string(std::get<0>(param.param)) + "_" + std::get<1>(param.param) + "_" +
               (std::get<2>(param.param) == StepDispatch::ManySteps ? "many" : "per");
    });

// The viewer's setPinned, as on the CPU: re-pinning a following vertex keeps it following; a
// released one falls free; pinned again it stays where it is, at rest; setParameters then
// refuses the scene's pins.
using GpuPinFollowControls = test::GpuTest;

TEST_F(GpuPinFollowControls, SetPinnedReleasesAndRepinsAndSetParametersTakesAMotion) {
    const Scene s = parseFollowScene(followScene(kWalking, "symplectic_euler"));
    auto solver = makeGpuSolver(s, {});
    solver->step(50);
    solver->setPinned(0, 0, true);
    solver->setPinned(6, 0, false);
    solver->step(50);
    const SimState st = solver->read();
    const glm::dvec3 x0 = s.grid().restPosition(0, 0);
    const glm::dvec3 want = x0 + solver->time() * glm::dvec3(0.3, 0, -0.2);
    EXPECT_LT(glm::length(st.positions[0] - want), 1e-6);
    EXPECT_LT(st.positions[6].y, s.grid().restPosition(6, 0).y - 1e-3);
    solver->setPinned(6, 0, true);
    const glm::dvec3 held = solver->read().positions[6];
    solver->step(20);
    EXPECT_EQ(solver->read().positions[6], held);
    EXPECT_EQ(solver->read().velocities[6], glm::dvec3(0));
    EXPECT_THROW(solver->setParameters(s), std::invalid_argument);
    // A new motion for the same follow pins is a parameter.
    auto fresh = makeGpuSolver(s, {});
    Json faster = followScene(Json::parse(R"({"type": "linear", "velocity": [0.6, 0, -0.4]})"),
                              "symplectic_euler");
    fresh->setParameters(parseFollowScene(faster));
    fresh->step(100);
    EXPECT_LT(glm::length(fresh->read().positions[0] - (x0 + 0.1 * glm::dvec3(0.6, 0, -0.4))),
              1e-6);
}

}  // namespace
}  // namespace cloth

namespace cloth {
namespace {

using GpuSolverTime = test::GpuTest;

// docs/colliders.md §3: a Δt change keeps the time (the poses go on from where they are), and a
// CPU → GPU switch (read, a new solver, write) keeps the time and so the follow pin's pose.
TEST_F(GpuSolverTime, DtChangeAndCpuToGpuSwitchKeepThePose) {
    const Scene s = parseFollowScene(followScene(kTurning, "symplectic_euler"));
    auto cpu = makeCpuSolver(s, {Precision::Float, 1});
    cpu->step(150);
    auto gpu = makeGpuSolver(s, {});
    gpu->write(cpu->read());
    EXPECT_DOUBLE_EQ(gpu->time(), 0.15);
    gpu->step(1);
    EXPECT_LT(followPinError(s, *gpu).first, 1e-6);
    Json halved = followScene(kTurning, "symplectic_euler");
    halved["integrator"]["dt"] = 0.0005;
    gpu->setParameters(parseFollowScene(halved));
    EXPECT_DOUBLE_EQ(gpu->time(), 0.151);
    gpu->step(3);
    EXPECT_NEAR(gpu->time(), 0.1525, 1e-15);
    EXPECT_LT(followPinError(s, *gpu).first, 1e-6);  // the pose of t = 0.1525 s
}

}  // namespace
}  // namespace cloth
