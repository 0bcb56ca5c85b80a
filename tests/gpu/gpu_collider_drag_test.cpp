// Solver::setColliderDrag on the GPU (docs/colliders.md §3, §9), tests/core/collider_drag_test.cpp
// mirrored: a dragged still box (compiled again as moving, the state kept) carries the cloth
// resting on it, offsets persist and outlive setParameters, a dragged plain sphere takes the
// general response, an index out of range is refused, and the GPU agrees with the CPU float.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "gpu_test_support.h"

namespace cloth {
namespace {

using Json = nlohmann::json;
using GpuColliderDrag = test::GpuTest;

// collider_drag_test.cpp's 6×6 cloth of 20 cm resting (h = 2 mm above) on a still box whose top
// is at y = 0.1.
Scene clothOnBox() {
    return parseScene(R"({
      "cloth": { "resolution": [6, 6], "size": [0.2, 0.2], "origin": [-0.1, 0.1021, -0.1],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.001 },
      "springs": { "structural": 20.0, "shear": 5.0 },
      "damping": 0.002,
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "colliders": [ { "type": "box", "center": [0, 0, 0], "half_extents": [0.5, 0.1, 0.5],
                       "thickness": 0.002, "friction": 0.8 } ]
    })",
                      "drag (test)");
}

glm::dvec3 meanOf(const std::vector<glm::dvec3>& v) {
    glm::dvec3 m(0);
    for (const glm::dvec3& w : v) m += w;
    return m / double(v.size());
}

// Law: static friction carries the cloth with the dragged box at the drag's velocity; the GPU
// and the CPU float backend take the same steps (both dispatches).
TEST_F(GpuColliderDrag, DraggedBoxCarriesTheClothRestingOnItAsOnTheCpu) {
    const Scene s = clothOnBox();
    for (StepDispatch d : {StepDispatch::PerStep, StepDispatch::ManySteps}) {
        GpuOptions o;
        o.dispatch = d;
        auto gpu = makeGpuSolver(s, o);
        auto cpu = makeCpuSolver(s, {Precision::Float, 1});
        gpu->step(200);  // settle
        cpu->step(200);
        const glm::dvec3 x0 = meanOf(gpu->read().positions);
        gpu->setColliderDrag(0, glm::dvec3(0), glm::dvec3(0.3, 0, 0));
        cpu->setColliderDrag(0, glm::dvec3(0), glm::dvec3(0.3, 0, 0));
        for (long n : {1, 63, 70, 200, 666}) {  // runs that straddle the pose batches
            ASSERT_FALSE(gpu->step(n).unstable);
            cpu->step(n);
        }
        const SimState st = gpu->read();
        const glm::dvec3 v = meanOf(st.velocities), x1 = meanOf(st.positions);
        double minY = 1e300;
        for (const glm::dvec3& p : st.positions) minY = std::min(minY, p.y);
        const double dev = test::maxDifferenceOverExtent(st, cpu->read(), 0.2);
        std::printf(
            "gpu drag (%s): mean velocity (%.4f, %.4f, %.4f) m/s, |gpu - cpu float| / "
            "extent %.3g\n",
            stepDispatchName(d), v.x, v.y, v.z, dev);
        EXPECT_NEAR(v.x, 0.3, 0.01);
        EXPECT_NEAR(v.z, 0.0, 0.01);
        EXPECT_NEAR(x1.x - x0.x, 0.3, 0.02);
        EXPECT_GT(minY, 0.1 + 0.002 - 1e-6);
        EXPECT_LT(dev, 1e-4);
    }
}

// Law: offsets persist; velocity 0 leaves the box where it is; drags outlive setParameters.
TEST_F(GpuColliderDrag, OffsetsPersistAndOutliveSetParameters) {
    Scene s = clothOnBox();
    auto solver = makeGpuSolver(s, {});
    solver->step(100);
    solver->setColliderDrag(0, glm::dvec3(0, 0.01, 0), glm::dvec3(0));
    solver->step(1);
    for (const glm::dvec3& p : solver->read().positions) EXPECT_GE(p.y, 0.112 - 1e-6);
    solver->step(500);
    for (const glm::dvec3& p : solver->read().positions) EXPECT_NEAR(p.y, 0.112, 2e-3);
    solver->setColliderDrag(0, glm::dvec3(0, 0.01, 0), glm::dvec3(0, 0.05, 0));
    solver->step(400);
    solver->setColliderDrag(0, glm::dvec3(0, 0.03, 0), glm::dvec3(0));
    s.colliders[0].friction = 0.5;
    solver->setParameters(s);  // the dragged variant's defines
    solver->step(300);
    for (const glm::dvec3& p : solver->read().positions) EXPECT_NEAR(p.y, 0.132, 2e-3);
}

// A plain sphere (DESIGN.md §2's rule) that is dragged takes the general response with v_c.
TEST_F(GpuColliderDrag, DraggedPlainSphereMovesItsContactWithIt) {
    const Scene s = parseScene(R"({
      "cloth": { "resolution": [3, 3], "size": [0.02, 0.02], "origin": [-0.01, 0.5, -0.01],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.001 },
      "springs": { "structural": 10.0 }, "damping": 0.001, "gravity": [0, 0, 0],
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "colliders": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.49 } ]
    })",
                               "plain sphere (test)");
    auto solver = makeGpuSolver(s, {});
    solver->setColliderDrag(0, glm::dvec3(0), glm::dvec3(0, 0.2, 0));
    solver->step(250);
    const SimState st = solver->read();
    EXPECT_NEAR(st.positions[4].y, 0.49 + 0.05, 1e-3);
    EXPECT_NEAR(st.velocities[4].y, 0.2, 1e-5);
    EXPECT_THROW(solver->setColliderDrag(1, glm::dvec3(0), glm::dvec3(0)), std::invalid_argument);
    EXPECT_THROW(solver->setColliderDrag(-1, glm::dvec3(0), glm::dvec3(0)), std::invalid_argument);
}

}  // namespace
}  // namespace cloth
