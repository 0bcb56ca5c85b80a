// The measured stability bound (solver/stability_probe.h) against closed forms: on the pinned 1×2
// spring every integrator's bound is exact for its one mode λ = K; on a small cloth explicit
// Euler's measured bound is μ/λ_max, between the Gershgorin (safe) and the power-iteration
// (tight) predictions.
#include "solver/stability_probe.h"

#include <gtest/gtest.h>

#include <cmath>

#include "cpu/cpu_backend.h"
#include "model/stability.h"
#include "scene/scene_loader.h"

namespace cloth {
namespace {

Scene load(const std::string& file, const std::vector<std::string>& sets = {}) {
    return loadScene(CLOTH_SOURCE_DIR "/scenes/" + file, sets);
}

ProbeResult probe(const Scene& s, Method m, Precision p = Precision::Double) {
    ProbeOptions o;
    o.kick = p == Precision::Double ? 1e-6 : 1e-3;
    o.maxSteps = 5000;
    return probeStableDt(
        s, m, estimateStability(s, 40).tightDt(m),
        [&](const Scene& scene) {
            return makeCpuSolver(scene, {p, 1});
        },
        o);
}

TEST(StabilityProbe, EveryExplicitIntegratorMeetsItsBoundOnTheSpring) {
    for (const char* k : {"100", "1e5"}) {
        const Scene s = load("spring.json", {std::string("springs.structural=") + k});
        for (Method m :
             {Method::ExplicitEuler, Method::SymplecticEuler, Method::Verlet, Method::Rk4}) {
            const double exact = methodDt(m, s.springs.structural, s.cloth.mass, s.damping);
            const ProbeResult r = probe(s, m);
            EXPECT_EQ(r.status, ProbeStatus::Bounded) << methodName(m) << " K = " << k;
            // The largest stable Δt found lies below the bound, the smallest unstable above.
            EXPECT_LE(r.stableDt, exact * (1 + 1e-9)) << methodName(m) << " K = " << k;
            EXPECT_GE(r.unstableDt, exact * (1 - 1e-9)) << methodName(m) << " K = " << k;
            EXPECT_NEAR(r.stableDt, exact, 0.03 * exact) << methodName(m) << " K = " << k;
        }
    }
}

// The seed's per-vertex hanging cloth (one mass, drag μ per vertex: DESIGN.md §2's bound).
TEST(StabilityProbe, ExplicitEulerOnAClothSitsBetweenTheSafeAndTheTightPrediction) {
    const Scene s =
        loadScene(CLOTH_SOURCE_DIR "/bench/hanging_per_vertex.json", {"cloth.resolution=[6,7]"});
    const StabilityBound b = estimateStability(s, 40);
    for (Precision p : {Precision::Double, Precision::Float}) {
        const ProbeResult r = probe(s, Method::ExplicitEuler, p);
        EXPECT_GE(r.stableDt, b.safeDt(Method::ExplicitEuler));
        EXPECT_LE(r.stableDt, b.tightDt(Method::ExplicitEuler) * 1.02);
        EXPECT_GE(r.stableDt, b.tightDt(Method::ExplicitEuler) * 0.9);
    }
}

TEST(StabilityProbe, ImplicitEulerIsStableToTheCapAndUndampedExplicitEulerNowhere) {
    const Scene s = load("spring.json");
    const ProbeResult implicit = probe(s, Method::ImplicitEuler);
    EXPECT_EQ(implicit.status, ProbeStatus::StableToCap);
    EXPECT_EQ(implicit.stableDt, ProbeOptions{}.cap);

    ProbeOptions o;
    o.maxSteps = 500;
    o.floor = 1e-6;
    const ProbeResult none = probeStableDt(
        load("spring.json", {"damping=0"}), Method::ExplicitEuler, 0.01,
        [](const Scene& scene) {
            return makeCpuSolver(scene, {Precision::Double, 1});
        },
        o);
    EXPECT_EQ(none.status, ProbeStatus::UnstableEverywhere);
    EXPECT_EQ(none.stableDt, 0);
}

}  // namespace
}  // namespace cloth
