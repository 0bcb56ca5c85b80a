// The solver's time (Solver::time(), docs/colliders.md §3): t = t₀ + (steps − step₀)·Δt, re-based
// when setParameters changes Δt, so a moving collider and a follow pin go on from where they are;
// read() carries the time in SimState::time and write() restores it (a backend switch).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cpu/cpu_backend.h"
#include "model/pin_follow.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth {
namespace {

// A 5 × 4 cloth whose pin (0, 0) follows a sphere swinging at 1 Hz.
Scene swingingScene(double dt) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "cloth": { "resolution": [5, 4], "size": [0.4, 0.3], "origin": [-0.2, 1.0, 0.0],
                 "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": 0.01 },
      "springs": { "structural": 50 }, "damping": 0.02,
      "pins": [ {"at": [0, 0], "follow": 0} ],
      "integrator": { "method": "symplectic_euler", "dt": 0.001 },
      "colliders": [ { "type": "sphere", "center": [-0.2, 1.2, 0], "radius": 0.1,
                       "motion": { "type": "oscillation", "axis": [1, 0, 0], "amplitude": 0.1,
                                   "frequency": 1.0 } } ]
    })");
    j["integrator"]["dt"] = dt;
    return parseScene(j.dump(), "time (test)");
}

// Law: halving Δt at t = 0.2 s keeps the time, and the follow pin one step later is at the
// pose of t = 0.2 s + the new Δt, not of (steps + 1)·Δt_new = 0.1005 s.
TEST(SolverTime, DtChangeKeepsTheTimeAndThePosesContinuous) {
    for (Precision p : {Precision::Double, Precision::Float}) {
        auto solver = makeCpuSolver(swingingScene(0.001), {p, 1});
        solver->step(200);
        EXPECT_DOUBLE_EQ(solver->time(), 0.2);
        solver->setParameters(swingingScene(0.0005));
        EXPECT_DOUBLE_EQ(solver->time(), 0.2);
        solver->step(1);
        EXPECT_DOUBLE_EQ(solver->time(), 0.2005);
        const FollowPin f = followPins(swingingScene(0.0005))[0];
        const glm::dvec3 want = followPinAt(f, 0.2005).position;
        EXPECT_LT(glm::length(solver->read().positions[0] - want), 1e-6);
    }
}

// Law: read() gives the time, write() restores it into another solver.
TEST(SolverTime, WriteCarriesTheTime) {
    const Scene s = swingingScene(0.001);
    auto a = makeCpuSolver(s, {Precision::Double, 1});
    a->step(300);
    const SimState st = a->read();
    EXPECT_DOUBLE_EQ(st.time, 0.3);
    auto b = makeCpuSolver(s, {Precision::Float, 1});
    b->write(st);
    EXPECT_DOUBLE_EQ(b->time(), 0.3);
    b->step(1);
    const glm::dvec3 want = followPinAt(followPins(s)[0], 0.301).position;
    EXPECT_LT(glm::length(b->read().positions[0] - want), 1e-6);
}

}  // namespace
}  // namespace cloth
