// Tunnelling at the level of one vertex (docs/colliders.md §7): a vertex that starts a step
// outside the offset surface (φ ≥ h) and moves by s·Δt relative to the collider ends on the
// near side of a slab of half thickness a iff s·Δt ≤ a + h (beyond the midplane the nearest face
// is the far one, and the projection completes the passage), and of a sphere iff s·Δt ≤ R + h
// (head-on, through the centre). Collider motion counts through the relative speed only.
#include <gtest/gtest.h>

#include <random>

#include "core/collider_contact.h"
#include "core/collider_motion.h"

namespace cloth {
namespace {

using D3 = glm::dvec3;

constexpr double kDt = 1e-3, kH = 0.002, kHalf = 0.01;  // step [s], thickness, slab half [m]

// One explicit-Euler position update (DESIGN.md §2, no forces: the speed is what matters) and the
// contact with a slab whose top face is y = 0 at t = 0, rising at `lift` m/s. True when the
// vertex ends below the slab's midplane: it went through.
bool tunnels(double startPhi, double fallSpeed, double lift) {
    Motion m;
    m.type = MotionType::Linear;
    m.velocity = {0, lift, 0};
    const BoxT<double> slab{{0, -kHalf, 0}, {1, kHalf, 1}, glm::dmat3(1)};
    D3 p(0.1, startPhi, -0.2), v(0, -fallSpeed, 0);
    p += kDt * v;
    const BoxT<double> now = moved(slab, poseAt(m, kDt));
    collide(now, ContactParamsT<double>{kH, 0.3}, velocityAt(m, kDt).at(p), p, v);
    return p.y < now.center.y;
}

// Law: no start outside the offset surface tunnels while s·Δt ≤ a + h (s the relative speed),
// and the limit is sharp: from φ = h, 1 % faster goes through.
TEST(Tunnelling, ASlabHoldsWhileTheRelativeStepIsBelowHalfItsThicknessPlusH) {
    const double limit = (kHalf + kH) / kDt;  // [m/s]
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(0, 1);
    for (int k = 0; k < 20000; ++k) {
        const double start = kH + 0.05 * u(rng), lift = 4 * (u(rng) - 0.5);
        const double s = limit * u(rng);  // relative speed below the limit
        EXPECT_FALSE(tunnels(start, s - lift, lift)) << "start " << start << " s " << s;
    }
    for (const double lift : {0.0, 3.0, -2.0}) {
        EXPECT_FALSE(tunnels(kH, 0.99 * limit - lift, lift)) << lift;
        EXPECT_TRUE(tunnels(kH, 1.01 * limit - lift, lift)) << lift;
    }
}

// Law: a vertex falling head-on at a sphere of radius R comes out the far side iff
// s·Δt > R + h (it ends past the centre, where the nearest surface is the far one).
TEST(Tunnelling, ASphereHoldsWhileTheRelativeStepIsBelowItsRadiusPlusH) {
    const double r = 0.05;
    const SphereT<double> ball{{0, 0, 0}, r};
    const auto through = [&](double s) {
        D3 p(0, r + kH, 0), v(0, -s, 0);
        p += kDt * v;
        collide(ball, ContactParamsT<double>{kH, 0}, D3(0), p, v);
        return p.y < 0;
    };
    const double limit = (r + kH) / kDt;
    EXPECT_FALSE(through(0.99 * limit));
    EXPECT_TRUE(through(1.01 * limit));
}

}  // namespace
}  // namespace cloth
