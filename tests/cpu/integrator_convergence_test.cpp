// The CPU backend's five integrators (docs/integrators.md) against the closed form of the seed's
// damped spring (tests/support/damped_spring.h): the error at a fixed time shrinks as h^p with
// each scheme's order p — 1 for the Euler schemes, explicit, symplectic and implicit; 2 for
// Verlet with its trapezoidal damping; 4 for RK4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "cpu/cpu_backend.h"
#include "solver/solver.h"
#include "support/integrator_scenes.h"

namespace cloth {
namespace {

// Error at time T, in double on one thread, from the spring's rest (g ≠ 0) or from a stretch.
double springError(const DampedSpring& s, Method method, double h, double T) {
    const long steps = std::lround(T / h);
    std::unique_ptr<Solver> solver =
        makeCpuSolver(springScene(s, method, h), {Precision::Double, 1});
    if (s.stretch0 != 0) solver->write(springState(s.stretch0, 0));
    const StepResult r = solver->step(steps);
    EXPECT_EQ(r.stepsTaken, steps) << methodName(method) << ": " << r.reason;
    const SimState st = solver->read();
    EXPECT_EQ(st.positions[1].x, 0);
    EXPECT_EQ(st.positions[1].z, 0);
    return s.error(double(steps) * h, -st.positions[1].y - 1, -st.velocities[1].y);
}

// Each scheme's order within ±0.3 (tests/support/damped_spring.h has the cases), and the error
// small in absolute terms too.
TEST(IntegratorConvergence, CpuDampedSpringConvergesAtEachSchemesOrder) {
    for (const DampedSpring& s : kOrderSprings) {
        for (const OrderCase& c : kOrderCases) {
            const Method method = *methodFromName(c.method);
            const ObservedOrders r = observedOrders(
                c.h, [&](double h) { return springError(s, method, h, kOrderTime); });
            std::printf("cpu %-16s g = %4.2f: errors %.3e %.3e %.3e, orders %.3f %.3f\n", c.method,
                        s.g, r.e1, r.e2, r.e4, r.o1, r.o2);
            EXPECT_NEAR(r.o1, c.order, 0.3) << c.method << ", g = " << s.g;
            EXPECT_NEAR(r.o2, c.order, 0.3) << c.method << ", g = " << s.g;
            // Below 5 % of the oscillation's amplitude.
            EXPECT_LT(r.e1, 0.05 * std::fabs(s.stretch0 - s.equilibrium())) << c.method;
        }
    }
}

}  // namespace
}  // namespace cloth
