// Convergence order of every integrator on the GPU (docs/integrators.md) against the closed form
// of the seed's damped spring (scenes/spring.json's shape: a 1×2 grid, the top vertex pinned,
// K = 100 N/m, μ = 0.5 N·s/m, m = 1 kg), released from an initial stretch under gravity.
#include <cmath>
#include <cstdio>

#include "gpu/gpu_test_support.h"

namespace cloth::test {
namespace {

constexpr double kK = 100, kMu = 0.5, kM = 1, kG = 9.81;
constexpr double kStretch0 = 0.3;  // initial stretch beyond the rest length L = 1 m [m]

// m x'' = −K x − μ x' + m g for the stretch x, from x(0) = x0, x'(0) = 0. About the
// equilibrium x_e = m g / K, y = x − x_e obeys y'' + 2γ y' + ω0² y = 0, γ = μ/2m, ω0² = K/m;
// underdamped (γ = 0.25 /s < ω0 = 10 rad/s): y = e^{−γt} (y0 cos ω_d t + (γ y0/ω_d) sin ω_d t),
// ω_d = √(ω0² − γ²), y0 = x0 − x_e; and y' = −(ω0²/ω_d) y0 e^{−γt} sin ω_d t.
struct DampedSpring {
    double gamma = kMu / (2 * kM), w0 = std::sqrt(kK / kM);
    double wd = std::sqrt(w0 * w0 - gamma * gamma);
    double xe = kM * kG / kK, y0 = kStretch0 - xe;
    double stretch(double t) const {
        return xe +
               std::exp(-gamma * t) * (y0 * std::cos(wd * t) + gamma * y0 / wd * std::sin(wd * t));
    }
    double rate(double t) const {
        return -w0 * w0 / wd * y0 * std::exp(-gamma * t) * std::sin(wd * t);
    }
};

Scene springScene(Method method, double dt) {
    char text[640];
    std::snprintf(text, sizeof text, R"({
      "name": "spring",
      "cloth": { "resolution": [1, 2], "size": [1.0, 1.0], "origin": [0, 0, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": %.17g },
      "springs": { "structural": %.17g },
      "damping": %.17g,
      "gravity": [0, -9.81, 0],
      "pins": [[0, 0]],
      "integrator": { "method": "%s", "dt": %.17g, "tolerance": 1e-7 }
    })",
                  kM, kK, kMu, methodName(method), dt);
    return parseScene(text, "spring (test)");
}

// Error of the state at time T: stretch, and velocity over ω0 so both are lengths [m]. One
// number, not the position alone, which an oscillating error can cross 0 with.
double errorAt(Method method, double dt, double T) {
    const Scene scene = springScene(method, dt);
    std::unique_ptr<Solver> solver = makeGpuSolver(scene);
    SimState s = solver->read();
    s.positions[1].y = -(1 + kStretch0);
    solver->write(s);
    const long steps = std::lround(T / dt);
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << methodName(method) << " dt " << dt << ": " << r.reason;
    s = solver->read();
    const DampedSpring exact;
    const double ex = (-s.positions[1].y - 1) - exact.stretch(T);
    const double ev = (-s.velocities[1].y - exact.rate(T)) / exact.w0;
    return std::sqrt(ex * ex + ev * ev);
}

// In float, the state's rounding error after the ~10³ steps here is about 1e-6 m (seen: RK4's
// error stops falling at ~1e-6 below Δt = 0.0125). Every error an order is read from stays at
// least this many times above that floor.
constexpr double kFloatFloor = 1e-6;
constexpr double kAboveFloor = 20;

struct OrderCase {
    Method method;
    double dt;     // the largest of Δt, Δt/2, Δt/4 [s]
    double order;  // expected
};
void PrintTo(const OrderCase& c, std::ostream* os) {
    *os << methodName(c.method);
}

class GpuConvergence : public GpuTest, public ::testing::WithParamInterface<OrderCase> {};

// log2 of the error ratio from Δt to Δt/2, twice, at T = 1 s: within ±0.3 of the scheme's order.
TEST_P(GpuConvergence, OrderOnTheDampedSpring) {
    const OrderCase c = GetParam();
    const double T = 1.0;
    const double e1 = errorAt(c.method, c.dt, T), e2 = errorAt(c.method, c.dt / 2, T),
                 e4 = errorAt(c.method, c.dt / 4, T);
    const double order1 = std::log2(e1 / e2), order2 = std::log2(e2 / e4);
    std::printf("%-16s dt %g %g %g: errors %.3e %.3e %.3e, orders %.3f %.3f\n",
                methodName(c.method), c.dt, c.dt / 2, c.dt / 4, e1, e2, e4, order1, order2);
    EXPECT_NEAR(order1, c.order, 0.3);
    EXPECT_NEAR(order2, c.order, 0.3);
    EXPECT_GT(e4, kAboveFloor * kFloatFloor) << "Δt too small: float rounding, not truncation";
}

// Δt per scheme: small enough to be in the asymptotic range (ω0 Δt ≤ 0.25 for the Euler
// schemes, whose first-order error is large), large enough that the error is truncation, not
// float rounding. Explicit Euler also needs Δt < μ/λ = 5 ms (DESIGN.md §2). RK4's error falls so
// fast that in float it needs the largest steps: ω0 Δt = 1, 0.5, 0.25 (stable below 2.78).
INSTANTIATE_TEST_SUITE_P(Methods, GpuConvergence,
                         ::testing::Values(OrderCase{Method::ExplicitEuler, 2.5e-3, 1},
                                           OrderCase{Method::SymplecticEuler, 2.5e-3, 1},
                                           OrderCase{Method::Verlet, 2e-2, 2},
                                           OrderCase{Method::Rk4, 1e-1, 4},
                                           OrderCase{Method::ImplicitEuler, 2.5e-3, 1}),
                         [](const ::testing::TestParamInfo<OrderCase>& p) {
                             return std::string(methodName(p.param.method));
                         });

}  // namespace
}  // namespace cloth::test
