// maxMotionSpeed (model/collider_speed.h) against the speed of the collider's surface points
// measured by central differences of poseAt: never exceeded, and reached where the bound is
// exact (linear, oscillation, a sphere or a capsule turning about an axis across its middle).
#include "model/collider_speed.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/collider_motion.h"
#include "support/draws.h"

namespace cloth {
namespace {

ColliderMotion linear(glm::dvec3 v) {
    ColliderMotion m;
    m.type = MotionType::Linear;
    m.velocity = v;
    return m;
}
ColliderMotion rotation(glm::dvec3 axis, glm::dvec3 pivot, double degreesPerSecond) {
    ColliderMotion m;
    m.type = MotionType::Rotation;
    m.axis = glm::normalize(axis);
    m.pivot = pivot;
    m.degreesPerSecond = degreesPerSecond;
    return m;
}
ColliderMotion oscillation(glm::dvec3 axis, double amplitude, double frequency, double phase) {
    ColliderMotion m;
    m.type = MotionType::Oscillation;
    m.axis = glm::normalize(axis);
    m.amplitude = amplitude;
    m.frequency = frequency;
    m.phaseDegrees = phase;
    return m;
}

// Points of the shape's surface at rest: random directions from the centre pushed onto it
// (sphere, capsule), or the box's corners and random points of its faces.
std::vector<glm::dvec3> surfacePoints(const Collider& c, std::mt19937& rng) {
    std::normal_distribution<double> n;
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<glm::dvec3> out;
    for (int k = 0; k < 4000; ++k) {
        const glm::dvec3 d = glm::normalize(test::drawVec3(n, rng));
        if (const Sphere* s = c.as<Sphere>()) out.push_back(s->center + s->radius * d);
        if (const Capsule* cap = c.as<Capsule>()) {  // a third on each cap, a third between
            const double t = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 1.0 : 0.5 + 0.5 * u(rng);
            out.push_back(cap->a + t * (cap->b - cap->a) + cap->radius * d);
        }
        if (const Box* b = c.as<Box>()) {
            glm::dvec3 q = test::drawVec3(u, rng);
            const int axis = k % 3;
            q[axis] = q[axis] < 0 ? -1 : 1;
            if (k < 8) q = glm::dvec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
            out.push_back(b->center + b->rotation.matrix() * (q * b->halfExtents));
        }
    }
    return out;
}

// The largest central-difference speed of the surface points over times spread over 2 s.
double measuredMaxSpeed(const Collider& c) {
    std::mt19937 rng(7);
    const Motion m = c.motion->motion();
    const double e = 1e-6;
    double worst = 0;
    for (const glm::dvec3& x0 : surfacePoints(c, rng))
        for (double t = 0; t < 2; t += 0.0125) {
            const glm::dvec3 d =
                (poseAt(m, t + e).apply(x0) - poseAt(m, t - e).apply(x0)) / (2 * e);
            worst = std::max(worst, glm::length(d));
        }
    return worst;
}

struct Case {
    const char* name;
    Collider collider;
    bool exact;  // the bound is reached by some surface point
};

Collider with(Collider c, const ColliderMotion& m) {
    c.motion = m;
    return c;
}

std::vector<Case> cases() {
    const Sphere sphere{{0.3, 1, -0.2}, 0.25};
    const Capsule capsule{{-0.2, 1.2, 0}, {0.4, 1.2, 0}, 0.08};
    Box box{{0.5, 0.4, 0.1}, {0.3, 0.05, 0.2}, {}};
    box.rotation = {glm::normalize(glm::dvec3(1, 2, 0)), 20};
    return {
        {"sphere_linear", with(sphere, linear({0.3, -0.4, 1.2})), true},
        {"sphere_turning", with(sphere, rotation({0, 1, 0}, {0, 0, 0}, 90)), true},
        {"sphere_tilted_turning", with(sphere, rotation({1, 1, 0}, {0, 0.5, 0}, -40)), true},
        {"sphere_swinging", with(sphere, oscillation({1, 0, 1}, 0.15, 0.8, 20)), true},
        {"capsule_turning_across", with(capsule, rotation({0, 1, 0}, {0.1, 0, 0}, 60)), true},
        {"capsule_turning_along", with(capsule, rotation({1, 0, 0}, {0, 0, 0}, 60)), false},
        {"box_turning", with(box, rotation({0, 1, 0}, {0, 0, 0}, 45)), false},
        {"box_walking", with(box, linear({0.5, 0, 0})), true},
    };
}

TEST(ColliderSpeed, BoundsTheSurfaceSpeedAndIsReachedWhereExact) {
    for (const Case& c : cases()) {
        const double bound = maxMotionSpeed(c.collider), measured = measuredMaxSpeed(c.collider);
        std::printf("%-24s maxMotionSpeed %.6f m/s, measured %.6f m/s (%.4f)\n", c.name, bound,
                    measured, measured / bound);
        EXPECT_LE(measured, bound * (1 + 1e-7)) << c.name;
        // Where the bound is not exact it is still not a gross one.
        EXPECT_GT(measured, bound * (c.exact ? 0.995 : 0.5)) << c.name;
    }
}

TEST(ColliderSpeed, StillPlanesAndTurningPlanes) {
    const Plane plane{{0, 0, 0}, {0, 1, 0}};
    EXPECT_EQ(maxMotionSpeed(Collider(plane)), 0);
    EXPECT_EQ(maxMotionSpeed(with(plane, linear({0, 0.1, 0}))), 0.1);
    EXPECT_EQ(maxMotionSpeed(with(plane, oscillation({0, 1, 0}, 0.5, 1 / M_PI, 0))), 1.0);
    EXPECT_TRUE(std::isinf(maxMotionSpeed(with(plane, rotation({1, 0, 0}, {0, 0, 0}, 10)))));
    EXPECT_EQ(maxMotionSpeed(with(plane, rotation({1, 0, 0}, {0, 0, 0}, 0))), 0);
    // Turning about its own axis through the centre: the sphere's points still move, ω R.
    const Sphere s{{0, 2, 0}, 0.5};
    EXPECT_NEAR(maxMotionSpeed(with(s, rotation({0, 1, 0}, {0, 0, 0}, 180))), M_PI * 0.5, 1e-15);
}

TEST(ColliderSpeed, BoundingSpheres) {
    const BoundingSphere c = boundingSphere(Capsule{{0, 0, 0}, {0, 2, 0}, 0.1});
    EXPECT_EQ(c.center, glm::dvec3(0, 1, 0));
    EXPECT_DOUBLE_EQ(c.radius, 1.1);
    const BoundingSphere b = boundingSphere(Box{{1, 2, 3}, {0.3, 0.4, 1.2}, {}});
    EXPECT_EQ(b.center, glm::dvec3(1, 2, 3));
    EXPECT_DOUBLE_EQ(b.radius, 1.3);
    EXPECT_TRUE(std::isinf(boundingSphere(Plane{{0, 0, 0}, {0, 1, 0}}).radius));
}

}  // namespace
}  // namespace cloth
