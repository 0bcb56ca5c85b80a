// Moving colliders (docs/colliders.md §3): the pose is rigid, equals the rest pose at t = 0 (up
// to an oscillation's phase), and its time derivative is the stated velocity field
// v_c(p) = v_lin + ω × (p − o) — checked by central differences of the pose.
#include "model/collider_motion.h"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "model/collider_contact.h"

namespace cloth {
namespace {

using D3 = glm::dvec3;

std::vector<Motion> motions() {
    Motion linear;
    linear.type = MotionType::Linear;
    linear.velocity = {0.3, -0.1, 2.0};
    Motion spin;
    spin.type = MotionType::Rotation;
    spin.axis = glm::normalize(D3(0.2, 1, -0.4));
    spin.pivot = {1, 0.5, -2};
    spin.angularSpeed = 3.0;
    Motion wave;
    wave.type = MotionType::Oscillation;
    wave.axis = glm::normalize(D3(1, 1, 0));
    wave.amplitude = 0.25;
    wave.frequency = 1.5;
    wave.phase = 0.4;
    return {Motion{}, linear, spin, wave};
}

// Law: d/dt poseAt(t)·x₀ = velocityAt(t) at the moved point, for attached points all around.
TEST(ColliderMotion, FiniteDifferenceOfThePoseIsThePointVelocity) {
    const double h = 1e-5;
    for (const Motion& m : motions()) {
        for (const double t : {0.0, 0.37, 2.9}) {
            for (const D3 x0 : {D3(0), D3(1, 2, 3), D3(-0.5, 0.1, 4)}) {
                const D3 fd = (poseAt(m, t + h).apply(x0) - poseAt(m, t - h).apply(x0)) / (2 * h);
                const D3 v = velocityAt(m, t).at(poseAt(m, t).apply(x0));
                EXPECT_NEAR(glm::length(fd - v), 0, 1e-8 * (1 + glm::length(v)))
                    << "motion " << int(m.type) << " t " << t;
            }
        }
    }
}

// Law: the pose is rigid (R orthonormal, det 1) and a rotation leaves its pivot and axis fixed.
TEST(ColliderMotion, PosesAreRigidAndARotationFixesItsAxis) {
    for (const Motion& m : motions()) {
        const Pose q = poseAt(m, 1.3);
        EXPECT_NEAR(glm::determinant(q.rotation), 1, 1e-14);
        const glm::dmat3 id = glm::transpose(q.rotation) * q.rotation;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) EXPECT_NEAR(id[i][j], i == j, 1e-14);
    }
    const Motion spin = motions()[2];
    const Pose q = poseAt(spin, 0.8);
    EXPECT_NEAR(glm::length(q.apply(spin.pivot) - spin.pivot), 0, 1e-14);
    EXPECT_NEAR(glm::length(q.apply(spin.pivot + 2.0 * spin.axis) - spin.pivot - 2.0 * spin.axis),
                0, 1e-14);
    // After t = π/6 s at 3 rad/s the turn is π/2: x ↦ a × x + a⟨a, x⟩ about the pivot.
    const D3 x(1, 0, 0);
    const D3 r = poseAt(spin, std::numbers::pi / 6).apply(spin.pivot + x) - spin.pivot;
    const D3 expected = glm::cross(spin.axis, x) + glm::dot(spin.axis, x) * spin.axis;
    EXPECT_NEAR(glm::length(r - expected), 0, 1e-14);
}

// Law: an oscillation returns after one period 1/f and stays within its amplitude.
TEST(ColliderMotion, OscillationIsPeriodicAndBounded) {
    const Motion wave = motions()[3];
    for (double t = 0; t < 2; t += 0.01) {
        const Pose a = poseAt(wave, t), b = poseAt(wave, t + 1 / wave.frequency);
        EXPECT_NEAR(glm::length(a.translation - b.translation), 0, 1e-12);
        EXPECT_LE(glm::length(a.translation), wave.amplitude * (1 + 1e-15));
    }
}

// Law: moving a shape moves its surface: φ of the moved shape at the moved point is unchanged.
TEST(ColliderMotion, MovedShapesCarryTheirDistanceField) {
    const BoxT<double> box{{0.1, 0.2, 0.3}, {0.3, 0.2, 0.1}, axisAngle(D3(0, 0, 1), 0.3)};
    const CapsuleT<double> cap{{0, 0, 0}, {1, 0, 0}, 0.2};
    const SphereT<double> sphere{{0, 1, 0}, 0.5};
    const PlaneT<double> plane{{0, 0, 0}, {0, 1, 0}};
    for (const Motion& m : motions()) {
        const Pose q = poseAt(m, 0.7);
        for (const D3 x : {D3(0.4, 0.1, -0.2), D3(-1, 2, 0.5), D3(0.05, 0.1, 0.3)}) {
            EXPECT_NEAR(contact(moved(box, q), q.apply(x)).phi, contact(box, x).phi, 1e-13);
            EXPECT_NEAR(contact(moved(cap, q), q.apply(x)).phi, contact(cap, x).phi, 1e-13);
            EXPECT_NEAR(contact(moved(sphere, q), q.apply(x)).phi, contact(sphere, x).phi, 1e-13);
            EXPECT_NEAR(contact(moved(plane, q), q.apply(x)).phi, contact(plane, x).phi, 1e-13);
        }
    }
}

// One vertex under gravity on a box that moves (explicit Euler as DESIGN.md §2, then the
// contact with the box posed at the new time and v_c of the point touched).
struct Carried {
    D3 p, v;
    double minPhi = INFINITY;  // the lowest φ after any step's contact
};
Carried ride(const Motion& m, double friction, double seconds) {
    const BoxT<double> table{{0, -0.1, 0}, {0.5, 0.1, 0.5}, glm::dmat3(1)};
    const double dt = 1e-3, h = 0.001;
    Carried c{{0, h, 0}, D3(0)};  // at rest on the box
    for (int s = 1; s <= int(seconds / dt); ++s) {
        const D3 vOld = c.v;
        c.v += dt * D3(0, -9.81, 0);
        c.p += dt * vOld;
        const double t = s * dt;
        const BoxT<double> now = moved(table, poseAt(m, t));
        collide(now, ContactParamsT<double>{h, friction}, velocityAt(m, t).at(c.p), c.p, c.v);
        c.minPhi = std::min(c.minPhi, contact(now, c.p).phi);
    }
    return c;
}

// Law: a moving collider carries the cloth instead of punching through it: on a rising box the
// vertex stays on top (φ ≥ h after every step) and rises with it; on a box that starts sliding
// sideways, friction (c_f = 1) takes the vertex up to the box's speed within ~v/(c_f g) and then
// carries it (static: exactly v_c), while without friction the box slides away under it.
TEST(ColliderMotion, AMovingColliderCarriesTheVertex) {
    Motion lift;
    lift.type = MotionType::Linear;
    lift.velocity = {0, 0.5, 0};
    const Carried up = ride(lift, 0, 1.0);
    EXPECT_GE(up.minPhi, 0.001 - 1e-12);
    EXPECT_NEAR(up.p.y, 0.5 + 0.001, 1e-3);
    EXPECT_NEAR(up.v.y, 0.5, 1e-2);

    Motion slide;
    slide.type = MotionType::Linear;
    slide.velocity = {0.3, 0, 0};
    const Carried sticky = ride(slide, 1.0, 1.0);
    EXPECT_NEAR(sticky.p.x, 0.3, 0.3 * 0.3 / 9.81);  // lags by at most v·(v/(c_f g))
    EXPECT_NEAR(sticky.v.x, 0.3, 1e-12);
    EXPECT_GE(sticky.minPhi, 0.001 - 1e-12);
    const Carried slippery = ride(slide, 0.0, 1.0);
    EXPECT_EQ(slippery.p.x, 0);
    EXPECT_EQ(slippery.v.x, 0);
}

}  // namespace
}  // namespace cloth
