// vbd's translation levels (integrator.translation_levels; docs/integrators.md "vbd", the
// translation's levels): before the first sweep, the Newton step of G on the translation of each
// block of the sheet cut into 2 × 2, 4 × 4, … 2^L × 2^L parts. Each test names the law it checks:
// - a sheet that lands carries the landing's tension across itself within the step: the bench's
//   drape at 96² and 10 sweeps at Δt = 1/60 stays under max_strain in every frame, where the
//   sweeps alone let the springs at the sphere's apex pass it;
// - the levels change where the sweeps go, not where they converge: 300 sweeps give the same
//   state with and without them;
// - vbd's default (4 levels) holds the 128² landing that the sweeps alone tear;
// - a second pass of the levels between the sweeps holds a landing off the middle that one pass
//   before the first sweep lets tear;
// - the passes fall before sweeps spread evenly over the step;
// - the finest blocks' width, not their number, decides how far a landing holds: levels are added
//   where blocks would be wider than translation_block_width, and blocks 16 wide hold a landing
//   that blocks 32 wide let tear.
// (Bits across threads and instruction sets: Vbd.EveryInstructionSetAndThreadCount… .)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "cpu/cpu_backend.h"
#include "model/vbd_local.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"
#include "support/contact_runs.h"

namespace cloth {
namespace {

// The bench's drape (src/bench/bench_realtime_scene.cpp): 1 m of cotton falls 0.3 m onto a
// sphere of 0.25 m on the ground, vbd at 10 sweeps and Δt = 1/60; `levels` < 0: vbd's default.
// The sphere lies (east, north) off the sheet's middle.
Scene drape(int n, int levels, double east = 0, double north = 0) {
    const std::string doc =
        R"({"name": "apex", "cloth": {"resolution": [)" + std::to_string(n) + ", " +
        std::to_string(n) +
        R"(], "size": [1, 1], "origin": [-0.5, 0.8, -0.5], "u_axis": [1, 0, 0], "v_axis": [0, 0, 1]},)"
        R"( "material": {"preset": "cotton"},)"
        R"( "integrator": {"method": "vbd", "dt": 0.016666666666666666, "iterations": 10)" +
        (levels < 0 ? std::string() : ", \"translation_levels\": " + std::to_string(levels)) +
        R"(}, "colliders": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},)"
        R"( {"type": "sphere", "center": [)" +
        std::to_string(east) + ", 0.25, " + std::to_string(north) +
        R"(], "radius": 0.25}], "max_strain": 100})";
    return parseScene(doc, "drape.json");
}

// The largest structural or shear strain over `frames` steps, every step measured.
double largestStrainEveryFrame(const Scene& scene, int frames) {
    auto solver = makeCpuSolver(scene, {Precision::Float, 2});
    double most = 0;
    for (int f = 0; f < frames; ++f) {
        EXPECT_FALSE(solver->step(1).unstable);
        most = std::max(most, largestStrain(scene, solver->read()).strain);
    }
    return most;
}

// Measured at 96²: 0.53 with 5 levels, 2.1 without them: the tension
// that stops the sheet at the apex reaches one vertex further a sweep, while the rest falls on.
TEST(VbdLevels, ALandingSheetHoldsInEveryFrameAtTenSweeps) {
    const double with = largestStrainEveryFrame(drape(96, 5), 60);
    const double without = largestStrainEveryFrame(drape(96, 0), 60);
    std::printf("drape 96², 10 sweeps, 1/60: largest strain %.3g with 5 levels, %.3g without\n",
                with, without);
    EXPECT_LT(with, 0.7);
    EXPECT_GT(without, 1.0) << "the sweeps alone held it";
}

// vbd as a scene gets it, without naming the levels, holds the 128² landing (4 levels: 0.60 in
// docs/integrators.md's table), which tears with the levels off (3.8).
TEST(VbdLevels, TheDefaultHoldsTheLandingThatTearsWithoutThem) {
    const Scene defaults = drape(128, -1);
    EXPECT_EQ(defaults.integrator.translationLevels, 4);
    const double with = largestStrainEveryFrame(defaults, 60);
    const double without = largestStrainEveryFrame(drape(128, 0), 60);
    std::printf("drape 128², vbd's defaults at 1/60: largest strain %.3g, %.3g without levels\n",
                with, without);
    EXPECT_LT(with, 0.8);
    EXPECT_GT(without, 1.0) << "the sweeps alone held it";
}

// A landing off the middle crosses the blocks, whose edges the pass before the first sweep
// cannot move: with 5 sweeps at 1/60 the 192² sheet, the sphere 0.2 m and 0.1 m off its middle,
// reaches strain 1.26 with one pass of 4 levels and 0.82 with a second pass before the fourth
// sweep (in double 1.27 and 0.88; docs/integrators.md "The translation's levels").
TEST(VbdLevels, ASecondPassHoldsALandingOffTheMiddleThatOnePassLetsTear) {
    Scene scene = drape(192, 4, 0.2, 0.1);
    scene.integrator.iterations = 5;
    const double one = largestStrainEveryFrame(scene, 60);
    scene.integrator.translationLevelPasses = 2;
    const double two = largestStrainEveryFrame(scene, 60);
    std::printf(
        "drape 192², sphere off the middle, 5 sweeps: largest strain %.3g with one pass "
        "of the levels, %.3g with two\n",
        one, two);
    EXPECT_GT(one, 1.1) << "one pass held it";
    EXPECT_LT(two, 0.95);
}

// The passes fall before sweep 1 and before sweeps 1 + ⌈p N / P⌉: evenly spread, at most one a
// sweep; Chebyshev's sequence starts after the sweep that follows the last of them.
TEST(VbdLevels, ThePassesAreSpreadEvenlyOverTheSweeps) {
    const auto sweeps = [](int iterations, int passes) {
        std::string out;
        for (int n = 1; n <= iterations; ++n)
            if (vbdLevelsBefore(n, iterations, passes)) out += std::to_string(n) + " ";
        return out;
    };
    EXPECT_EQ(sweeps(10, 1), "1 ");
    EXPECT_EQ(sweeps(10, 2), "1 6 ");
    EXPECT_EQ(sweeps(7, 2), "1 5 ");
    EXPECT_EQ(sweeps(6, 3), "1 3 5 ");
    EXPECT_EQ(sweeps(3, 5), "1 2 3 ");          // no more passes than sweeps
    EXPECT_EQ(sweeps(10, 0), "");               // no levels, no pass
    EXPECT_EQ(vbdChebyshevStart(1, 10, 1), 1);  // one pass: after the translation's step
    EXPECT_EQ(vbdChebyshevStart(1, 10, 2), 6);  // the pass before sweep 6
    EXPECT_EQ(vbdChebyshevStart(1, 10, 0), 1);  // no levels
    EXPECT_EQ(vbdChebyshevStart(8, 10, 2), 8);
}

// The levels that run: translation_levels, and more while the finest blocks are wider than
// translation_block_width (16 by default, so 4 levels up to 256 vertices a side).
TEST(VbdLevels, TheBlockWidthAddsLevelsOnlyWhereTheBlocksWouldBeWider) {
    EXPECT_EQ(vbdTranslationLevels(4, 16, 256, 256), 4);  // blocks 16 wide
    EXPECT_EQ(vbdTranslationLevels(4, 16, 257, 100), 5);  // the widest side counts
    EXPECT_EQ(vbdTranslationLevels(4, 16, 512, 512), 5);
    EXPECT_EQ(vbdTranslationLevels(4, 16, 1024, 1024), 6);
    EXPECT_EQ(vbdTranslationLevels(4, 16, 128, 128), 4);  // never fewer than asked
    EXPECT_EQ(vbdTranslationLevels(2, 16, 128, 128), 3);
    EXPECT_EQ(vbdTranslationLevels(4, 0, 1024, 1024), 4);   // 0: exactly the levels asked
    EXPECT_EQ(vbdTranslationLevels(0, 16, 1024, 1024), 0);  // no levels stays none
    EXPECT_EQ(vbdTranslationLevels(4, 1, 100000, 8), 16);   // at most 16
    // What runs: as far as blocks stay 2 vertices wide, and the widest finest block.
    const VbdLevelsRun wide = vbdLevelsRun(4, 16, 300, 200), cape = vbdLevelsRun(4, 16, 21, 33);
    EXPECT_EQ(wide.levels, 5);
    EXPECT_EQ(wide.width, 10);
    EXPECT_EQ(wide.height, 7);
    EXPECT_EQ(cape.levels, 3);  // 21 vertices: blocks of 2 or 3 after 3 levels
    EXPECT_EQ(cape.width, 3);
    EXPECT_EQ(cape.height, 5);
    EXPECT_EQ(vbdLevelsRun(0, 16, 1024, 1024).levels, 0);
}

// With 3 sweeps at 1/60 the 128² landing tears with 2 levels (blocks 32 wide: strain 4.8 in
// float, 4.4 in double) and holds with 3 (blocks 16 wide: 0.78 and 0.75). Asked for 2 levels with
// blocks at most 16 wide, vbd runs 3: the same bits as 3 asked for (docs/integrators.md "The
// translation's levels": the same holds 256², 512² and 1024² with 8 sweeps and 2 passes at 1/60,
// 1/120 and 1/240 s).
TEST(VbdLevels, BlocksSixteenWideHoldALandingThatBlocksThirtyTwoWideLetTear) {
    Scene narrow = drape(128, 2);
    narrow.integrator.iterations = 3;
    Scene wide = narrow, three = narrow;
    wide.integrator.translationBlockWidth = 0;
    three.integrator.translationLevels = 3;
    const double heldBy = largestStrainEveryFrame(narrow, 60);
    const double toreBy = largestStrainEveryFrame(wide, 60);
    std::printf(
        "drape 128², 3 sweeps, 2 levels asked: largest strain %.3g with blocks at most 16 "
        "wide, %.3g with blocks 32 wide\n",
        heldBy, toreBy);
    EXPECT_LT(heldBy, 0.9);
    EXPECT_GT(toreBy, 1.5) << "blocks 32 wide held it";
    EXPECT_EQ(test::farthestApartAfter(narrow, three, 20), 0.0);
}

// Converged, vbd is backward Euler whatever path its sweeps took: 300 sweeps with the levels (one
// pass a step, and three) and without them end 1 s of the stiff slide within 1e-5 m of each
// other.
TEST(VbdLevels, TheyChangeThePathNotTheConvergedStep) {
    for (int passes : {1, 3}) {
        Scene with = test::stiffSheetOnSlope(10, 0, 0), without = with;
        with.integrator.translationLevels = 3;
        with.integrator.translationLevelPasses = passes;
        without.integrator.translationLevels = 0;  // (the default runs 4)
        with.integrator.iterations = without.integrator.iterations = 300;
        const double most = test::farthestApartAfter(with, without, 60);
        std::printf(
            "300 sweeps with and without the translation's levels (%d passes): %.3g m "
            "apart\n",
            passes, most);
        EXPECT_LT(most, 1e-5) << passes << " passes";
    }
}

}  // namespace
}  // namespace cloth
