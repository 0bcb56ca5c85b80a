// Tunnelling at the level of one vertex (docs/colliders.md §7): a vertex that starts a step
// outside the offset surface (φ ≥ h) and moves by s·Δt relative to the collider ends on the
// near side of a slab of half thickness a iff s·Δt ≤ a + h (beyond the midplane the nearest face
// is the far one, and the projection completes the passage), and of a sphere iff s·Δt ≤ R + h
// (head-on, through the centre). Collider motion counts through the relative speed only. At
// cloth level: a cloth thrown at a thin box at increasing speeds below the limit never has a
// vertex on the far side, after any step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>

#include "cpu/cpu_backend.h"
#include "model/collider_contact.h"
#include "model/collider_motion.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

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

// ---- at cloth level ----------------------------------------------------------------------------

struct Throw {
    double lowestEver = 1e300;  // the lowest vertex after any step, above the box's midplane [m]
    double lowestAtEnd = 1e300;
    bool unstable = false;
};

// A 9×9 cloth, 0.2 m square, level 5 cm above the midplane of a thin box (half thickness
// a = 1 cm, h = 2 mm), thrown down at `speed` [m/s] and run 0.1 s (100 steps of 1 ms, the
// seed's explicit Euler; no damping, but 100 steps are far too few for its slow growth).
Throw throwAtThinBox(double speed) {
    const Scene s = parseScene(R"({
      "cloth": { "resolution": [9, 9], "size": [0.2, 0.2], "origin": [-0.1, 0.05, -0.1],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.001 },
      "springs": { "structural": 5.0 },
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "colliders": [ { "type": "box", "center": [0, 0, 0], "half_extents": [0.5, 0.01, 0.5],
                       "thickness": 0.002 } ]
    })",
                               "thin box (test)");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    SimState st = solver->read();
    for (glm::dvec3& v : st.velocities) v = {0, -speed, 0};
    solver->write(st);
    Throw out;
    for (int n = 0; n < 100; ++n) {
        out.unstable |= solver->step(1).unstable;
        out.lowestAtEnd = 1e300;
        for (const glm::dvec3& p : solver->read().positions)
            out.lowestAtEnd = std::min(out.lowestAtEnd, p.y);
        out.lowestEver = std::min(out.lowestEver, out.lowestAtEnd);
    }
    return out;
}

// Law (docs/colliders.md §7): a vertex that starts outside the offset surface is held by a slab
// of half thickness a iff its speed relative to it satisfies s·Δt ≤ a + h. Thrown at 10 % to
// 99 % of that limit (12 m/s here), no vertex of the cloth is ever on the far side of the
// midplane, none ends a step inside the offset surface, and the cloth ends resting on the near
// side; at 2.5× the limit it passes through (the test can see a tunnel).
TEST(ColliderTunnelling, ClothThrownAtAThinBoxStaysOnItBelowTheLimit) {
    const double top = kHalf + kH, limit = top / kDt;  // (a + h)/Δt [m/s]
    for (double fraction : {0.1, 0.3, 0.6, 0.9, 0.99}) {
        const Throw t = throwAtThinBox(fraction * limit);
        std::printf(
            "thrown at %.2f m/s (%.0f%% of the limit): lowest vertex %.4f m above the midplane "
            "at any step, %.4f m at the end\n",
            fraction * limit, 100 * fraction, t.lowestEver, t.lowestAtEnd);
        EXPECT_FALSE(t.unstable) << fraction * limit << " m/s";
        EXPECT_GT(t.lowestEver, top - 1e-9) << fraction * limit << " m/s: a vertex got through";
        EXPECT_NEAR(t.lowestAtEnd, top, 1e-3) << fraction * limit << " m/s: not resting on it";
    }
    const Throw fast = throwAtThinBox(2.5 * limit);
    EXPECT_FALSE(fast.unstable);
    EXPECT_LT(fast.lowestAtEnd, -kHalf) << "the test would not see a tunnel";
}

}  // namespace
}  // namespace cloth
