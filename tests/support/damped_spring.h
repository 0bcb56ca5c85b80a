// The closed form of the seed's damped spring (DESIGN.md §6): a 1×2 cloth hanging along −y from
// its pinned top vertex moves only along its axis, where the spring force K (|d| − L) is exactly
// linear in the stretch x = |d| − L as long as |d| > 0:
//     m x'' = −K x − μ x' + m g.
// About the equilibrium x_e = m g / K, y = x − x_e obeys y'' + 2γ y' + ω0² y = 0 with γ = μ/2m,
// ω0² = K/m. Underdamped (γ < ω0), from y(0) = y0 and y'(0) = 0:
//     y(t) = e^{−γt} (y0 cos ω_d t + (γ y0/ω_d) sin ω_d t),  ω_d = √(ω0² − γ²),
//     y'(t) = −(ω0²/ω_d) y0 e^{−γt} sin ω_d t   (the cos terms cancel).
#pragma once

#include <cmath>

namespace cloth {

struct DampedSpring {
    double k;             // K [N/m]
    double mu;            // μ [N·s/m]
    double m;             // mass of the free vertex [kg]
    double g = 9.81;      // gravity along the spring's axis [m/s²] (0: none)
    double stretch0 = 0;  // x(0) [m]; x'(0) = 0

    double omega0() const { return std::sqrt(k / m); }
    double gamma() const { return mu / (2 * m); }
    double omegaD() const { return std::sqrt(k / m - gamma() * gamma()); }
    double equilibrium() const { return m * g / k; }

    double stretch(double t) const {
        const double y0 = stretch0 - equilibrium(), wd = omegaD(), gam = gamma();
        return equilibrium() +
               std::exp(-gam * t) * (y0 * std::cos(wd * t) + gam * y0 / wd * std::sin(wd * t));
    }
    double rate(double t) const {
        const double y0 = stretch0 - equilibrium(), wd = omegaD();
        return -(k / m) / wd * y0 * std::exp(-gamma() * t) * std::sin(wd * t);
    }
    // |(x − x_exact, (x' − x'_exact)/ω0)| at time t: both components are lengths [m].
    double error(double t, double x, double xDot) const {
        const double ex = x - stretch(t), ev = (xDot - rate(t)) / omega0();
        return std::sqrt(ex * ex + ev * ev);
    }
};

// Convergence order at a fixed time T: for each scheme (by its scene name), a step h with ω0 h
// small enough to be asymptotic and the errors far above rounding on kOrderSprings (ω0 ≈ 7.07
// rad/s: ω0 h = 0.007 for the Euler schemes, 0.07 for Verlet, 0.14 for RK4), and its order.
struct OrderCase {
    const char* method;
    double h;      // [s]
    double order;  // the scheme's order of accuracy
};
inline constexpr OrderCase kOrderCases[] = {
    {"explicit_euler", 1e-3, 1}, {"symplectic_euler", 1e-3, 1},
    {"verlet", 1e-2, 2},         {"rk4", 2e-2, 4},
    {"implicit_euler", 1e-3, 1},
};
// Hanging under gravity from rest, and released from a stretch without gravity.
inline const DampedSpring kOrderSprings[] = {{100, 0.5, 2, 9.81, 0}, {100, 0.5, 2, 0, 0.2}};
inline constexpr double kOrderTime = 1.3;  // T [s]

// The errors e(h), e(h/2), e(h/4) and the observed orders log2(e(h)/e(h/2)), log2(e(h/2)/e(h/4)).
struct ObservedOrders {
    double e1, e2, e4, o1, o2;
};
template <typename Error>
ObservedOrders observedOrders(double h, const Error& error) {
    ObservedOrders r{error(h), error(h / 2), error(h / 4), 0, 0};
    r.o1 = std::log2(r.e1 / r.e2);
    r.o2 = std::log2(r.e2 / r.e4);
    return r;
}

}  // namespace cloth
