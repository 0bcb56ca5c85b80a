// Self-collision on the CPU backend (docs/physics.md "Self-collision"), checked by the
// independent checker of tests/reference/self_intersection.h, which shares no code with src/:
// on every checked frame of the shipped pile, fold and cape, in float and double, no edge passes
// through a triangle and no two elements that share no vertex are closer than half the
// thickness. With self-collision off the same scenes do cross, so the checks can fail.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "cpu/cpu_backend.h"
#include "model/self_contact.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/collapsed_cloth.h"
#include "support/self_collision_check.h"

namespace cloth {
namespace {

using test::runAndCheck;
using Outcome = test::SelfCheck;

// Runs `scene` on the CPU backend for `steps`, checking every `every` steps.
Outcome runAndCheck(const Scene& scene, Precision precision, long steps, long every) {
    auto solver = makeCpuSolver(scene, CpuOptions{precision, 0});
    const double cutoff = scene.selfCollision ? scene.selfCollision->thickness : 0.01;
    return runAndCheck(*solver, steps, every, cutoff);
}

Scene shipped(const std::string& name, const std::vector<std::string>& sets = {}) {
    return loadScene(std::string(CLOTH_SOURCE_DIR) + "/scenes/" + name + ".json", sets);
}

struct Case {
    const char* name;
    std::vector<std::string> sets;  // a coarser or shorter run than the shipped one
    long steps, every;
};

// The shipped scenes at the resolutions the tests afford: the pile at half its resolution (and
// so twice its step, which the stability bound allows), the fold and the cape as shipped over
// the part of their runs where they fold.
const Case kCases[] = {
    {"pile", {"cloth.resolution=[12,24]", "integrator.dt=5e-4"}, 3000, 50},
    {"fold", {}, 6000, 100},
    {"cape", {}, 3500, 100},
};

class SelfCollisionScenes : public ::testing::TestWithParam<Case> {};

// Law: no crossing and no pair closer than h/2 at the end of any checked step.
TEST_P(SelfCollisionScenes, NeverCrossItselfAndKeepHalfTheThickness) {
    const Case& c = GetParam();
    const Scene scene = shipped(c.name, c.sets);
    ASSERT_TRUE(scene.selfCollision);
    const double h = scene.selfCollision->thickness;
    for (Precision p : {Precision::Double, Precision::Float}) {
        const Outcome o = runAndCheck(scene, p, c.steps, c.every);
        std::printf(
            "%s %s: %ld crossings at worst, closest %.3g m (h = %g m), %.2f substeps a "
            "step (at most %d), %.1f contacts an iteration\n",
            c.name, precisionName(p), o.worstCrossings, o.closest, h,
            double(o.stats.substeps) / double(o.stats.steps), o.stats.mostSubsteps,
            double(o.stats.contacts) / double(std::max(1L, o.stats.iterations)));
        EXPECT_EQ(o.worstCrossings, 0) << c.name << " " << precisionName(p);
        EXPECT_GE(o.closest, 0.5 * h) << c.name << " " << precisionName(p);
        EXPECT_EQ(o.stats.stepsOverBound, 0);
        EXPECT_GT(o.stats.contacts, 0) << "the scene never touched itself: it tests nothing";
    }
}

// The same scenes without self-collision do pass through themselves: the check above can fail.
TEST_P(SelfCollisionScenes, CrossThemselvesWithSelfCollisionOff) {
    const Case& c = GetParam();
    Scene scene = shipped(c.name, c.sets);
    scene.selfCollision.reset();
    const Outcome o = runAndCheck(scene, Precision::Double, c.steps, c.every);
    std::printf("%s without self-collision: %ld frames crossed, %ld crossings at worst\n", c.name,
                o.crossedFrames, o.worstCrossings);
    EXPECT_GT(o.worstCrossings, 0);
    EXPECT_EQ(o.stats.steps, 0);  // and nothing of it ran
}

INSTANTIATE_TEST_SUITE_P(Shipped, SelfCollisionScenes, ::testing::ValuesIn(kCases),
                         [](const auto& param) { return std::string(param.param.name); });

// The first contacts of the coarse pile, short enough to run under the sanitizers too (make
// asan leaves the scene runs above to make test): no crossing, h/2 kept, contacts made.
TEST(SelfCollision, TheCoarsePilesFirstContactsKeepItApart) {
    const Scene scene = shipped("pile", {"cloth.resolution=[12,24]", "integrator.dt=5e-4"});
    const Outcome o = runAndCheck(scene, Precision::Double, 600, 50);
    EXPECT_EQ(o.worstCrossings, 0);
    EXPECT_GE(o.closest, 0.5 * scene.selfCollision->thickness);
    EXPECT_GT(o.stats.contacts, 0);
}

// The corrections are summed in fixed point with integer atomics: one thread and two give the
// same bits (as the GPU's work groups will, in whatever order they add).
TEST(SelfCollision, AnyThreadCountGivesTheSameBits) {
    const Scene scene = shipped("pile", {"cloth.resolution=[12,24]", "integrator.dt=5e-4"});
    std::vector<SimState> states;
    for (int threads : {1, 2}) {
        auto solver = makeCpuSolver(scene, CpuOptions{Precision::Double, threads});
        ASSERT_FALSE(solver->step(700).unstable);
        EXPECT_GT(solver->selfCollisionStats().contacts, 0);
        states.push_back(solver->read());
    }
    for (std::size_t k = 0; k < states[0].positions.size(); ++k) {
        ASSERT_EQ(states[0].positions[k], states[1].positions[k]) << "vertex " << k;
        ASSERT_EQ(states[0].velocities[k], states[1].velocities[k]) << "vertex " << k;
    }
}

// A cloth collapsed onto itself (the coarse pile's 288 vertices within 1 cm of a point: each in
// more contacts than its fixed-point sums hold) stops at its first iteration, naming a vertex, and
// keeps the state the integrator left, on 1 and 2 threads. Before, such a step ran its 256
// substeps of 16 iterations over every pair: 3.7 s a step at this size, 32 s at 24², and its
// sums could overflow.
TEST(SelfCollision, ACollapsedClothStopsAtOnceNamingACrowdedVertex) {
    const Scene scene = shipped("pile", {"cloth.resolution=[12,24]", "integrator.dt=5e-4"});
    Scene without = scene;
    without.selfCollision.reset();
    auto plain = makeCpuSolver(without, CpuOptions{Precision::Double, 1});
    const SimState start = plain->read();
    const SimState collapsed = test::collapsedCloth(start, {0, 0.5, 0}, 0.01);
    plain->write(collapsed);
    ASSERT_FALSE(plain->step(1).unstable);
    for (int threads : {1, 2}) {
        auto solver = makeCpuSolver(scene, CpuOptions{Precision::Double, threads});
        solver->write(collapsed);
        const StepResult r = solver->step(5);
        std::printf("%d threads: %s\n", threads, r.reason.c_str());
        ASSERT_TRUE(r.unstable);
        EXPECT_EQ(r.firstBadStep, 1);
        EXPECT_EQ(r.stepsTaken, 1);
        EXPECT_EQ(r.reason.rfind("self-collision: vertex (", 0), 0u) << r.reason;
        EXPECT_NE(r.reason.find("collapsed onto itself"), std::string::npos) << r.reason;
        EXPECT_EQ(solver->selfCollisionStats().iterations, 0);  // none finished
        const SimState s = solver->read(), p = plain->read();
        for (std::size_t k = 0; k < s.positions.size(); ++k) {
            ASSERT_EQ(s.positions[k], p.positions[k]) << "vertex " << k;
            ASSERT_EQ(s.velocities[k], p.velocities[k]) << "vertex " << k;
        }
        solver->write(start);  // a fresh state runs on
        EXPECT_FALSE(solver->step(20).unstable);
        EXPECT_GT(solver->selfCollisionStats().iterations, 0);
    }
}

// Law (momentum): a contact's corrections are Δx_j = α_j w_j D / Σ α² w with Σ α_j = 0 (the
// relative position of the contact is an affine difference), so Σ m_j Δx_j = 0.
TEST(SelfContact, CorrectionsConserveMomentumAndOpenTheGapToTheThickness) {
    using V = glm::dvec3;
    const double h = 0.01;
    // A point 2 mm above the centroid of a horizontal triangle, sides taken where it is.
    const V a(0, 0, 0), b(1, 0, 0), c(0, 0, 1), p(1.0 / 3, 0.002, 1.0 / 3);
    ContactGeometry<double> g;
    ASSERT_TRUE(pointTriangle(p, a, b, c, pointTriangleSide(p, a, b, c), g));
    EXPECT_NEAR(g.gap, 0.002, 1e-15);
    const std::array<double, 4> w{1 / 0.5, 1 / 2.0, 1 / 1.0, 1 / 4.0};  // 1/m [1/kg]
    std::array<V, 4> dx;
    ASSERT_TRUE(contactCorrection(g, w, 4, V(0), h, 0.0, dx));
    V momentum(0);
    for (int j = 0; j < 4; ++j) momentum += dx[j] / w[j];
    EXPECT_LT(glm::length(momentum), 1e-17);
    // The gap on the moved points is h to first order: the triangle's vertices move by
    // different amounts (α_j w_j), so it turns a little.
    const V p2 = p + dx[0], a2 = a + dx[1], b2 = b + dx[2], c2 = c + dx[3];
    const V centroid = (a2 + b2 + c2) / 3.0;
    EXPECT_NEAR(glm::dot(p2 - centroid, V(0, 1, 0)), h, 2e-4);
    // Two skew edges 1 mm apart: the same conservation.
    ContactGeometry<double> e;
    const V p0(-1, 0, 0), p1(1, 0, 0), q0(0, 0.001, -1), q1(0, 0.001, 1);
    const V cross = glm::cross(p1 - p0, q1 - q0);
    ASSERT_TRUE(edgeEdge(p0, p1, q0, q1, sideOf(glm::dot(cross, p0 - q0)), cross, e));
    EXPECT_NEAR(e.gap, 0.001, 1e-15);
    ASSERT_TRUE(contactCorrection(e, w, 4, V(0), h, 0.0, dx));
    momentum = V(0);
    for (int j = 0; j < 4; ++j) momentum += dx[j] / w[j];
    EXPECT_LT(glm::length(momentum), 1e-17);
    // The closest points, the edges' middles: p below q, now h apart.
    const V pMiddle = 0.5 * (p0 + dx[0] + p1 + dx[1]), qMiddle = 0.5 * (q0 + dx[2] + q1 + dx[3]);
    EXPECT_NEAR(pMiddle.y - qMiddle.y, -h, 1e-15);
}

// The side is where the substep's motion put the point, before any correction: a point that
// is below a triangle is pushed further down, never through it.
TEST(SelfContact, AContactKeepsThePointOnItsOwnSide) {
    using V = glm::dvec3;
    const V a(0, 0, 0), b(1, 0, 0), c(0, 0, 1), below(0.2, -0.001, 0.2);
    ContactGeometry<double> g;
    ASSERT_TRUE(pointTriangle(below, a, b, c, pointTriangleSide(below, a, b, c), g));
    std::array<V, 4> dx;
    ASSERT_TRUE(contactCorrection(g, {1.0, 1.0, 1.0, 1.0}, 4, V(0), 0.01, 0.0, dx));
    EXPECT_LT(dx[0].y, 0);
    EXPECT_GT(dx[1].y + dx[2].y + dx[3].y, 0);
}

}  // namespace
}  // namespace cloth
