// The CPU backend's five integrators (docs/integrators.md) against the closed form of the seed's
// damped spring (tests/support/damped_spring.h): the error at a fixed time shrinks as h^p with
// each scheme's order p — 1 for the Euler schemes, explicit, symplectic and implicit; 2 for
// Verlet with its trapezoidal damping; 4 for RK4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "core/solver.h"
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

struct OrderCase {
    Method method;
    double h;      // [s]: ω0 h small enough to be asymptotic, errors far above rounding
    double order;  // the scheme's order of accuracy
};
// ω0 ≈ 7.07 rad/s: ω0 h = 0.007 for the Euler schemes, 0.07 for Verlet, 0.14 for RK4.
constexpr OrderCase kOrderCases[] = {
    {Method::ExplicitEuler, 1e-3, 1}, {Method::SymplecticEuler, 1e-3, 1}, {Method::Verlet, 1e-2, 2},
    {Method::Rk4, 2e-2, 4},           {Method::ImplicitEuler, 1e-3, 1},
};

// log2(e(h)/e(h/2)) and log2(e(h/2)/e(h/4)) are each scheme's order within ±0.3, hanging under
// gravity from rest and (through write()) released from a stretch without gravity.
TEST(IntegratorConvergence, CpuDampedSpringConvergesAtEachSchemesOrder) {
    const double T = 1.3;
    for (const DampedSpring s :
         {DampedSpring{100, 0.5, 2, 9.81, 0}, DampedSpring{100, 0.5, 2, 0, 0.2}}) {
        for (const OrderCase& c : kOrderCases) {
            const double e1 = springError(s, c.method, c.h, T);
            const double e2 = springError(s, c.method, c.h / 2, T);
            const double e4 = springError(s, c.method, c.h / 4, T);
            const double o1 = std::log2(e1 / e2), o2 = std::log2(e2 / e4);
            std::printf("cpu %-16s g = %4.2f: errors %.3e %.3e %.3e, orders %.3f %.3f\n",
                        methodName(c.method), s.g, e1, e2, e4, o1, o2);
            EXPECT_NEAR(o1, c.order, 0.3) << methodName(c.method) << ", g = " << s.g;
            EXPECT_NEAR(o2, c.order, 0.3) << methodName(c.method) << ", g = " << s.g;
            // Small in absolute terms too: below 5 % of the oscillation's amplitude.
            EXPECT_LT(e1, 0.05 * std::fabs(s.stretch0 - s.equilibrium())) << methodName(c.method);
        }
    }
}

}  // namespace
}  // namespace cloth
