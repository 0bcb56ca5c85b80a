// The interactive controls of the Solver interface on the CPU (the viewer's pins, grab,
// parameter changes and backend switch), each checked against the law it implements.
#include <gtest/gtest.h>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth {
namespace {

// The seed's per-vertex hanging cloth (explicit Euler, one mass m per vertex), whose step the
// laws below write out.
Scene hanging() {
    return loadScene(CLOTH_SOURCE_DIR "/bench/hanging_per_vertex.json");
}

TEST(Controls, WriteCarriesTheStateSoTheRunContinuesIdentically) {
    const Scene s = hanging();
    auto a = makeCpuSolver(s, {Precision::Double, 1});
    a->step(300);
    auto b = makeCpuSolver(s, {Precision::Double, 2});
    b->write(a->read());
    a->step(200);
    b->step(200);
    EXPECT_EQ(a->read().positions, b->read().positions);  // the same arithmetic, bit for bit
    EXPECT_EQ(a->read().velocities, b->read().velocities);
}

TEST(Controls, PinnedVertexStaysExactlyWhereItWasPinnedAndFallsWhenReleased) {
    const Scene s = hanging();
    auto solver = makeCpuSolver(s, {Precision::Float, 1});
    solver->step(200);
    const auto k = s.grid().index(12, 12);
    const glm::dvec3 at = solver->read().positions[k];
    solver->setPinned(12, 12, true);
    solver->step(500);
    EXPECT_EQ(solver->read().positions[k], at);
    EXPECT_EQ(solver->read().velocities[k], glm::dvec3(0));
    solver->setPinned(12, 12, false);
    solver->step(500);
    EXPECT_LT(solver->read().positions[k].y, at.y);  // gravity takes it again
}

TEST(Controls, GrabSpringPullsTheVertexWithForceKTimesDistance) {
    Scene s = hanging();
    s.gravity = glm::dvec3(0);
    s.pins.clear();
    s.damping = 0;
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const auto k = s.grid().index(5, 7);
    const glm::dvec3 x0 = solver->read().positions[k], target = x0 + glm::dvec3(0, 1, 0);
    solver->setGrab(Grab{k, target, 2.0});
    solver->step(2);
    // Explicit Euler from rest: v1 = Δt·F/m, x2 = x0 + Δt·v1, F = K (target − x0) at step one
    // (the springs are at rest length and feel nothing).
    const double dt = s.integrator.dt, m = s.cloth.mass;
    EXPECT_NEAR(solver->read().positions[k].y - x0.y, dt * dt * 2.0 / m, 1e-15);
    solver->setGrab(std::nullopt);
    auto free = makeCpuSolver(s, {Precision::Double, 1});
    free->write(solver->read());
    solver->step(10);
    free->step(10);
    EXPECT_EQ(solver->read().positions, free->read().positions);  // released: no force left
}

TEST(Controls, SetParametersMatchesASolverBuiltWithThem) {
    const Scene s = hanging();
    Scene t = s;
    t.springs.structural *= 1.5;
    t.damping *= 2;
    t.gravity = {0.5, -9, 0};
    t.cloth.mass *= 1.1;
    auto live = makeCpuSolver(s, {Precision::Double, 1});
    live->setParameters(t);
    auto fresh = makeCpuSolver(t, {Precision::Double, 1});
    live->step(300);
    fresh->step(300);
    EXPECT_EQ(live->read().positions, fresh->read().positions);
}

TEST(Controls, SetParametersRefusesAnotherGridOrOtherFeatures) {
    const Scene s = hanging();
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    Scene noBend = s;
    noBend.springs.bend = 0;
    EXPECT_THROW(solver->setParameters(noBend), std::invalid_argument);
    Scene bigger = s;
    bigger.cloth.nu += 1;
    EXPECT_THROW(solver->setParameters(bigger), std::invalid_argument);
    Scene wind = s;
    wind.wind = Wind{{1, 0, 0}, 1};
    EXPECT_THROW(solver->setParameters(wind), std::invalid_argument);
}

// An unstable step stops the run; writing a finite state starts it afresh, as on the GPU, so a
// later step is judged on the new state, not on the old report.
TEST(Controls, WritingAStateClearsAnEarlierInstability) {
    Scene s = loadScene(std::string(CLOTH_SOURCE_DIR) + "/scenes/spring.json");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const SimState start = solver->read();
    s.integrator.dt = 0.3;  // past every explicit bound of the spring: blows up
    solver->setParameters(s);
    StepResult r;
    for (int i = 0; i < 100 && !r.unstable; ++i) r = solver->step(10);
    ASSERT_TRUE(r.unstable);
    s.integrator.dt = 1e-3;
    solver->setParameters(s);
    solver->write(start);
    r = solver->step(100);
    EXPECT_FALSE(r.unstable) << r.reason;
    EXPECT_EQ(r.stepsTaken, 100);
}

}  // namespace
}  // namespace cloth
