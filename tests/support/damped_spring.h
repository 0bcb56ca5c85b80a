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

}  // namespace cloth
