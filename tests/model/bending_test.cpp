// The bending energy of model/bending.h: zero for every affine map of the sheet, its force the
// exact negative gradient of its energy, and its small-deflection statics those of a plate: a
// cantilever strip clamped by two pinned columns sags under its own weight by δ = ρ g L⁴ / (8B),
// converging at first order as the grid refines.
#include "model/bending.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "model/scene.h"
#include "support/draws.h"

namespace cloth {
namespace {

using V = Vec3<double>;

Grid grid(int nu, int nv, double sizeU, double sizeV) {
    Scene s;
    s.cloth.nu = nu;
    s.cloth.nv = nv;
    s.cloth.size = {sizeU, sizeV};
    s.cloth.origin = {0.2, 1, -0.3};
    return s.grid();
}

TEST(Bending, AnAffineMapOfTheSheetCostsNothing) {
    const Grid g = grid(7, 5, 1.2, 0.7);
    const BendingWeights w = bendingWeights(g, 3e-5);
    const glm::dmat3 maps[] = {glm::dmat3(1.0),
                               glm::dmat3(0, 1, 0, -1, 0, 0, 0, 0, 1),            // a quarter turn
                               glm::dmat3(1.3, 0.2, 0, 0.1, 0.8, 0.4, 0, 0, 1)};  // stretch, shear
    for (const glm::dmat3& a : maps) {
        auto x = [&](int i, int j) { return a * g.restPosition(i, j) + V(0.5, -2, 1); };
        EXPECT_NEAR(bendingEnergy(w, x), 0, 1e-20);
        for (int j = 0; j < g.nv; ++j)
            for (int i = 0; i < g.nu; ++i)
                EXPECT_LT(glm::length(bendingForce<double>(w, i, j, x)), 1e-9) << i << ", " << j;
    }
}

// F = −∂E/∂x, checked by central differences of the energy (exact for a quadratic, up to
// rounding) on a randomly crumpled 7 × 5 sheet with du ≠ dv: every vertex, every axis.
TEST(Bending, TheForceIsMinusTheGradientOfTheEnergy) {
    const Grid g = grid(7, 5, 1.2, 0.7);
    const BendingWeights w = bendingWeights(g, 3e-5);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(-0.05, 0.05);
    std::vector<V> p;
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i)
            p.push_back(g.restPosition(i, j) + V(test::drawVec3(noise, rng)));
    auto at = [&](int i, int j) { return p[std::size_t(j * g.nu + i)]; };
    const double h = 1e-4;
    double worst = 0, scale = 0;
    for (int k = 0; k < g.count(); ++k) {
        const V f = bendingForce<double>(w, k % g.nu, k / g.nu, at);
        for (int axis = 0; axis < 3; ++axis) {
            const double keep = p[std::size_t(k)][axis];
            p[std::size_t(k)][axis] = keep + h;
            const double up = bendingEnergy(w, at);
            p[std::size_t(k)][axis] = keep - h;
            const double down = bendingEnergy(w, at);
            p[std::size_t(k)][axis] = keep;
            worst = std::max(worst, std::abs(f[axis] + (up - down) / (2 * h)));
            scale = std::max(scale, std::abs(f[axis]));
        }
    }
    EXPECT_LT(worst, 1e-8 * scale) << "largest force " << scale;
}

// The small-deflection cantilever: a strip of n cells along u, clamped by pinning its first two
// columns, loaded by the weight of its lumped masses. At rest the membrane springs have no
// transverse stiffness, so the deflection y solves W y = −m g on the free vertices, W the
// bending Hessian (solved here by conjugate gradients to 1e-12). Beam theory for a uniform load
// q = ρ g per unit area on a clamped plate strip of free length L (cylindrical bending: ν plays
// no part for ν = 0): δ_tip = q L⁴ / (8B).
double cantileverTipRatio(int cells, const BendingWeights** keep = nullptr) {
    const double length = 0.5, width = 0.1, rho = 0.15, g0 = 9.81, bend = 2e-5;
    const int nu = cells + 1, nv = 3;
    const Grid g = grid(nu, nv, length, width);
    static BendingWeights w;
    w = bendingWeights(g, bend);
    if (keep) *keep = &w;
    const auto n = std::size_t(g.count());
    auto free = [&](std::size_t k) { return k % std::size_t(nu) >= 2; };
    // (W y)_k for a field y of vertical displacements: −bendingForce applied to (0, y, 0).
    auto apply = [&](const std::vector<double>& y) {
        std::vector<double> out(n, 0.0);
        auto at = [&](int i, int j) { return V(0, y[std::size_t(j * nu + i)], 0); };
        for (std::size_t k = 0; k < n; ++k)
            if (free(k)) out[k] = -bendingForce<double>(w, int(k % nu), int(k / nu), at).y;
        return out;
    };
    std::vector<double> b(n, 0.0), y(n, 0.0);
    for (std::size_t k = 0; k < n; ++k)
        if (free(k))
            b[k] = -rho * g.du * BendingWeights::share(int(k % nu), nu) * g.dv *
                   BendingWeights::share(int(k / nu), nv) * g0;
    std::vector<double> r = b, d = b;
    auto dot = [](const std::vector<double>& a, const std::vector<double>& c) {
        double s = 0;
        for (std::size_t k = 0; k < a.size(); ++k) s += a[k] * c[k];
        return s;
    };
    double rr = dot(r, r);
    const double bb = rr;
    for (int it = 0; it < 20 * int(n) && rr > 1e-24 * bb; ++it) {
        const std::vector<double> ad = apply(d);
        const double alpha = rr / dot(d, ad);
        for (std::size_t k = 0; k < n; ++k) {
            y[k] += alpha * d[k];
            r[k] -= alpha * ad[k];
        }
        const double next = dot(r, r);
        for (std::size_t k = 0; k < n; ++k) d[k] = r[k] + (next / rr) * d[k];
        rr = next;
    }
    const double freeLength = length - g.du;  // from the second pinned column to the tip
    const double closedForm = rho * g0 * std::pow(freeLength, 4) / (8 * bend);
    double tip = 0;
    for (int j = 0; j < nv; ++j) tip += -y[std::size_t(j * nu + nu - 1)] / nv;
    return tip / closedForm;
}

TEST(Bending, ACantileverSagsByTheBeamValueConvergingAtFirstOrder) {
    double previousError = 0;
    for (int cells : {8, 16, 32, 64, 128}) {
        const double error = cantileverTipRatio(cells) - 1;
        std::printf("cantilever, %3d cells: tip sag %+.2f%% off rho g L^4 / 8B\n", cells,
                    100 * error);
        if (cells >= 32) {
            EXPECT_LT(std::abs(error), 0.10) << cells << " cells";
        }
        if (previousError != 0) {
            // First order: each doubling halves the error (1.7× at least, allowing the
            // higher-order terms at the coarsest grid).
            EXPECT_GT(std::abs(previousError) / std::abs(error), 1.7) << cells << " cells";
        }
        previousError = error;
    }
}

}  // namespace
}  // namespace cloth
