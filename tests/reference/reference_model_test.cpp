// Checks of the reference model itself (tests/reference), against values worked out by hand from
// DESIGN.md §2, so that the oracle the backends are compared with is itself trusted.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/reference.h"

namespace cloth {
namespace {

// A vertical 1×2 spring along −y: vertex (0, 0) on top, pinned; (0, 1) hangs below it.
ref::Params verticalSpring(double k, double mu, double m, double dt) {
    ref::Params p;
    p.nu = 1;
    p.nv = 2;
    p.sizeV = 1;
    p.vAxis = {0, -1, 0};
    p.kStructural = k;
    p.damping = mu;
    p.mass = m;
    p.dt = dt;
    p.pins = {{0, 0}};
    return p;
}

// Explicit Euler (seed eq. (6)) from rest, by hand: step 1 only gravity acts, so v1 = Δt g and
// p1 = p0 (old velocity 0); step 2: p2 = p0 + Δt² g, v2 = 2 Δt g (p1 unstretched, μ v1 damping);
// step 3: the spring is stretched by Δt²|g| and pulls back.
TEST(ReferenceModel, FirstStepsOfASpringMatchExplicitEulerByHand) {
    const double k = 50, mu = 0.3, m = 2, dt = 1e-2, g = 9.81;
    ref::Simulation sim(verticalSpring(k, mu, m, dt));
    sim.step();
    double v1 = -dt * g;
    EXPECT_DOUBLE_EQ(sim.positions()[1][1], -1.0);
    EXPECT_DOUBLE_EQ(sim.velocities()[1][1], v1);
    sim.step();
    double p2 = -1.0 + dt * v1;
    double v2 = v1 + dt * (-mu * v1 / m - g);
    EXPECT_DOUBLE_EQ(sim.positions()[1][1], p2);
    EXPECT_DOUBLE_EQ(sim.velocities()[1][1], v2);
    sim.step();
    const double spring = k * (-p2 - 1.0);  // stretched below rest: pulls up (+y)
    const double v3 = v2 + dt * ((spring - mu * v2) / m - g);
    EXPECT_DOUBLE_EQ(sim.positions()[1][1], p2 + dt * v2);
    EXPECT_DOUBLE_EQ(sim.velocities()[1][1], v3);
    EXPECT_EQ(sim.steps(), 3);
}

// Pinned vertices are reset to their rest position with zero velocity every step (§2).
TEST(ReferenceModel, PinnedVertexStaysExactlyAtRest) {
    ref::Simulation sim(verticalSpring(100, 0.1, 1, 1e-3));
    const ref::V3 top = sim.positions()[0];
    for (int s = 0; s < 500; ++s) sim.step();
    EXPECT_EQ(sim.positions()[0], top);
    EXPECT_EQ(sim.velocities()[0], (ref::V3{0, 0, 0}));
    EXPECT_NE(sim.positions()[1][1], -1.0);
}

// Without damping the energy of a spring oscillation is conserved up to the O(Δt) drift of
// explicit Euler; with ω Δt = 1e-3 over a tenth of a period the drift is far below 1e-3.
TEST(ReferenceModel, UndampedSpringConservesEnergyForSmallSteps) {
    ref::Params p = verticalSpring(100, 0, 1, 1e-5);
    ref::Simulation sim(p);
    const double e0 = sim.kineticEnergy() + sim.springEnergy() + sim.gravityEnergy();
    for (int s = 0; s < 6000; ++s) sim.step();
    const double e1 = sim.kineticEnergy() + sim.springEnergy() + sim.gravityEnergy();
    EXPECT_GT(sim.kineticEnergy(), 0.1);
    EXPECT_NEAR(e1, e0, 1e-3 * sim.kineticEnergy());
    EXPECT_TRUE(sim.finiteAndBelowMaxSpeed());
}

// Each spring counts once: a 2×2 cloth stretched uniformly by a factor s along û stores
// ½K((s−1)du)² in each of its two û springs and shear energy in its two diagonals.
TEST(ReferenceModel, SpringEnergyCountsEachSpringOnce) {
    ref::Params p;
    p.nu = 2;
    p.nv = 2;
    p.kStructural = 10;
    p.kShear = 4;
    ref::Simulation sim(p);
    std::vector<ref::V3> x = sim.positions();
    for (ref::V3& q : x) q[0] *= 2;  // û spacing 1 → 2
    const double diag = std::sqrt(5.0) - std::sqrt(2.0);
    EXPECT_DOUBLE_EQ(sim.springEnergy(x), 2 * 0.5 * 10 * 1.0 + 2 * 0.5 * 4 * diag * diag);
}

// Wind on a flat 2×2 cloth in the xz plane: n = (û × v̂) = (1,0,0)×(0,0,1) = (0,−1,0), so wind
// along −y of strength K_w pushes each vertex by K_w along −y (seed §5.3).
TEST(ReferenceModel, WindPushesAlongTheVertexNormal) {
    ref::Params p;
    p.nu = 2;
    p.nv = 2;
    p.gravity = {0, 0, 0};
    p.wind = true;
    p.windDirection = {0, -3, 0};  // normalised by the reference
    p.windStrength = 2;
    p.mass = 4;
    p.dt = 0.1;
    ref::Simulation sim(p);
    sim.step();
    for (const ref::V3& v : sim.velocities()) {
        EXPECT_DOUBLE_EQ(v[1], -0.1 * 2 / 4);
        EXPECT_EQ(v[0], 0);
        EXPECT_EQ(v[2], 0);
    }
}

// A 1-D chain has a = 0 on the sides of one vertex, so |a × b| = 0 and it feels no wind.
TEST(ReferenceModel, ChainFeelsNoWind) {
    ref::Params p = verticalSpring(0, 0, 1, 0.1);
    p.pins.clear();
    p.gravity = {0, 0, 0};
    p.wind = true;
    p.windStrength = 5;
    ref::Simulation sim(p);
    sim.step();
    for (const ref::V3& v : sim.velocities()) EXPECT_EQ(v, (ref::V3{0, 0, 0}));
}

// Plane (Q12): a vertex that falls below is projected back and loses its normal velocity.
// Sphere (Q13): a vertex at the centre goes to the top, c + R (0, 1, 0).
TEST(ReferenceModel, CollidersProjectAndCancelNormalVelocity) {
    ref::Params p = verticalSpring(0, 0, 1, 0.5);
    p.pins.clear();
    p.gravity = {1, -4, 0};
    ref::Collider plane;
    plane.plane = {{0, -1.5, 0}, {0, 2, 0}};
    p.colliders = {plane};
    ref::Simulation sim(p);
    sim.step();  // v = (0.5, -2, 0), positions unchanged
    sim.step();  // vertex 1: y = -1 - 1 = -2 < -1.5
    EXPECT_DOUBLE_EQ(sim.positions()[1][1], -1.5);
    EXPECT_DOUBLE_EQ(sim.positions()[1][0], 0.25);
    EXPECT_DOUBLE_EQ(sim.velocities()[1][0], 1.0);
    EXPECT_EQ(sim.velocities()[1][1], 0.0);
    EXPECT_DOUBLE_EQ(sim.positions()[0][1], -1.0);  // above the plane: untouched

    ref::Params q = verticalSpring(0, 0, 1, 0.1);
    q.pins.clear();
    q.gravity = {0, 0, 0};
    ref::Collider sphere;
    sphere.isSphere = true;
    sphere.sphere = {{0, 0, 0}, 0.5};
    q.colliders = {sphere};
    ref::Simulation s2(q);
    s2.step();
    EXPECT_EQ(s2.positions()[0], (ref::V3{0, 0.5, 0}));
    EXPECT_EQ(s2.positions()[1], (ref::V3{0, -1, 0}));
}

// Negative pin indices count from the end (DESIGN.md §4): [-1, -1] is the last vertex.
TEST(ReferenceModel, NegativePinIndicesCountFromTheEnd) {
    ref::Params p;
    p.nu = 3;
    p.nv = 4;
    p.kStructural = 10;
    p.pins = {{-1, -1}};
    ref::Simulation sim(p);
    const ref::V3 last = sim.positions().back();
    for (int s = 0; s < 10; ++s) sim.step();
    EXPECT_EQ(sim.positions().back(), last);
    EXPECT_NE(sim.positions()[0], (ref::V3{0, 0, 0}));
}

}  // namespace
}  // namespace cloth
