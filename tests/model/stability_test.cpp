// The stability law of DESIGN.md §2 for the seed's explicit Euler: stable iff Δt < μ/λ_max,
// independent of the mass. A pinned 1×2 spring moving along its axis is exactly one mode with
// λ = K, so the predicted bound is exact there and the law can be checked on both sides of it.
#include "model/stability.h"

#include <gtest/gtest.h>

#include <cmath>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth {
namespace {

Scene spring(double k, double mu, double m, double dt, Method method = Method::ExplicitEuler) {
    char text[600];
    std::snprintf(text, sizeof text,
                  R"({"cloth": {"resolution": [1, 2], "size": [1, 1], "u_axis": [1, 0, 0],
                  "v_axis": [0, -1, 0], "mass": %.17g}, "springs": {"structural": %.17g},
                  "damping": %.17g, "pins": [[0, 0]],
                  "integrator": {"method": "%s", "dt": %.17g, "tolerance": 1e-12},
                  "gravity": [0, -9.81, 0]})",
                  m, k, mu, methodName(method), dt);
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

// Largest sqrt((y − y_eq)² + (v/ω)²) of a run, over its start mg/K. A growing mode soon reaches
// the pin, where the spring flips and the motion stops being linear, so growth shows as this
// peak rather than as a late-over-early ratio. Infinite if the run was reported unstable.
double peakPhaseAmplitude(const Scene& s, long n) {
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const double k = s.springs.structural, m = s.cloth.mass, offset = m * 9.81 / k;
    const double eq = -1 - offset, omega = std::sqrt(k / m);
    double peak = 0;
    for (long i = 0; i < n; ++i) {
        if (solver->step(1).unstable) return INFINITY;
        const SimState st = solver->read();
        peak = std::max(peak, std::hypot(st.positions[1].y - eq, st.velocities[1].y / omega));
    }
    return peak / offset;
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

// The pinned 1×2 spring along its axis is one mode with ω² = K/m, c = μ/m, so each
// integrator's predicted bound (docs/stability.md) is exact there: just below it the oscillation
// decays, just above it grows. Verlet's bound 2/ω does not depend on the damping.
TEST(IntegratorBounds, EachSchemeIsStableJustBelowItsPredictedBoundAndGrowsJustAbove) {
    for (Method method : {Method::SymplecticEuler, Method::Verlet, Method::Rk4}) {
        for (double mu : {0.0, 0.5}) {
            const double k = 100, m = 1;
            const double bound = methodDt(method, k, m, mu);
            ASSERT_TRUE(std::isfinite(bound) && bound > 0) << methodName(method);
            const long n = 4000;
            // Undamped, the symplectic schemes neither grow nor decay below the bound.
            const double below = mu > 0 ? 1.0 : 1.01;
            EXPECT_LT(amplitudeGrowth(spring(k, mu, m, 0.97 * bound, method), n), below)
                << methodName(method) << " mu = " << mu;
            EXPECT_GT(peakPhaseAmplitude(spring(k, mu, m, 1.03 * bound, method), n), 10.0)
                << methodName(method) << " mu = " << mu;
        }
    }
}

TEST(IntegratorBounds, ClosedFormsOfTheUndampedMode) {
    const double k = 100, m = 4, omega = std::sqrt(k / m);
    EXPECT_DOUBLE_EQ(methodDt(Method::Verlet, k, m, 0), 2 / omega);
    EXPECT_DOUBLE_EQ(methodDt(Method::SymplecticEuler, k, m, 0), 2 / omega);
    EXPECT_NEAR(methodDt(Method::Rk4, k, m, 0), 2 * std::sqrt(2.0) / omega, 1e-9);
    EXPECT_EQ(methodDt(Method::ExplicitEuler, k, m, 0), 0.0);  // no stable step at all
    EXPECT_TRUE(std::isinf(methodDt(Method::ImplicitEuler, k, m, 0)));
    // The rigid drag mode alone: |1 − cΔt| ≤ 1 for the Euler schemes, RK4's real-axis reach.
    EXPECT_DOUBLE_EQ(methodDt(Method::SymplecticEuler, 0, m, 2), 2 / (2 / m));
    EXPECT_NEAR(methodDt(Method::Rk4, 0, m, 2), 2.7853 / (2 / m), 1e-3);
}

// Heavy damping: the symplectic and Verlet bounds (−c + √(c² + 4ω²))/ω² tend to 2/c (Verlet's c
// the spring damping's βω²). Evaluated as written they cancelled to 0 ("none") at βω² = 1e14 and
// overflowed to ∞ ("unconditional") at β = 1e200; the cancellation-free form keeps 2/c.
TEST(IntegratorBounds, HeavyDampingKeepsTheBoundsFiniteAndPositive) {
    const double omega2 = 1e4;
    for (double beta : {1e10, 1e100, 1e200}) {
        const double c = beta * omega2;
        for (Method m : {Method::SymplecticEuler, Method::Verlet}) {
            const double dt = dampedMethodDt(m, omega2, 0, beta);
            EXPECT_TRUE(std::isfinite(dt) && dt > 0) << methodName(m) << " β " << beta;
            EXPECT_NEAR(dt * c / 2, 1.0, 1e-9) << methodName(m) << " β " << beta;
        }
    }
}

TEST(IntegratorBounds, ImplicitEulerDecaysFarPastEveryExplicitBound) {
    const double k = 100, mu = 0.5, m = 1;
    const double dt = 20 * methodDt(Method::Rk4, k, m, mu);  // 5.6 s
    EXPECT_LT(amplitudeGrowth(spring(k, mu, m, dt, Method::ImplicitEuler), 400), 1.0);
}

// Power iteration estimates λ_max of H from below; Gershgorin bounds it from above. For a free
// chain of springs K the stiffest mode alternates and λ_max → 4K.
TEST(PowerIteration, ChainEstimateLiesBetweenTheTrueValueAndGershgorin) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [1, 64], "size": [1, 1],
        "u_axis": [1, 0, 0], "v_axis": [0, -1, 0]}, "springs": {"structural": 10},
        "damping": 1, "integrator": {"dt": 0.001}})",
                               "chain");
    const StabilityBound b = estimateStability(s, 40);
    const double exact = 4 * 10 * std::pow(std::sin(M_PI * 63 / (2 * 64)), 2);  // free-free
    EXPECT_NEAR(b.lambdaPower, exact, 1e-3 * exact);
    EXPECT_LE(b.lambdaPower, b.lambdaMax);
    EXPECT_GE(b.tightDt(Method::Verlet), b.safeDt(Method::Verlet));
}

TEST(PowerIteration, ClothEstimateIsTighterThanGershgorin) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [24, 24], "size": [1, 1]},
        "springs": {"structural": 400, "shear": 100, "bend": 10}, "damping": 0.1,
        "pins": [[0, 0], [-1, 0]], "integrator": {"dt": 0.001}})",
                               "cloth");
    const StabilityBound b = estimateStability(s, 40);
    // Along u alone the stiffest in-plane mode has λ = 4 K_structural + 2 K_shear = 2000 N/m.
    EXPECT_NEAR(b.lambdaPower, 2000, 0.01 * 2000);
    EXPECT_LT(b.lambdaPower, b.lambdaMax);
}

}  // namespace
}  // namespace cloth
