// Solver::setColliderDrag on the GPU (docs/colliders.md §3, §9), tests/cpu/collider_drag_test.cpp
// mirrored: a dragged still box (compiled again as moving, the state kept) carries the cloth
// resting on it, offsets persist and outlive setParameters, a dragged plain sphere takes the
// general response, an index out of range is refused, and the GPU agrees with the CPU float.
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>

#include "cpu/cpu_backend.h"
#include "gpu_test_support.h"
#include "support/contact_scenes.h"

namespace cloth {
namespace {

using GpuColliderDrag = test::GpuTest;

// support/contact_scenes.h's cloth resting on a still box, as collider_drag_test.cpp runs it.
Scene clothOnBox() {
    return parseScene(test::clothOnBox().dump(), "drag (test)");
}

using test::meanOf;

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
        const double minY = test::lowestY(st.positions);
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
    const Scene s = parseScene(test::kPatchAbovePlainSphere, "plain sphere (test)");
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
