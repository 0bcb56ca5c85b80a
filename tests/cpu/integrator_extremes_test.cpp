// Extreme parameters (DESIGN.md §2, "Instability"): for every method, in double and in float, a
// run either stays finite or is stopped and reported unstable at its first bad step — never a
// non-finite state left unreported, never a crash or a hang — and implicit Euler's capped solves
// are counted as misses.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "solver/diagnostics.h"
#include "scene/scene_loader.h"
#include "cpu/cpu_backend.h"
#include "solver/solver.h"

namespace cloth {
namespace {

constexpr long kSteps = 300;

// A 5×4 cloth with every feature: three families, wind, a floor below it, two pinned corners.
Scene baseScene() {
    return parseScene(R"({
      "cloth": { "resolution": [5, 4], "size": [1, 0.8], "origin": [0, 1, 0], "mass": 0.1 },
      "springs": { "structural": 100, "shear": 30, "bend": 5 }, "damping": 0.5,
      "pins": [[0, 0], [-1, 0]],
      "integrator": { "dt": 0.001 },
      "colliders": [ { "type": "plane", "point": [0, 0.5, 0], "normal": [0, 1, 0] } ],
      "wind": { "direction": [1, 0, 1], "strength": 0.5 } })",
                      "extremes (test)");
}

struct Extreme {
    const char* name;
    std::function<void(Scene&)> apply;
};

void scaleSprings(Scene& s, double k) {
    s.springs.structural = k;
    s.springs.shear = 0.3 * k;
    s.springs.bend = 0.05 * k;
}

const Extreme kExtremes[] = {
    {"dt 1e-7", [](Scene& s) { s.integrator.dt = 1e-7; }},
    {"dt 1e-1", [](Scene& s) { s.integrator.dt = 1e-1; }},
    {"K 1e-3", [](Scene& s) { scaleSprings(s, 1e-3); }},
    {"K 1e9", [](Scene& s) { scaleSprings(s, 1e9); }},
    {"mass 1e-6", [](Scene& s) { s.cloth.mass = 1e-6; }},
    {"mass 1e6", [](Scene& s) { s.cloth.mass = 1e6; }},
    {"zero damping", [](Scene& s) { s.damping = 0; }},
    {"1x2 grid",
     [](Scene& s) {
         s.cloth.nu = 1;
         s.cloth.nv = 2;
         s.pins = {{0, 0}};
     }},
};

// Runs `scene` for kSteps and checks the contract; returns a one-word outcome for the table.
std::string runAndCheck(const Scene& scene, Precision precision, const std::string& what) {
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {precision, 1});
    const StepResult r = solver->step(kSteps);
    const SolveStats& cg = solver->solveStats();
    if (r.unstable) {
        EXPECT_FALSE(r.reason.empty()) << what;
        EXPECT_GE(r.firstBadStep, 1) << what;
        EXPECT_EQ(r.firstBadStep, r.stepsTaken) << what << ": stopped at the first bad step";
        EXPECT_EQ(solver->stepsDone(), r.stepsTaken) << what;
    } else {
        EXPECT_EQ(r.stepsTaken, kSteps) << what;
        EXPECT_TRUE(allFinite(solver->read())) << what << ": a non-finite state not reported";
    }
    if (scene.integrator.method == Method::ImplicitEuler) {
        EXPECT_EQ(cg.solves, r.stepsTaken) << what;
        if (cg.misses > 0) {
            EXPECT_GE(cg.firstMissStep, 1) << what;
            EXPECT_GT(cg.worstResidual, scene.integrator.tolerance) << what;
        }
    } else {
        EXPECT_EQ(cg.solves, 0) << what;
    }
    char out[96];
    const char* tag = precision == Precision::Float ? "f:" : "";
    if (r.unstable)
        std::snprintf(out, sizeof out, "%sunstable@%ld", tag, r.firstBadStep);
    else if (cg.misses > 0)
        std::snprintf(out, sizeof out, "%sfinite,%ldmiss", tag, cg.misses);
    else
        std::snprintf(out, sizeof out, "%sfinite", tag);
    return out;
}

TEST(IntegratorExtremes, EveryMethodRunsFiniteOrReportsInstability) {
    std::printf("%-13s", "");
    for (Method m : kMethods) std::printf(" %-17s", methodName(m));
    std::printf("\n");
    for (const Extreme& e : kExtremes) {
        std::printf("%-13s", e.name);
        for (Method m : kMethods) {
            Scene s = baseScene();
            s.integrator.method = m;
            e.apply(s);
            const std::string what = std::string(e.name) + ", " + methodName(m);
            const std::string d = runAndCheck(s, Precision::Double, what);
            const std::string f = runAndCheck(s, Precision::Float, what + ", float");
            // The table shows double, and float where it differs (prefixed "f:").
            std::printf(" %-17s", (d + (f == "f:" + d ? "" : " " + f)).c_str());
        }
        std::printf("\n");
    }
}

// Explicit Euler without damping grows at every Δt (DESIGN.md §2); left long enough it is
// reported, not written as NaN.
TEST(IntegratorExtremes, UndampedExplicitEulerIsEventuallyReported) {
    Scene s = baseScene();
    s.damping = 0;
    s.integrator.dt = 5e-3;
    std::unique_ptr<Solver> solver = makeCpuSolver(s, {Precision::Double, 1});
    const StepResult r = solver->step(200000);
    EXPECT_TRUE(r.unstable);
    EXPECT_LT(r.stepsTaken, 200000);
}

// A conjugate gradient capped below what the system needs: every capped solve is a miss, with
// its step and residual; the step goes on with the last iterate and the run stays finite.
TEST(IntegratorExtremes, CappedConjugateGradientReportsItsMisses) {
    Scene s = baseScene();
    s.integrator.method = Method::ImplicitEuler;
    scaleSprings(s, 1e6);  // h² K / m = 10: CG needs far more than two iterations
    s.integrator.tolerance = 1e-12;
    s.integrator.maxIterations = 2;
    std::unique_ptr<Solver> solver = makeCpuSolver(s, {Precision::Double, 1});
    const StepResult r = solver->step(50);
    const SolveStats& cg = solver->solveStats();
    std::printf("capped CG: %ld solves, %ld misses, first at step %ld, worst residual %.3g\n",
                cg.solves, cg.misses, cg.firstMissStep, cg.worstResidual);
    EXPECT_FALSE(r.unstable) << r.reason;
    EXPECT_TRUE(allFinite(solver->read()));
    EXPECT_EQ(cg.solves, 50);
    EXPECT_GT(cg.misses, 0);
    EXPECT_EQ(cg.firstMissStep, 1);
    EXPECT_EQ(cg.mostIterations, 2);
    EXPECT_GT(cg.worstResidual, 1e-12);

    s.integrator.maxIterations = 1000;  // the same run, uncapped: no miss
    std::unique_ptr<Solver> full = makeCpuSolver(s, {Precision::Double, 1});
    EXPECT_FALSE(full->step(50).unstable);
    EXPECT_EQ(full->solveStats().misses, 0);
    EXPECT_GT(full->solveStats().mostIterations, 2);
}

}  // namespace
}  // namespace cloth
