// The stability law of DESIGN.md §2 for the seed's explicit Euler: stable iff Δt < μ/λ_max,
// independent of the mass. A pinned 1×2 spring moving along its axis is exactly one mode with
// λ = K, so the predicted bound is exact there and the law can be checked on both sides of it.
#include "core/stability.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/scene_loader.h"
#include "core/solver.h"

namespace cloth {
namespace {

Scene spring(double k, double mu, double m, double dt) {
    char text[512];
    std::snprintf(text, sizeof text,
                  R"({"cloth": {"resolution": [1, 2], "size": [1, 1], "u_axis": [1, 0, 0],
                  "v_axis": [0, -1, 0], "mass": %.17g}, "springs": {"structural": %.17g},
                  "damping": %.17g, "pins": [[0, 0]], "integrator": {"dt": %.17g},
                  "gravity": [0, -9.81, 0]})",
                  m, k, mu, dt);
    return parseScene(text, "spring");
}

// Peak |y − y_eq| over the last tenth of a run of n steps, against the first tenth.
double amplitudeGrowth(const Scene& s, long n) {
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const double eq = -1 - s.cloth.mass * 9.81 / s.springs.structural;  // rest length + mg/K
    double early = 0, late = 0;
    for (long k = 0; k < n; ++k) {
        if (solver->step(1).unstable) return INFINITY;
        const double y = solver->read().positions[1].y;
        if (k < n / 10) early = std::max(early, std::abs(y - eq));
        if (k >= n - n / 10) late = std::max(late, std::abs(y - eq));
    }
    return late / early;
}

TEST(StabilityBound, PinnedSpringBoundIsMuOverK) {
    const Scene s = spring(100, 0.5, 1, 1e-3);
    const StabilityBound b = estimateStability(s);
    EXPECT_DOUBLE_EQ(b.lambdaMax, 100);  // one spring to a pinned vertex: λ = K
    EXPECT_DOUBLE_EQ(b.explicitEulerDt, 0.5 / 100);
}

TEST(StabilityBound, InteriorVertexGivesTwiceTheSumOfTheTwelveSprings) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [9, 9], "size": [1, 1]},
        "springs": {"structural": 10, "shear": 5, "bend": 1}, "damping": 1,
        "integrator": {"dt": 0.001}})",
                               "grid");
    EXPECT_DOUBLE_EQ(estimateStability(s).lambdaMax, 2 * (4 * 10 + 4 * 5 + 4 * 1));
}

TEST(ExplicitEulerLaw, StableJustBelowMuOverKAndGrowingJustAbove) {
    for (double m : {0.1, 1.0, 10.0}) {  // the bound does not depend on the mass
        const double k = 100, mu = 0.5, bound = mu / k;
        const long n = 4000;
        EXPECT_LT(amplitudeGrowth(spring(k, mu, m, 0.9 * bound), n), 1.0) << "m = " << m;
        EXPECT_GT(amplitudeGrowth(spring(k, mu, m, 1.1 * bound), n), 1.0) << "m = " << m;
    }
}

TEST(ExplicitEulerLaw, WithoutDampingEveryStepSizeGrows) {
    const Scene s = spring(100, 0, 1, 1e-4);
    EXPECT_EQ(estimateStability(s).explicitEulerDt, 0.0);
    EXPECT_GT(amplitudeGrowth(s, 20000), 1.0);
    EXPECT_NE(stabilityAdvice(s).find("damping"), std::string::npos);
}

}  // namespace
}  // namespace cloth
