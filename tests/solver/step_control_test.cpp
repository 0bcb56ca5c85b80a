// Step control (solver/step_control.h): a step that stretches a structural spring by more than
// integrator.max_step_strain is taken again from its start in halves. What it must keep: the
// steps that pass are the backend's own, bit for bit; a step split to the shortest is a run at
// that step; the time and step count are the scene's; and the stiff sheet that one long
// implicit step tears at the impact is held.
#include "solver/step_control.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "backends/solver_factory.h"
#include "cpu/cpu_backend.h"
#include "model/pin_follow.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"
#include "support/impact_runs.h"
#include "support/same_bits.h"

namespace cloth {
namespace {

Scene withControl(Scene scene, double maxStepStrain) {
    scene.integrator.maxStepStrain = maxStepStrain;
    return scene;
}

// An 8 × 6 sheet of springs hanging from two corners, falling from flat: its springs stretch
// a little more at every step of the first tenth of a second.
Scene hangingSheet(double dt) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "cloth": { "resolution": [8, 6], "size": [0.7, 0.5], "origin": [0, 1, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.01 },
      "springs": { "structural": 300, "shear": 100, "bend": 10 }, "damping": 0.01,
      "gravity": [0, -9.81, 0], "pins": [[0, 0], [-1, 0]],
      "integrator": { "method": "symplectic_euler", "dt": 0.001 }
    })");
    j["integrator"]["dt"] = dt;
    return parseScene(j.dump(), "hanging (test)");
}

// The measure: a structural spring's stretch max(0, ε) and how much a step grew it; compression,
// and the shear and bend springs, do not count.
TEST(StepControl, StretchGrowthIsTheStructuralSpringsStretch) {
    const Scene scene = hangingSheet(0.001);
    const Grid g = scene.grid();
    SimState before{g.nu, g.nv, {}, {}, 0};
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) before.positions.push_back(g.restPosition(i, j));
    before.velocities.assign(before.positions.size(), glm::dvec3(0));
    SimState after = before;
    const double du = g.restLength(1, 0);
    after.positions[std::size_t(g.index(7, 5))].x += 0.2 * du;  // the (6,5)-(7,5) spring: +0.2
    after.positions[std::size_t(g.index(0, 3))].x += 0.5 * du;  // (0,3)-(1,3) squeezed by half
    SpringStrain s = largestStretchGrowth(scene, before, after);
    EXPECT_NEAR(s.strain, 0.2, 1e-12);
    EXPECT_EQ(s.a, g.index(6, 5));
    EXPECT_EQ(s.b, g.index(7, 5));
    // A spring already stretched by 0.2 that goes to 0.25 grew by 0.05; one squeezed by 0.5 that
    // comes back to its rest length grew by nothing.
    SimState later = after;
    later.positions[std::size_t(g.index(7, 5))].x += 0.05 * du;
    later.positions[std::size_t(g.index(0, 3))].x -= 0.5 * du;
    s = largestStretchGrowth(scene, after, later);
    EXPECT_NEAR(s.strain, 0.05, 1e-12);
    // A length that is not finite, before or after, is the worst (+inf) wherever it lies, not
    // only on the last spring looked at.
    const double inf = std::numeric_limits<double>::infinity();
    SimState huge = later;
    huge.positions[std::size_t(g.index(3, 2))].y = 1e300;  // finite, its spring's length not
    EXPECT_EQ(largestStretchGrowth(scene, huge, later).strain, inf);
    later.positions[std::size_t(g.index(3, 2))].y = std::nan("");
    EXPECT_EQ(largestStretchGrowth(scene, after, later).strain, inf);
    EXPECT_TRUE(std::isnan(largestStrain(scene, later).strain));
}

// The CPU's own check (cpu/cpu_step_check.cpp) decides as the states read back would: its
// measure is largestStretchGrowth's of read() before and after, in float and double, +inf where
// a length is not finite now or at the kept start; and restore() gives back the kept state bit
// for bit, with its time.
TEST(StepControl, TheCpusCheckMeasuresWhatTheStatesReadBackDo) {
    const Scene scene = withControl(hangingSheet(0.001), 0.1);
    for (Precision p : {Precision::Float, Precision::Double}) {
        std::unique_ptr<Solver> cpu = makeCpuSolver(scene, {p, 1});
        ASSERT_FALSE(cpu->step(40).unstable);
        const SimState before = cpu->read();
        StepCheck* check = cpu->stepCheck();
        ASSERT_NE(check, nullptr);
        check->keep();
        ASSERT_FALSE(cpu->step(5).unstable);
        const double grown = check->stretchGrowth();
        EXPECT_GT(grown, 0) << precisionName(p);
        EXPECT_DOUBLE_EQ(grown, largestStretchGrowth(scene, before, cpu->read()).strain)
            << precisionName(p);
        SimState torn = cpu->read();
        torn.positions[std::size_t(scene.grid().index(3, 2))].y = std::nan("");
        cpu->write(torn);
        const double inf = std::numeric_limits<double>::infinity();
        EXPECT_EQ(check->stretchGrowth(), inf) << precisionName(p);
        check->restore();
        test::expectSameBits(cpu->read(), before, precisionName(p));
        EXPECT_EQ(cpu->time(), before.time) << precisionName(p);
        SimState huge = before;  // a length of +inf (not NaN) at the start, a finite one now
        huge.positions[std::size_t(scene.grid().index(3, 2))].y = 1e300;
        cpu->write(huge);
        check->keep();
        cpu->write(before);
        EXPECT_EQ(check->stretchGrowth(), inf) << precisionName(p);
    }
    EXPECT_EQ(makeCpuSolver(withControl(scene, 0), {Precision::Double, 1})->stepCheck(), nullptr);
}

// Where no step stretches a spring by the limit, the control only reads: the same bits as the
// scene without it, and nothing split.
TEST(StepControl, StepsThatPassAreTheBackendsOwn) {
    const Scene scene = hangingSheet(0.001);
    auto plain = makeSolver(scene, {Backend::Cpu, Precision::Double, 1});
    auto controlled = makeSolver(withControl(scene, 0.5), {Backend::Cpu, Precision::Double, 1});
    ASSERT_FALSE(plain->step(300).unstable);
    ASSERT_FALSE(controlled->step(300).unstable);
    test::expectSameBits(plain->read(), controlled->read(), "max_step_strain 0.5");
    EXPECT_EQ(controlled->stepControlStats().split, 0);
    EXPECT_EQ(controlled->stepControlStats().substeps, 300);
    EXPECT_EQ(controlled->stepsDone(), 300);
}

// A limit no step can meet splits every step to Δt/16, where a step is kept as it comes: the run
// is then the run at Δt/16, bit for bit (a thrown-away try leaves no trace in the state).
TEST(StepControl, EveryStepSplitToTheShortestIsTheRunAtThatStep) {
    const long steps = 40;
    const int pieces = 1 << StepControl::kMaxHalvings;
    auto controlled =
        makeSolver(withControl(hangingSheet(0.0016), 1e-12), {Backend::Cpu, Precision::Double, 1});
    auto fine = makeSolver(hangingSheet(0.0001), {Backend::Cpu, Precision::Double, 1});
    ASSERT_FALSE(controlled->step(steps).unstable);
    ASSERT_FALSE(fine->step(steps * pieces).unstable);
    const StepControlStats stats = controlled->stepControlStats();
    ASSERT_EQ(stats.substeps, steps * pieces) << "some piece passed above the shortest";
    EXPECT_EQ(stats.deepest, StepControl::kMaxHalvings);
    EXPECT_EQ(stats.split, steps);
    // The first step threw away its try at Δt, both at Δt/2, the four at Δt/4 and the eight at
    // Δt/8; as its pieces at Δt/16 failed the check too, every later step starts there.
    EXPECT_EQ(stats.rejected, pieces - 1);
    test::expectSameBits(fine->read(), controlled->read(), "every step in 16 pieces");
    EXPECT_EQ(controlled->stepsDone(), steps);
    EXPECT_NEAR(controlled->time(), double(steps) * 0.0016, 1e-15);
}

// The time the moving parts are posed at is the scene's: a pin following a swinging sphere is,
// after 200 split steps, where the sphere's motion puts it at t = 200 Δt.
TEST(StepControl, TheTimeIsTheScenesStepsTimesDt) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "cloth": { "resolution": [5, 4], "size": [0.4, 0.3], "origin": [-0.2, 1.0, 0.0],
                 "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": 0.01 },
      "springs": { "structural": 50 }, "damping": 0.02,
      "pins": [ {"at": [0, 0], "follow": 0} ],
      "integrator": { "method": "symplectic_euler", "dt": 0.001, "max_step_strain": 1e-12 },
      "colliders": [ { "type": "sphere", "center": [-0.2, 1.2, 0], "radius": 0.1,
                       "motion": { "type": "oscillation", "axis": [1, 0, 0], "amplitude": 0.1,
                                   "frequency": 1.0 } } ]
    })");
    const Scene scene = parseScene(j.dump(), "swinging (test)");
    auto solver = makeSolver(scene, {Backend::Cpu, Precision::Double, 1});
    ASSERT_FALSE(solver->step(200).unstable);
    EXPECT_GT(solver->stepControlStats().split, 100);
    EXPECT_EQ(solver->stepsDone(), 200);
    EXPECT_NEAR(solver->time(), 0.2, 1e-15);
    EXPECT_NEAR(solver->read().time, 0.2, 1e-12);
    const glm::dvec3 want = followPinAt(followPins(scene)[0], 0.2).position;
    EXPECT_LT(glm::length(solver->read().positions[0] - want), 1e-9);
}

// Turning the control on or off changes what the solver is: setParameters refuses, and the
// caller (the viewer) builds a new one.
TEST(StepControl, TurningItOnOrOffBuildsANewSolver) {
    const Scene scene = hangingSheet(0.001);
    auto controlled = makeSolver(withControl(scene, 0.1), {Backend::Cpu, Precision::Float, 1});
    auto plain = makeSolver(scene, {Backend::Cpu, Precision::Float, 1});
    EXPECT_THROW(controlled->setParameters(scene), std::invalid_argument);
    EXPECT_THROW(plain->setParameters(withControl(scene, 0.1)), std::invalid_argument);
    EXPECT_NO_THROW(controlled->setParameters(withControl(scene, 0.3)));
}

// The case the control is for: implicit Euler at Δt = 1/60 through the drape's impact on the
// sphere, stretch 1e6 N/m, 48². One linearisation a step cannot follow the sheet turning about
// the sphere: springs reach 1.02 in float, 0.50 in double (docs/stability.md). Split where a
// step stretches a spring by more than 0.1, no spring passes 0.15, only the impact's steps (the
// sheet touches the sphere in frame 13) are split, and the pieces' solves cost less than twice
// the torn run's over these 30 frames (1277 against 780 iterations; over 45 frames, 2462
// against 2403, when the torn sheet's solves grow).
TEST(StepControl, HoldsTheStiffSheetThroughTheImpact) {
    const BackendChoice cpu{Backend::Cpu, Precision::Float, 1};
    const test::ImpactRun plain = test::runImpact(test::stiffDrape(48, 0), cpu, 30);
    const test::ImpactRun controlled = test::runImpact(test::stiffDrape(48, 0.1), cpu, 30);
    std::printf(
        "48² drape, stretch 1e6, 30 frames: largest strain %.3f without, %.3f with "
        "(%ld steps split in frames %ld–%ld, %ld substeps, Δt/%d at the shortest); CG "
        "iterations %ld, %ld\n",
        plain.largest, controlled.largest, controlled.control.split, controlled.firstSplitFrame,
        controlled.lastSplitFrame, controlled.control.substeps, 1 << controlled.control.deepest,
        plain.iterations, controlled.iterations);
    EXPECT_GT(plain.largest, 0.5) << "the case no longer tears without the control";
    EXPECT_LT(controlled.largest, 0.15);
    EXPECT_GE(controlled.firstSplitFrame, 13);
    EXPECT_LT(double(controlled.iterations), 2.0 * double(plain.iterations));
}

// The backend numbers its own steps, the pieces of split steps and the tries thrown away among
// them; the summary's "first miss at step N" (and Python's first_miss_step) names the scene's
// step. Here the impact's steps are split before the capped CG first misses. Before the
// renumbering the first miss was reported some pieces later than the step it fell in.
TEST(StepControl, TheFirstMissIsNumberedByTheScenesSteps) {
    Scene scene = test::stiffDrape(32, 0.1);
    scene.integrator.maxIterations = 12;
    auto solver = makeSolver(scene, {Backend::Cpu, Precision::Float, 1});
    long stepOfFirstMiss = 0, splitBefore = 0;
    for (long step = 1; step <= 30 && stepOfFirstMiss == 0; ++step) {
        splitBefore = solver->stepControlStats().split;
        ASSERT_FALSE(solver->step(1).unstable) << "step " << step;
        if (solver->solveStats().misses > 0) stepOfFirstMiss = step;
    }
    ASSERT_GT(stepOfFirstMiss, 0) << "no solve missed: the case no longer tests the numbering";
    ASSERT_GT(splitBefore, 0) << "no step was split before the first miss";
    EXPECT_EQ(solver->solveStats().firstMissStep, stepOfFirstMiss);
}

}  // namespace
}  // namespace cloth
