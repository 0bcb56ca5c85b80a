// Convergence order of every integrator on the GPU (docs/integrators.md) against the closed form
// of the seed's damped spring (tests/support/damped_spring.h; scenes/spring.json's shape: a 1×2
// grid, the top vertex pinned, K = 100 N/m, μ = 0.5 N·s/m, m = 1 kg), released from an initial
// stretch under gravity.
#include <cmath>
#include <cstdio>

#include "gpu/gpu_test_support.h"
#include "support/integrator_scenes.h"

namespace cloth::test {
namespace {

// Underdamped: γ = 0.25 /s, ω0 = 10 rad/s; released 0.3 m stretched (x_e = 0.0981 m).
const DampedSpring kSpring{100, 0.5, 1, 9.81, 0.3};

// Error of the state at time T (DampedSpring::error: stretch, and rate over ω0) [m]. One
// number, not the position alone, which an oscillating error can cross 0 with. The CG runs to
// 1e-6: float's limit, far below the truncation errors measured.
double errorAt(Method method, double dt, double T) {
    std::unique_ptr<Solver> solver = makeGpuSolver(springScene(kSpring, method, dt, 1e-6));
    solver->write(springState(kSpring.stretch0, 0));
    const long steps = std::lround(T / dt);
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << methodName(method) << " dt " << dt << ": " << r.reason;
    const SimState s = solver->read();
    return kSpring.error(T, -s.positions[1].y - 1, -s.velocities[1].y);
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
