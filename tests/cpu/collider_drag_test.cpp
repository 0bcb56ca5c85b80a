// Solver::setColliderDrag on the CPU (docs/colliders.md §3, the viewer's drag): a dragged box
// carries the cloth resting on it like a moving one, offsets persist, a dragged plain sphere
// takes the general response, drags outlive setParameters, and an index out of range is refused.
// Also maxColliderStepTravel (docs/colliders.md §7) for every shape.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "cpu/cpu_backend.h"
#include "model/collider_limits.h"
#include "model/collider_mesh.h"
#include "model/collider_pose.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/contact_scenes.h"

namespace cloth {
namespace {

using test::clothOnBox;
using test::meanOf;

// Steps n and checks the run stayed stable (DESIGN.md §2). clothOnBox's springs are outside
// explicit Euler's bound, but the cloth rests on the box with friction 0.8: every vertex sticks
// every step, its velocity set to the box's, and no mode can grow.
void stepStable(Solver& solver, long n) {
    const StepResult r = solver.step(n);
    EXPECT_FALSE(r.unstable) << r.reason << " at step " << r.firstBadStep;
}

// Law: static friction carries the cloth with the collider (v = v_c at a sticking contact), and
// the drag's velocity is the collider's: after 1 s at 0.3 m/s the cloth moves at 0.3 m/s.
TEST(ColliderDrag, DraggedBoxCarriesTheClothRestingOnIt) {
    const Scene s = parseScene(clothOnBox().dump(), "drag (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    stepStable(*solver, 200);  // settle
    const glm::dvec3 x0 = meanOf(solver->read().positions);
    solver->setColliderDrag(0, glm::dvec3(0), glm::dvec3(0.3, 0, 0));
    stepStable(*solver, 1000);
    const SimState st = solver->read();
    const glm::dvec3 v = meanOf(st.velocities), x1 = meanOf(st.positions);
    EXPECT_NEAR(v.x, 0.3, 0.01);
    EXPECT_NEAR(v.z, 0.0, 0.01);
    EXPECT_NEAR(x1.x - x0.x, 0.3, 0.02) << "the cloth travelled with the box";
    const double minY = test::lowestY(st.positions);
    EXPECT_GT(minY, 0.1 + 0.002 - 1e-6) << "the cloth sank into the box";
}

// Law: offsets persist. A box dragged 5 cm up and left there (velocity 0) holds the cloth 5 cm
// higher, from the next step on and for good; a later drag starts from the offset it is given.
TEST(ColliderDrag, OffsetsPersistAndVelocityZeroLeavesTheColliderWhereItIs) {
    const Scene s = parseScene(clothOnBox().dump(), "drag (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    stepStable(*solver, 100);
    solver->setColliderDrag(0, glm::dvec3(0, 0.01, 0), glm::dvec3(0));
    stepStable(*solver, 1);
    for (const glm::dvec3& p : solver->read().positions) EXPECT_GE(p.y, 0.112 - 1e-9);
    stepStable(*solver, 500);
    for (const glm::dvec3& p : solver->read().positions) EXPECT_NEAR(p.y, 0.112, 2e-3);
    // Rising at 0.05 m/s from that offset for 0.4 s: 2 cm more.
    solver->setColliderDrag(0, glm::dvec3(0, 0.01, 0), glm::dvec3(0, 0.05, 0));
    stepStable(*solver, 400);
    solver->setColliderDrag(0, glm::dvec3(0, 0.03, 0), glm::dvec3(0));
    stepStable(*solver, 300);
    for (const glm::dvec3& p : solver->read().positions) EXPECT_NEAR(p.y, 0.132, 2e-3);
}

// Drags outlive a live parameter change (the viewer's friction and thickness sliders).
TEST(ColliderDrag, DragsOutliveSetParameters) {
    Scene s = parseScene(clothOnBox().dump(), "drag (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    solver->setColliderDrag(0, glm::dvec3(0, 0.02, 0), glm::dvec3(0));
    s.colliders[0].friction = 0.5;
    solver->setParameters(s);
    stepStable(*solver, 300);
    for (const glm::dvec3& p : solver->read().positions) EXPECT_NEAR(p.y, 0.122, 2e-3);
}

// A plain sphere (DESIGN.md §2's rule, v_c = 0) that is dragged takes the general response with
// v_c: a sphere pushed up into a resting vertex chain lifts it at its own speed.
TEST(ColliderDrag, DraggedPlainSphereMovesItsContactWithIt) {
    const Scene s = parseScene(test::kPatchAbovePlainSphere, "plain sphere (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    solver->setColliderDrag(0, glm::dvec3(0), glm::dvec3(0, 0.2, 0));
    stepStable(*solver, 250);  // the shell meets the cloth after 0.05 s and pushes it for 0.2 s
    const SimState st = solver->read();
    const glm::dvec3 centre = st.positions[4];
    EXPECT_NEAR(centre.y, 0.49 + 0.05, 1e-3);
    EXPECT_NEAR(st.velocities[4].y, 0.2, 1e-6) << "v_c of the dragged sphere";
}

TEST(ColliderDrag, IndexOutOfRangeIsRefused) {
    const Scene s = parseScene(clothOnBox().dump(), "drag (test)");
    auto solver = makeCpuSolver(s, {Precision::Float, 1});
    EXPECT_THROW(solver->setColliderDrag(1, glm::dvec3(0), glm::dvec3(0)), std::invalid_argument);
    EXPECT_THROW(solver->setColliderDrag(-1, glm::dvec3(0), glm::dvec3(0)), std::invalid_argument);
}

// The drag's pose: the motion's, then the translation offset + velocity·(t − since).
TEST(ColliderDrag, PoseIsTheMotionThenTheDragTranslation) {
    Collider c = Sphere{glm::dvec3(1, 0, 0), 0.1};
    ColliderMotion m;
    m.type = MotionType::Rotation;
    m.axis = {0, 1, 0};
    m.degreesPerSecond = 90;
    c.motion = m;
    const ColliderDrag d{glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 2), 0.5};
    const ShapeD shape = posedShape(c, 1.0, &d);
    const auto* s = std::get_if<SphereT<double>>(&shape);
    ASSERT_NE(s, nullptr);
    // 90° about +y takes (1, 0, 0) to (0, 0, −1); then + (0, 1, 0) + (0, 0, 2)·0.5.
    EXPECT_NEAR(glm::length(s->center - glm::dvec3(0, 1, 0)), 0, 1e-12);
    EXPECT_NEAR(colliderVelocity(c, 1.0, &d).at(glm::dvec3(0, 0, -1)).z, 2, 1e-12);
}

TEST(ColliderLimits, MaxStepTravelIsTheHalfThicknessPlusH) {
    Collider plane = Plane{};
    EXPECT_EQ(maxColliderStepTravel(plane), std::numeric_limits<double>::infinity());
    Collider sphere = Sphere{glm::dvec3(0), 0.3};
    sphere.thickness = 0.01;
    EXPECT_DOUBLE_EQ(maxColliderStepTravel(sphere), 0.31);
    Box b;
    b.halfExtents = {0.5, 0.01, 0.3};
    Collider box = b;
    box.thickness = 0.002;
    EXPECT_DOUBLE_EQ(maxColliderStepTravel(box), 0.012);  // the slab bound a + h of §7
    Collider capsule = Capsule{glm::dvec3(0), glm::dvec3(0, 1, 0), 0.05};
    EXPECT_DOUBLE_EQ(maxColliderStepTravel(capsule), 0.05);
    MeshCollider m;  // half the OBJ's smallest extent: 0.05 of a 0.4 × 0.1 × 0.6 block
    m.baked = std::make_shared<BakedMesh>(
        BakedMesh{boxMesh({glm::dvec3(1), glm::dvec3(0.2, 0.05, 0.3), glm::dmat3(1)}), SdfGrid{}});
    Collider mesh = m;
    mesh.thickness = 0.01;
    EXPECT_NEAR(maxColliderStepTravel(mesh), 0.06, 1e-12);
}

}  // namespace
}  // namespace cloth
